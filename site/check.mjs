// site/check.mjs — the course site in a real browser: Debian's Chromium, headless, driven by
// playwright-core (CTest site_browser, label common).
//
//   node site/check.mjs [--build] --out DIR --shots DIR [--student N]
//
// --build first builds the instructors' edition into DIR and the student edition of every lab N
// into DIR-student-labN (site/build.mjs; --student N: only that edition, in DIR). Then every page of each edition (each *.html) is opened
// from file:// (the instructors' edition's pages other than src/ also from `python3 -m http.server`
// on a free port), and the test fails when, on any page:
//   - the browser logs a console error or an uncaught exception, or a request fails (a missing
//     file, an HTTP status ≥ 400) — the site must need nothing but its own files;
//   - the page asks for anything from another origin (not file://, not the local server): every
//     such request is aborted in the browser and counted, whether or not a network is there;
//   - the navigation bar is not the edition's: lab 1 … lab N, diffs, docs, gallery, performance;
//   - an <a href> or <img src> inside the site points to a file that is not there, to an anchor the
//     target page does not have, or an image does not decode;
//   - the page is wider than a 390 px screen (the document scrolls sideways);
//   - a lesson diff page (diff-A-B.html) does not show the manifest's files (docs/diffs/lessons.md,
//     parsed here) in the manifest's order, each with its reading guide, a changed file side by side
//     and a new one whole in one column, drawn by diff2html with syntax colouring (highlight.js spans);
//   - text outside code still looks like `$…$` math, KaTeX reported an error, or a page whose
//     Markdown has math shows no KaTeX element.
// And for each edition: index.html's "next" leads to lab 1, and the previous/next links of the lab
// pages chain lab 1 → lab N and back; every file of every lab folder and its shader folder has a
// page (src/<path>.html) that the lab's page links. The instructors' edition: every README and doc
// of the repository has a page. A student edition of lab N: no page, link or picture names a later
// lab (nor does its text outside code), and docs/solutions.md has no page. A full-page screenshot of each instructors' page other
// than src/ (file://) goes to the shots folder. LAB_CHROMIUM=/path picks another Chromium (default
// /usr/bin/chromium). Exit codes: 0 pass, 1 fail, 77 skipped (CTest SKIP_RETURN_CODE) when
// site/node_modules or Chromium is missing or Chromium cannot start here — always with one line
// saying why.
import fs from 'node:fs';
import path from 'node:path';
import { spawn, spawnSync } from 'node:child_process';
import { fileURLToPath, pathToFileURL } from 'node:url';

const siteDir = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(siteDir, '..');
const args = process.argv.slice(2);
const opt = (name, fallback) => (args.includes(name) ? path.resolve(args[args.indexOf(name) + 1]) : fallback);
const out = opt('--out', path.join(root, 'build/site'));
const shots = opt('--shots', path.join(root, 'build/test_output/site'));
const chromiumPath = process.env.LAB_CHROMIUM ?? '/usr/bin/chromium';
const skip = (why) => { console.log(`site_browser: SKIPPED: ${why}`); process.exit(77); };

if (!fs.existsSync(path.join(siteDir, 'node_modules/playwright-core'))) {
  skip('site/node_modules is missing (scripts/setup.sh runs `npm ci` in site/; it needs the npm registry)');
}
if (!fs.existsSync(chromiumPath)) skip(`${chromiumPath} is missing (scripts/setup.sh installs Debian's chromium)`);
const labs = fs.readdirSync(root).filter((d) => /^lab\d+_\w+$/.test(d) && fs.existsSync(path.join(root, d, 'CMakeLists.txt')))
  .sort((a, b) => parseInt(a.slice(3), 10) - parseInt(b.slice(3), 10));
