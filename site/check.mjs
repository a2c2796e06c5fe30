// site/check.mjs — the course site in a real browser: Debian's Chromium, headless, driven by
// playwright-core (CTest site_browser, label common).
//
//   node site/check.mjs [--build] --out DIR --shots DIR
//
// --build first builds the site into DIR (site/build.mjs). Then every page of DIR (each *.html) is
// opened twice, from file:// and from `python3 -m http.server` on a free port, and the test fails
// when, on any page:
//   - the browser logs a console error or an uncaught exception, or a request fails (a missing
//     file, an HTTP status ≥ 400) — the site must need nothing but its own files;
//   - the navigation bar is not lab 1 … lab N, diffs, gallery, performance;
//   - an <a href> or <img src> inside the site points to a file that is not there, to an anchor the
//     target page does not have, or an image does not decode;
//   - a lesson diff page (diff-A-B.html) does not show the manifest's files (docs/diffs/lessons.md,
//     parsed here) in the manifest's order, each with its reading guide, as a side-by-side diff
//     drawn by diff2html with syntax colouring (highlight.js spans);
//   - text outside code still looks like `$…$` math, KaTeX reported an error, or a page whose
//     Markdown has math shows no KaTeX element.
// Also: every README and doc of the repository has a page. A full-page screenshot of each page
// (file://) goes to the shots folder. LAB_CHROMIUM=/path picks another Chromium (default /usr/bin/chromium).
// Exit codes: 0 pass, 1 fail, 77 skipped (CTest SKIP_RETURN_CODE) when site/node_modules or
// Chromium is missing or Chromium cannot start here — always with one line saying why.
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
if (args.includes('--build')) {
  const built = spawnSync(process.execPath, [path.join(siteDir, 'build.mjs'), '--out', out], { stdio: 'inherit' });
  if (built.status !== 0) { console.log('site_browser: FAILED: the site did not build'); process.exit(1); }
}
const { chromium } = await import('playwright-core');

// ---------------------------------------------------------------- what the site should contain
const pagesJson = JSON.parse(fs.readFileSync(path.join(out, 'pages.json'), 'utf8'));
const htmlFiles = (dir) => fs.readdirSync(dir, { withFileTypes: true }).flatMap((e) =>
  e.isDirectory() ? htmlFiles(path.join(dir, e.name)) : e.name.endsWith('.html') ? [path.join(dir, e.name)] : []);
const pages = htmlFiles(out).map((f) => path.relative(out, f).split(path.sep).join('/')).sort();
const labs = fs.readdirSync(root).filter((d) => /^lab\d+_\w+$/.test(d) && fs.existsSync(path.join(root, d, 'CMakeLists.txt')))
  .sort((a, b) => parseInt(a.slice(3), 10) - parseInt(b.slice(3), 10));
const expectedNav = ['Vulkan labs', ...labs.map((l) => `lab ${parseInt(l.slice(3), 10)}`), 'diffs', 'gallery', 'performance'];

// The manifest: "## <lab>", then "N. `path` [← `from`] — what it teaches" per file.
function manifest(lab) {
  let inLab = false;
  const entries = [];
  for (const line of fs.readFileSync(path.join(root, 'docs/diffs/lessons.md'), 'utf8').split('\n')) {
    if (/^## /.test(line)) inLab = line.slice(3).trim() === lab;
    const m = inLab && /^\d+\. `([^`]+)`.*? — (.*)$/.exec(line);
    if (m) entries.push({ path: m[1], guide: m[2].replace(/`/g, '') });
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
const server = spawn('python3', ['-u', '-m', 'http.server', '--bind', '127.0.0.1', '--directory', out, '0'], { stdio: ['ignore', 'pipe', 'pipe'] });
process.on('exit', () => server.kill());  // also when a step below throws
const port = await new Promise((resolve, reject) => {
  server.stdout.on('data', (chunk) => { const m = /port (\d+)/.exec(String(chunk)); if (m) resolve(Number(m[1])); });
  server.on('exit', (code) => reject(new Error(`python3 -m http.server exited (${code})`)));
  setTimeout(() => reject(new Error('python3 -m http.server did not start in 20 s')), 20000);
});
const bases = { file: pathToFileURL(out + '/').href, http: `http://127.0.0.1:${port}/` };

const problems = [];
const seen = new Map();  // page → what the DOM showed (file://)
fs.rmSync(shots, { recursive: true, force: true });
fs.mkdirSync(shots, { recursive: true });

for (const [kind, base] of Object.entries(bases)) {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  for (const name of pages) {
    const page = await context.newPage();
    const fail = (what) => problems.push(`${name} (${kind}): ${what}`);
    page.on('console', (m) => { if (m.type() === 'error') fail(`console error: ${m.text()}`); });
    page.on('pageerror', (e) => fail(`uncaught exception: ${e.message}`));
    page.on('requestfailed', (r) => fail(`request failed: ${r.url()} (${r.failure()?.errorText})`));
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
        nav: [...document.querySelectorAll('nav.site-nav a')].map((a) => a.textContent.trim()),
        links: [...document.querySelectorAll('a[href]')].map((a) => ({ raw: a.getAttribute('href'), url: a.href })),
        images: [...document.images].map((i) => ({ raw: i.getAttribute('src'), url: i.src, ok: i.complete && i.naturalWidth > 0 })),
        ids: [...document.querySelectorAll('[id]')].map((e) => e.id),
        rawMath: [...prose.values()].map((t) => t.match(/\$\$[^$]+\$\$|\$[^$\s][^$]*\$/)?.[0]).find(Boolean) ?? null,
        katex: document.querySelectorAll('.katex').length,
        katexErrors: document.querySelectorAll('.katex-error').length,
        lessonFiles: [...document.querySelectorAll('section.lesson-file')].map((s) => ({
          path: s.dataset.path,
          guide: s.querySelector('.guide')?.textContent.trim() ?? '',
          shown: [...s.querySelectorAll('.d2h-file-name')].map((e) => e.textContent.trim()),
          sides: s.querySelectorAll('.d2h-file-side-diff').length,
          lines: s.querySelectorAll('.d2h-code-side-line').length,
          coloured: s.querySelectorAll('.d2h-code-line-ctn.hljs').length,
          tokens: s.querySelectorAll('[class^="hljs-"]').length,
        })),
      };
    });
    if (kind === 'file') {
      seen.set(name, dom);
      await page.screenshot({ path: path.join(shots, name.replace(/\//g, '__').replace(/\.html$/, '.png')), fullPage: true });
    }
    if (dom.nav.join('|') !== expectedNav.join('|')) fail(`navigation bar is "${dom.nav.join(' | ')}", not "${expectedNav.join(' | ')}"`);
    if (dom.rawMath) fail(`raw math left in the text: ${dom.rawMath}`);
    if (dom.katexErrors) fail(`${dom.katexErrors} KaTeX error(s)`);
    for (const img of dom.images) if (!img.ok) fail(`image ${img.raw} did not load`);
    await page.close();
  }
  await context.close();
}

// ---------------------------------------------------------------- links, math, the diff pages (file:// DOM)
for (const [name, dom] of seen) {
  const fail = (what) => problems.push(`${name}: ${what}`);
  for (const { raw, url } of [...dom.links, ...dom.images.map((i) => ({ raw: i.raw, url: i.url }))]) {
    if (!url.startsWith('file:')) {
      if (!/^(https?|mailto):/.test(url)) fail(`link ${raw}: unexpected scheme`);
      continue;  // a link out of the site: the reader's choice, nothing loads by itself
    }
    const [file, hash] = decodeURIComponent(url).split('#');
    let target = path.relative(out, fileURLToPath(file)).split(path.sep).join('/');
    if (target.startsWith('..')) { fail(`link ${raw} leaves the site`); continue; }
    if (target === '' || fs.existsSync(path.join(out, target)) && fs.statSync(path.join(out, target)).isDirectory()) target = path.posix.join(target, 'index.html');
    if (!fs.existsSync(path.join(out, target))) { fail(`link ${raw} → ${target}: no such file`); continue; }
    if (hash && target.endsWith('.html') && !(seen.get(target)?.ids ?? []).includes(hash)) fail(`link ${raw}: ${target} has no #${hash}`);
  }
}
// Every README and doc is a page: the top README, each lab's, each gallery's, docs/*.md.
const markdownSources = ['README.md', ...labs.map((l) => `${l}/README.md`),
  ...fs.readdirSync(path.join(root, 'docs')).filter((f) => f.endsWith('.md')).map((f) => `docs/${f}`),
  ...labs.map((l) => `docs/images/${l}/README.md`).filter((f) => fs.existsSync(path.join(root, f)))];
for (const source of markdownSources) {
  if (!pagesJson.some((p) => p.source === source)) problems.push(`${source} has no page in the site`);
}
for (const p of pagesJson) {
  if (!seen.has(p.page)) problems.push(`pages.json lists ${p.page}, which was not found`);
  if (p.source?.endsWith('.md') && markdownHasMath(p.source) && !seen.get(p.page)?.katex) {
    problems.push(`${p.page}: ${p.source} has math, but the page shows no KaTeX`);
  }
}
let diffPages = 0;
for (const [name, dom] of seen) {
  const m = /^diff-(lab\d+_\w+)-(lab\d+_\w+)\.html$/.exec(name);
  if (!m) continue;
  diffPages++;
  const fail = (what) => problems.push(`${name}: ${what}`);
  const want = manifest(m[2]);
  const got = dom.lessonFiles;
  if (want.length === 0) fail(`docs/diffs/lessons.md has no section for ${m[2]}`);
  if (got.map((f) => f.path).join('\n') !== want.map((e) => e.path).join('\n')) {
    fail(`files are not the manifest's, in its order:\n    page:     ${got.map((f) => f.path).join(', ')}\n    manifest: ${want.map((e) => e.path).join(', ')}`);
  }
  got.forEach((f, i) => {
    // diff2html's own file header, "{lab1 → lab2}/x.h" or "a → b" for a changed path: the new side.
    const shown = (f.shown[0] ?? '').replace(/\{[^{}]* → ([^{}]*)\}/g, '$1').replace(/^.* → /, '');
    if (f.shown.length !== 1 || shown !== f.path) fail(`file ${i + 1}: diff2html shows "${f.shown.join(', ')}", not ${f.path}`);
    if (want[i] && f.guide !== want[i].guide) fail(`file ${i + 1} (${f.path}): reading guide "${f.guide}" is not the manifest's "${want[i].guide}"`);
    if (f.sides !== 2 || f.lines === 0) fail(`file ${i + 1} (${f.path}): not a side-by-side diff (${f.sides} sides, ${f.lines} lines)`);
    if (f.coloured === 0 || f.tokens === 0) fail(`file ${i + 1} (${f.path}): no syntax colouring (${f.coloured} highlighted lines, ${f.tokens} tokens)`);
  });
}
if (diffPages === 0) problems.push('no lesson diff page (diff-A-B.html) in the site');

const version = browser.version();
await browser.close();
server.kill();
const mathPages = [...seen.values()].filter((d) => d.katex > 0).length;
console.log(`site_browser: ${pages.length} pages, each from file:// and http://127.0.0.1:${port}/ in Chromium ` +
  `${version}; ${diffPages} diff pages, ${mathPages} pages with KaTeX; screenshots in ${shots}`);
if (problems.length) {
  console.log(`site_browser: FAILED, ${problems.length} problem(s):`);
  for (const p of problems) console.log(`  ${p}`);
  process.exit(1);
}
console.log('site_browser: passed');
process.exit(0);