const labNumber = (lab) => parseInt(lab.slice(3), 10);
// The editions: the instructors' in DIR, each student edition beside it.
// --student N: only the student edition of lab N (in DIR itself), e.g. to try the checks on a broken copy.
const only = args.includes('--student') ? Number(args[args.indexOf('--student') + 1]) : null;
const editions = only ? [{ dir: out, student: only }] : [{ dir: out, student: null },
  ...labs.map((lab) => ({ dir: `${out}-student-lab${labNumber(lab)}`, student: labNumber(lab) }))];
if (args.includes('--build')) {
  for (const e of editions) {
    const built = spawnSync(process.execPath, [path.join(siteDir, 'build.mjs'), '--out', e.dir, ...(e.student ? ['--student', String(e.student)] : [])], { stdio: 'inherit' });
    if (built.status !== 0) { console.log(`site_browser: FAILED: the site did not build (${e.dir})`); process.exit(1); }
  }
}
for (const e of editions) {
  if (!fs.existsSync(path.join(e.dir, 'pages.json'))) { console.log(`site_browser: FAILED: ${e.dir} holds no built site (run with --build)`); process.exit(1); }
}
const { chromium } = await import('playwright-core');

// ---------------------------------------------------------------- what a site should contain
const htmlFiles = (dir) => fs.readdirSync(dir, { withFileTypes: true }).flatMap((e) =>
  e.isDirectory() ? htmlFiles(path.join(dir, e.name)) : e.name.endsWith('.html') ? [path.join(dir, e.name)] : []);
const filesUnder = (dir) => (fs.existsSync(path.join(root, dir)) ? fs.readdirSync(path.join(root, dir), { withFileTypes: true }).flatMap((e) =>
  e.isDirectory() ? filesUnder(`${dir}/${e.name}`) : [`${dir}/${e.name}`]) : []);

// The manifest: "## <lab>", then "N. `path` [← `from`] — what it teaches" per file.
function manifest(lab) {
  let inLab = false;
  const entries = [];
  for (const line of fs.readFileSync(path.join(root, 'docs/diffs/lessons.md'), 'utf8').split('\n')) {
    if (/^## /.test(line)) inLab = line.slice(3).trim() === lab;
    const m = inLab && /^\d+\. `([^`]+)`(?: ← `([^`]+)`)? — (.*)$/.exec(line);
    if (m) entries.push({ path: m[1], from: m[2], guide: m[3].replace(/`/g, '') });
  }
  return entries;
}
// Math in Markdown: $…$ or $$…$$ outside code (fences, indented blocks, inline code).
function markdownHasMath(file) {
  const text = fs.readFileSync(path.join(root, file), 'utf8')
    .replace(/^(```|~~~)[\s\S]*?^\1/gm, '').replace(/^( {4}|\t).*$/gm, '').replace(/`[^`\n]*`/g, '');
  return /\$\$[\s\S]+?\$\$|\$[^$\s][^$\n]*\$/.test(text);
}

// ---------------------------------------------------------------- the browser
let browser;
try {
  browser = await chromium.launch({ executablePath: chromiumPath, args: ['--no-sandbox'] });
} catch (error) {
  skip(`Chromium (${chromiumPath}) cannot start here: ${String(error.message).split('\n')[0]}`);
}
const servers = [];
process.on('exit', () => servers.forEach((s) => s.kill()));  // also when a step below throws
async function serve(dir) {
  const server = spawn('python3', ['-u', '-m', 'http.server', '--bind', '127.0.0.1', '--directory', dir, '0'], { stdio: ['ignore', 'pipe', 'pipe'] });
  servers.push(server);
  const port = await new Promise((resolve, reject) => {
    server.stdout.on('data', (chunk) => { const m = /port (\d+)/.exec(String(chunk)); if (m) resolve(Number(m[1])); });
    server.on('exit', (code) => reject(new Error(`python3 -m http.server exited (${code})`)));
    setTimeout(() => reject(new Error('python3 -m http.server did not start in 20 s')), 20000);
  });
  return `http://127.0.0.1:${port}/`;
}

const problems = [];
fs.rmSync(shots, { recursive: true, force: true });
fs.mkdirSync(shots, { recursive: true });
const summary = [];

// Opens every page of one edition; returns page → what the DOM showed (file://).
async function visit(edition) {
  const { dir, student } = edition;
  const tag = student ? `student lab ${student}` : 'instructors';
  const pages = htmlFiles(dir).map((f) => path.relative(dir, f).split(path.sep).join('/')).sort();
  const bases = { file: pathToFileURL(dir + '/').href };
  if (!student) bases.http = await serve(dir);
  const seen = new Map();
  const editionLabs = labs.filter((l) => !student || labNumber(l) <= student);
  // The diffs between the edition's labs; a student edition leaves out the one into lab N (its
  // reading guides state lab N's answers: site/student.mjs).
  const expectedDiffs = Math.max(editionLabs.length - (student ? 2 : 1), 0);
  const expectedNav = ['Vulkan labs', ...editionLabs.map((l) => `lab ${labNumber(l)}`), ...(expectedDiffs > 0 ? ['diffs'] : []),
    'docs', 'gallery', ...(pages.includes('performance.html') ? ['performance'] : [])];
  for (const [kind, base] of Object.entries(bases)) {
    const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
    // Nothing may come from another origin: every such request is aborted here and counted.
    let current = null;
    await context.route('**/*', (route) => {
      const url = route.request().url();
      if (url.startsWith(base) || url.startsWith('data:')) return route.continue();
      problems.push(`${current} (${tag}, ${kind}): asked another origin for ${url} (blocked)`);
      return route.abort('blockedbyclient');
    });
    for (const name of pages) {
      if (kind === 'http' && name.startsWith('src/')) continue;  // one template, all of them seen from file://
      // A student edition: of the source pages only lab N's (the earlier labs' are the instructors' files).
      if (student && name.startsWith('src/') && !name.includes(`lab${student}_`)) { seen.set(name, null); continue; }
      current = name;
      const page = await context.newPage();
      const fail = (what) => problems.push(`${name} (${tag}, ${kind}): ${what}`);
      page.on('console', (m) => { if (m.type() === 'error' && !m.text().includes('ERR_BLOCKED_BY_CLIENT')) fail(`console error: ${m.text()}`); });
      page.on('pageerror', (e) => fail(`uncaught exception: ${e.message}`));
      page.on('requestfailed', (r) => { if (!r.failure()?.errorText.startsWith('net::ERR_BLOCKED_BY_CLIENT')) fail(`request failed: ${r.url()} (${r.failure()?.errorText})`); });
      page.on('response', (r) => { if (r.status() >= 400) fail(`HTTP ${r.status()} for ${r.url()}`); });
      await page.goto(base + name, { waitUntil: 'load' });
      await page.evaluate(() => document.fonts.ready);
      const dom = await page.evaluate(() => {
        const prose = new Map();  // block element → its text outside code, diffs and KaTeX
        const walker = document.createTreeWalker(document.querySelector('main'), NodeFilter.SHOW_TEXT);
        for (let n = walker.nextNode(); n; n = walker.nextNode()) {
          if (n.parentElement.closest('code, pre, script, style, .katex, .katex-error, .lesson-diff')) continue;
          const block = n.parentElement.closest('p, li, td, th, h1, h2, h3, h4, h5, h6, dd, dt, blockquote, main');
          prose.set(block, (prose.get(block) ?? '') + n.textContent);
        }
        return {
          title: document.title,
          nav: [...document.querySelectorAll('nav.site-nav a')].map((a) => a.textContent.trim()),
          prev: document.querySelector('a[rel=prev]')?.getAttribute('href') ?? null,
          next: document.querySelector('a[rel=next]')?.getAttribute('href') ?? null,
          links: [...document.querySelectorAll('a[href]')].map((a) => ({ raw: a.getAttribute('href'), url: a.href })),
          images: [...document.images].map((i) => ({ raw: i.getAttribute('src'), url: i.src, ok: i.complete && i.naturalWidth > 0 })),
          ids: [...document.querySelectorAll('[id]')].map((e) => e.id),
          rawMath: [...prose.values()].map((t) => t.match(/\$\$[^$]+\$\$|\$[^$\s][^$]*\$/)?.[0]).find(Boolean) ?? null,
          katex: document.querySelectorAll('.katex').length,
          katexErrors: document.querySelectorAll('.katex-error').length,
          prose: [...prose.values()].join('\n'),  // the page's own words: a lab's code may name the next lab in a comment
          lessonFiles: [...document.querySelectorAll('section.lesson-file')].map((s) => ({
            path: s.dataset.path,
            guide: s.querySelector('.guide')?.textContent.trim() ?? '',
            shown: [...s.querySelectorAll('.d2h-file-name')].map((e) => e.textContent.trim()),
            sides: s.querySelectorAll('.d2h-file-side-diff').length,
            columns: s.querySelectorAll('.d2h-file-diff').length,
            lines: s.querySelectorAll('.d2h-code-side-line, .d2h-code-line').length,
            coloured: s.querySelectorAll('.d2h-code-line-ctn.hljs').length,
            tokens: s.querySelectorAll('[class^="hljs-"]').length,
          })),
        };
      });
      if (kind === 'file') {
        seen.set(name, dom);
        if (!student && !name.startsWith('src/')) {
          await page.screenshot({ path: path.join(shots, name.replace(/\//g, '__').replace(/\.html$/, '.png')), fullPage: true });
        }
        // A phone: the page may not scroll sideways (wide tables and diffs scroll in their own box).
        await page.setViewportSize({ width: 390, height: 844 });
        const width = await page.evaluate(() => document.documentElement.scrollWidth);
        if (width > 390) {
          const culprit = await page.evaluate(() => {  // the outermost too-wide element not inside a scrolling box
            const scrolls = (e) => ['auto', 'scroll', 'hidden'].includes(getComputedStyle(e).overflowX);
            const inBox = (e) => { for (let p = e.parentElement; p && p !== document.body; p = p.parentElement) if (scrolls(p)) return true; return false; };
            return [...document.body.querySelectorAll('*')].find((e) => e.getBoundingClientRect().right > 391 && !inBox(e))?.outerHTML.slice(0, 120);
          });
          fail(`${width} px wide at a 390 px width (first too wide: ${culprit})`);
        }
      }
      if (dom.nav.join('|') !== expectedNav.join('|')) fail(`navigation bar is "${dom.nav.join(' | ')}", not "${expectedNav.join(' | ')}"`);
      if (/— Vulkan labs.*— Vulkan labs|^Vulkan labs.*— Vulkan labs/.test(dom.title)) fail(`title repeats the site's name: "${dom.title}"`);
      if (dom.rawMath) fail(`raw math left in the text: ${dom.rawMath}`);
      if (dom.katexErrors) fail(`${dom.katexErrors} KaTeX error(s)`);
      for (const img of dom.images) if (!img.ok) fail(`image ${img.raw} did not load`);
      await page.close();
    }
    await context.close();
  }
  return { pages, seen, editionLabs, expectedDiffs };
}

for (const edition of editions) {
  const { dir, student } = edition;
  const tag = student ? `student lab ${student}` : 'instructors';
  const { pages, seen, editionLabs, expectedDiffs } = await visit(edition);
  const pagesJson = JSON.parse(fs.readFileSync(path.join(dir, 'pages.json'), 'utf8'));
  const fail = (name, what) => problems.push(`${name} (${tag}): ${what}`);

  // ------------------------------------------------------------ links, math, the diff pages (file:// DOM)
  for (const [name, dom] of seen) {
    if (!dom) continue;  // not opened (above)
    for (const { raw, url } of [...dom.links, ...dom.images.map((i) => ({ raw: i.raw, url: i.url }))]) {
      if (!url.startsWith('file:')) {
        if (!/^(https?|mailto):/.test(url)) fail(name, `link ${raw}: unexpected scheme`);
        continue;  // a link out of the site: the reader's choice, nothing loads by itself
      }
      const [file, hash] = decodeURIComponent(url).split('#');
      let target = path.relative(dir, fileURLToPath(file)).split(path.sep).join('/');
      if (target.startsWith('..')) { fail(name, `link ${raw} leaves the site`); continue; }
      if (target === '' || fs.existsSync(path.join(dir, target)) && fs.statSync(path.join(dir, target)).isDirectory()) target = path.posix.join(target, 'index.html');
      if (!fs.existsSync(path.join(dir, target))) { fail(name, `link ${raw} → ${target}: no such file`); continue; }
      if (hash && target.endsWith('.html') && seen.get(target) !== null && !(seen.get(target)?.ids ?? []).includes(hash)) fail(name, `link ${raw}: ${target} has no #${hash}`);
      if (student) {
        const later = /lab(\d+)_/.exec(target);
        if (later && Number(later[1]) > student) fail(name, `links a later lab's file: ${raw}`);
      }
    }
    if (student) {
      const later = [...dom.prose.matchAll(/\blab[ _]?(\d+)/gi)].find((m) => Number(m[1]) > student);
      if (later) fail(name, `names a later lab in its text: "${dom.prose.slice(Math.max(0, later.index - 60), later.index + 30).replace(/\s+/g, ' ')}"`);
    }
  }
  for (const p of pagesJson) {
    if (!seen.has(p.page)) fail(p.page, 'pages.json lists it, but it was not found');
    if (p.source?.endsWith('.md') && !student && markdownHasMath(p.source) && !seen.get(p.page)?.katex) {
      fail(p.page, `${p.source} has math, but the page shows no KaTeX`);
    }
  }
  if (!student) {  // every README and doc is a page: the top README, each lab's, each gallery's, docs/*.md
    const markdownSources = ['README.md', ...labs.map((l) => `${l}/README.md`),
      ...fs.readdirSync(path.join(root, 'docs')).filter((f) => f.endsWith('.md')).map((f) => `docs/${f}`),
      ...labs.map((l) => `docs/images/${l}/README.md`).filter((f) => fs.existsSync(path.join(root, f)))];
    for (const source of markdownSources) if (!pagesJson.some((p) => p.source === source)) fail(source, 'has no page in the site');
  } else if (pagesJson.some((p) => p.source === 'docs/solutions.md')) fail('solutions.html', 'docs/solutions.md has a page in a student edition');

  // ------------------------------------------------------------ previous/next: lab 1 → lab N and back
  const follow = (start, rel) => {
    const chain = [];
    for (let at = start; at && chain.length <= labs.length; ) {
      chain.push(at);
      const href = seen.get(at)?.[rel];
      at = href ? path.posix.normalize(path.posix.join(path.posix.dirname(at), href.split('#')[0])) : null;
      if (at && !/^lab\d+_\w+\.html$/.test(at)) break;
    }
    return chain;
  };
  const labPages = editionLabs.map((l) => `${l}.html`);
  const indexNext = seen.get('index.html')?.next;
  if (indexNext !== labPages[0]) fail('index.html', `its "next" link is ${indexNext}, not ${labPages[0]}`);
  const forward = follow(labPages[0], 'next');
  const backward = follow(labPages.at(-1), 'prev');
  if (forward.join(' → ') !== labPages.join(' → ')) fail(labPages[0], `"next" chains ${forward.join(' → ')}, not ${labPages.join(' → ')}`);
  if (backward.join(' → ') !== [...labPages].reverse().join(' → ')) fail(labPages.at(-1), `"previous" chains ${backward.join(' → ')}`);

  // ------------------------------------------------------------ every lab file has a page the lab links
  let labFiles = 0;
  for (const lab of editionLabs) {
    const files = [...filesUnder(lab), ...filesUnder(`shaders/${lab}`)].filter((f) => f !== `${lab}/README.md`);
    const linked = new Set((seen.get(`${lab}.html`)?.links ?? []).map((l) => l.raw.split('#')[0]));
    for (const f of files) {
      labFiles++;
      if (!seen.has(`src/${f}.html`)) fail(`${lab}.html`, `${f} has no page (src/${f}.html)`);
      else if (!linked.has(`src/${f}.html`)) fail(`${lab}.html`, `does not link ${f}'s page`);
    }
  }

  // ------------------------------------------------------------ the diff pages
  let diffPages = 0;
  for (const [name, dom] of seen) {
    if (!dom) continue;
    const m = /^diff-(lab\d+_\w+)-(lab\d+_\w+)\.html$/.exec(name);
    if (!m) continue;
    diffPages++;
    const want = manifest(m[2]);
    const got = dom.lessonFiles;
    if (want.length === 0) fail(name, `docs/diffs/lessons.md has no section for ${m[2]}`);
    if (got.map((f) => f.path).join('\n') !== want.map((e) => e.path).join('\n')) {
      fail(name, `files are not the manifest's, in its order:\n    page:     ${got.map((f) => f.path).join(', ')}\n    manifest: ${want.map((e) => e.path).join(', ')}`);
    }
    got.forEach((f, i) => {
      // diff2html's own file header, "{lab1 → lab2}/x.h" or "a → b" for a changed path: the new side.
      const shown = (f.shown[0] ?? '').replace(/\{[^{}]* → ([^{}]*)\}/g, '$1').replace(/^.* → /, '');
      if (f.shown.length !== 1 || shown !== f.path) fail(name, `file ${i + 1}: diff2html shows "${f.shown.join(', ')}", not ${f.path}`);
      if (want[i] && f.guide !== want[i].guide) fail(name, `file ${i + 1} (${f.path}): reading guide "${f.guide}" is not the manifest's "${want[i].guide}"`);
      const isNew = want[i] && !want[i].from && !fs.existsSync(path.join(root, want[i].path.replace(m[2], m[1])));
      if (isNew && (f.columns !== 1 || f.sides !== 0 || f.lines === 0)) fail(name, `file ${i + 1} (${f.path}) is new: not shown whole in one column (${f.columns} columns, ${f.sides} sides)`);
      if (!isNew && (f.sides !== 2 || f.lines === 0)) fail(name, `file ${i + 1} (${f.path}): not a side-by-side diff (${f.sides} sides, ${f.lines} lines)`);
      if (f.coloured === 0 || f.tokens === 0) fail(name, `file ${i + 1} (${f.path}): no syntax colouring (${f.coloured} highlighted lines, ${f.tokens} tokens)`);
    });
  }
  if (diffPages !== expectedDiffs) fail('diffs', `${diffPages} lesson diff pages, not ${expectedDiffs}`);
  const mathPages = [...seen.values()].filter((d) => d?.katex > 0).length;
  summary.push(`${tag}: ${pages.length} pages (${labFiles} lab files), ${diffPages} diff pages, ${mathPages} with KaTeX`);
}

const version = browser.version();
await browser.close();
servers.forEach((s) => s.kill());
console.log(`site_browser: Chromium ${version}, every page from file:// (the instructors' also over HTTP), at 1280 and 390 px; ` +
  `screenshots in ${shots}\n  ${summary.join('\n  ')}`);
if (problems.length) {
  console.log(`site_browser: FAILED, ${problems.length} problem(s):`);
  for (const p of problems.slice(0, 200)) console.log(`  ${p}`);
  if (problems.length > 200) console.log(`  … and ${problems.length - 200} more`);
  process.exit(1);
}
console.log('site_browser: passed');
process.exit(0);
