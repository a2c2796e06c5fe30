// site/check.mjs — the course site checked page by page: every page of every edition read as HTML
// (site/check_static.mjs), and the pages that need a browser opened in a real one: Debian's
// Chromium, headless, driven by playwright-core (CTest site_browser, label common).
//
//   node site/check.mjs [--build] --out DIR [--shots DIR [--full-shots]] [--student N | --instructors]
//                       [--jobs J] [--plan] [--times] [--all]
//
// --build first builds the instructors' edition into DIR and the student edition of every lab N
// into DIR-student-labN (site/build.mjs, J builds at a time, default 2; each edition is checked as
// soon as it is built, while the others build). --student N: only the student edition of lab N, in
// DIR; --instructors: only the instructors' edition, in DIR (e.g. to try the checks on a broken
// copy: tests/site_check_fails.mjs). --plan: print which pages would be opened in the browser and
// why, and stop; --times: the time each opened page took; --all: open every page, not the sample
// below (what this check did before it read the HTML itself; about twice the browser time). The
// test fails when:
//
// On EVERY page of every edition, from its HTML (no browser):
//   - the navigation bar is not the edition's: lab 1 … lab N, diffs, docs, gallery, performance;
//     the title repeats the site's name;
//   - an <a href> or <img src> inside the site points to a file that is not there, to an anchor the
//     target page does not have, or out of the site; a link has an unexpected scheme;
//   - the page makes the browser load anything (stylesheet, icon, script, picture, frame, media)
//     from another origin, or a file of the site that is not there;
//   - text outside code still looks like `$…$` math, KaTeX reported an error (.katex-error), or a
//     page whose Markdown has math shows no KaTeX element (KaTeX renders at build time);
//   - a lesson diff page (diff-A-B.html) does not hold the manifest's files (docs/diffs/lessons.md)
//     in the manifest's order, each with its reading guide, a changed file side by side and a new
//     one whole in one column (diff2html renders these tables at build time; the browser only
//     colours them);
//   - student edition of lab N: a page, link or picture names a later lab, or its text outside code
//     does (every page: the earlier labs' source pages too).
// For each edition: index.html's "next" leads to lab 1 and the lab pages' previous/next links chain
// lab 1 → lab N and back; every file of every lab folder and its shader folder has a page
// (src/<path>.html) that the lab's page links; pages.json lists only pages that are there. The
// instructors' edition: every README and doc of the repository has a page. A student edition:
// docs/solutions.md has no page. Every url() of the edition's stylesheets (KaTeX's fonts) is there.
//
// In Chromium, on the pages opened (file://; the instructors' also over `python3 -m http.server`):
//   - a console error, an uncaught exception, a failed request (a missing file, HTTP status ≥ 400),
//     a request to another origin (aborted in the browser and counted, network or not);
//   - the page is wider than a 390 px screen (the document scrolls sideways);
//   - a picture does not decode: every picture of the edition, each distinct file once, in one page;
//   - a lesson diff page: diff2html's UI did not colour each file (highlight.js spans; a student
//     edition's twin of an instructors' diff page, below: as its twin did);
//   - this file's reading of the HTML (above) differs from Chromium's DOM: the same navigation bar,
//     previous/next, links, pictures, ids, KaTeX elements, text outside code and diff sections;
//     so the static checks read the pages as the browser does, wherever a page is opened.
// Screenshots (--shots DIR): the first screen (1280 × 900) of each instructors' page other than src/
// (--full-shots: the whole page, as this check used to: 20 MB of PNG and about a minute more on 2
// cores, the lab 3 → lab 4 diff alone 10-20 s).
//
// Which pages are opened, and why the others need not be. What a browser adds to the HTML is what
// the page loads and runs and how it lays out. Every page is frame.mjs's frame (the same four
// stylesheets, the favicon data: URL, no script) around a body of one of a few kinds; a page that
// loads or runs anything else — any script (the diff pages), frame, media, <style>, event handler,
// a style attribute outside KaTeX's output — is opened, wherever it is (`active` in
// check_static.mjs). Opened:
//   - every page of each edition other than src/ (the landing page, the labs, the docs, the diffs,
//     the galleries, performance and tradeoffs: hand-written Markdown and tables, whose width and
//     math depend on their text), except a student page that is the twin of an instructors' page
//     opened: the same HTML once the navigation bar and the edition banner are taken out, and the
//     same bytes in every file it loads (e.g. the earlier labs' diff pages). It would run and lay
//     out as its twin, and the bar and banner are opened on the edition's other pages;
//   - of the source pages (src/…, ~85% of the site: one template, site/source_pages.mjs: a title
//     in <code>, which wraps anywhere, a paragraph, the code in a box that scrolls, build-time
//     colouring, no script, picture or math), in each edition one per file type (extension), the
//     one with the longest path (the widest title), preferring one whose HTML differs from the
//     instructors' page of that name (a student's stubbed file), and one folder page
//     (src/…/index.html); links, anchors and text are checked on every source page as above;
//   - over HTTP (the instructors' edition): the smallest page of each combination of file types it
//     loads (stylesheets, pictures, scripts, KaTeX's fonts) and one source page: what HTTP changes
//     is how each type is served and what a script may do on an http:// origin.
// What a page left out could still get wrong only in a browser: a load (each is checked to be there
// and same-origin, and the pictures decode), something it runs or styles beyond the frame (that
// gets it opened), or its width: a source page cannot grow wider than the screen whatever the file
// holds (the title wraps, the code scrolls in its box, the pager wraps), and a change to that
// template changes the opened source pages too. tests/site_check_fails.mjs (CTest
// site_check_can_fail) breaks pages left out and opened ones and requires this check to name each.
//
// LAB_CHROMIUM=/path picks another Chromium (default /usr/bin/chromium). Exit codes: 0 pass,
// 1 fail, 77 skipped (CTest SKIP_RETURN_CODE) when site/node_modules is missing, or Chromium is
// missing or cannot start here and the static checks passed — always with one line saying why.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import crypto from 'node:crypto';
import { spawn } from 'node:child_process';
import { fileURLToPath, pathToFileURL } from 'node:url';

const siteDir = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(siteDir, '..');
const args = process.argv.slice(2);
if (args.includes('--help') || args.includes('-h')) {  // the usage and options: this file's header, to its first blank line after them
  const header = fs.readFileSync(fileURLToPath(import.meta.url), 'utf8').split('\n');
  console.log(header.slice(4, header.findIndex((l, i) => i > 8 && l === '//')).map((l) => l.replace(/^\/\/ ?/, '')).join('\n'));
  process.exit(0);
}
const opt = (name, fallback) => (args.includes(name) ? path.resolve(args[args.indexOf(name) + 1]) : fallback);
const out = opt('--out', path.join(root, 'build/site'));
const shots = opt('--shots', null);  // no screenshots without it
const jobs = args.includes('--jobs') ? Math.max(1, Number(args[args.indexOf('--jobs') + 1]) || 1) : Math.min(2, os.availableParallelism());
const planOnly = args.includes('--plan');
const fullShots = args.includes('--full-shots');
const showTimes = args.includes('--times');
const openAll = args.includes('--all');
const chromiumPath = process.env.LAB_CHROMIUM ?? '/usr/bin/chromium';
const skip = (why) => { console.log(`site_browser: SKIPPED: ${why}`); process.exit(77); };
const started = performance.now();
const seconds = (ms) => `${(ms / 1000).toFixed(1)} s`;

if (!fs.existsSync(path.join(siteDir, 'node_modules/playwright-core')) || !fs.existsSync(path.join(siteDir, 'node_modules/entities'))) {
  skip('site/node_modules is missing (scripts/setup.sh runs `npm ci` in site/; it needs the npm registry)');
}
const { pageFacts, withoutFrame } = await import('./check_static.mjs');
const labs = fs.readdirSync(root).filter((d) => /^lab\d+_\w+$/.test(d) && fs.existsSync(path.join(root, d, 'CMakeLists.txt')))
  .sort((a, b) => parseInt(a.slice(3), 10) - parseInt(b.slice(3), 10));
const labNumber = (lab) => parseInt(lab.slice(3), 10);
// The editions: the instructors' in DIR, each student edition beside it (or only one, in DIR).
const only = args.includes('--student') ? Number(args[args.indexOf('--student') + 1]) : null;
const editions = only ? [{ dir: out, student: only }] : args.includes('--instructors') ? [{ dir: out, student: null }]
  : [{ dir: out, student: null }, ...labs.map((lab) => ({ dir: `${out}-student-lab${labNumber(lab)}`, student: labNumber(lab) }))];

// ---------------------------------------------------------------- building, J editions at a time
const buildTimes = [];
if (args.includes('--build')) {
  let running = 0;
  const waiting = [];
  const slot = () => (running < jobs ? (running++, Promise.resolve()) : new Promise((resolve) => waiting.push(resolve)));
  const free = () => { running--; if (waiting.length) { running++; waiting.shift()(); } };
  for (const e of editions) {
    e.built = slot().then(() => new Promise((resolve) => {
      const t = performance.now();
      const child = spawn(process.execPath, [path.join(siteDir, 'build.mjs'), '--out', e.dir, ...(e.student ? ['--student', String(e.student)] : [])],
        { stdio: ['ignore', 'inherit', 'inherit'] });
      child.on('exit', (code) => {
        buildTimes.push(`${e.student ? `lab ${e.student}` : 'instructors'} ${seconds(performance.now() - t)}`);
        free();
        if (code !== 0) { console.log(`site_browser: FAILED: the site did not build (${e.dir})`); process.exit(1); }
        resolve();
      });
    }));
  }
} else {
  for (const e of editions) {
    if (!fs.existsSync(path.join(e.dir, 'pages.json'))) { console.log(`site_browser: FAILED: ${e.dir} holds no built site (run with --build)`); process.exit(1); }
    e.built = Promise.resolve();
  }
}

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
const hashes = new Map();
const sha = (file) => {
  if (!hashes.has(file)) hashes.set(file, crypto.createHash('sha1').update(fs.readFileSync(file)).digest('hex'));
  return hashes.get(file);
};

const problems = [];
const summary = [];
const timing = { static: 0, browser: 0, opened: 0, pages: 0 };
if (shots && !planOnly) {
  fs.rmSync(shots, { recursive: true, force: true });
  fs.mkdirSync(shots, { recursive: true });
}

// ---------------------------------------------------------------- the static reading of an edition
// Every page's facts, the checks they allow, and which pages the browser must open.
function readEdition(edition, reference) {
  const t = performance.now();
  const { dir, student } = edition;
  const tag = student ? `student lab ${student}` : 'instructors';
  const fail = (name, what) => problems.push(`${name} (${tag}): ${what}`);
  const pages = htmlFiles(dir).map((f) => path.relative(dir, f).split(path.sep).join('/')).sort();
  const base = pathToFileURL(dir + '/').href;
  const facts = new Map();
  const keys = new Map();  // page → its HTML without the frame's edition-specific parts
  for (const name of pages) {
    const html = fs.readFileSync(path.join(dir, name), 'utf8');
    facts.set(name, pageFacts(html));
    keys.set(name, withoutFrame(html));
  }
  const editionLabs = labs.filter((l) => !student || labNumber(l) <= student);
  // The diffs between the edition's labs; a student edition leaves out the one into lab N (its
  // reading guides state lab N's answers: site/student.mjs).
  const expectedDiffs = Math.max(editionLabs.length - (student ? 2 : 1), 0);
  const expectedNav = ['Vulkan labs', ...editionLabs.map((l) => `lab ${labNumber(l)}`), ...(expectedDiffs > 0 ? ['diffs'] : []),
    'docs', 'gallery', ...(pages.includes('performance.html') ? ['performance'] : [])];
  // A site URL → the file it names (relative to DIR, '..' if outside), or null for another scheme.
  const inSite = (raw, name) => {
    let url;
    try { url = new URL(raw, base + name); } catch { return { bad: true }; }
    if (url.protocol !== 'file:') return { other: url.href, scheme: url.protocol };
    const [file, hash] = decodeURIComponent(url.href).split('#');
    let target = path.relative(dir, fileURLToPath(file)).split(path.sep).join('/');
    if (!target.startsWith('..') && (target === '' || fs.existsSync(path.join(dir, target)) && fs.statSync(path.join(dir, target)).isDirectory())) {
      target = path.posix.join(target, 'index.html');
    }
    return { target, hash };
  };
  const images = new Map();  // site file of a picture → the first page showing it
  const loaded = new Map();  // page → the site files it loads (for its twin's bytes)
  for (const [name, f] of facts) {
    if (f.nav.join('|') !== expectedNav.join('|')) fail(name, `navigation bar is "${f.nav.join(' | ')}", not "${expectedNav.join(' | ')}"`);
    if (/— Vulkan labs.*— Vulkan labs|^Vulkan labs.*— Vulkan labs/.test(f.title)) fail(name, `title repeats the site's name: "${f.title}"`);
    if (f.rawMath) fail(name, `raw math left in the text: ${f.rawMath}`);
    if (f.katexErrors) fail(name, `${f.katexErrors} KaTeX error(s)`);
    for (const raw of [...f.links, ...f.images]) {
      const r = inSite(raw, name);
      if (r.bad) { fail(name, `link ${raw}: not a URL`); continue; }
      if (r.other) {
        if (!/^(https?|mailto):$/.test(r.scheme)) fail(name, `link ${raw}: unexpected scheme`);
        continue;  // a link out of the site: the reader's choice, nothing loads by itself
      }
      const { target, hash } = r;
      if (target.startsWith('..')) { fail(name, `link ${raw} leaves the site`); continue; }
      if (!fs.existsSync(path.join(dir, target))) { fail(name, `link ${raw} → ${target}: no such file`); continue; }
      if (hash && target.endsWith('.html') && !(facts.get(target)?.ids ?? []).includes(hash)) fail(name, `link ${raw}: ${target} has no #${hash}`);
      if (student) {
        const later = /lab(\d+)_/.exec(target);
        if (later && Number(later[1]) > student) fail(name, `links a later lab's file: ${raw}`);
      }
    }
    const files = [];
    for (const load of f.loads) {
      if (load.raw.startsWith('data:')) continue;
      const r = inSite(load.raw, name);
      if (r.bad || r.other) { fail(name, `${load.what} asks another origin for ${load.raw}`); continue; }
      if (r.target.startsWith('..') || !fs.existsSync(path.join(dir, r.target))) { fail(name, `${load.what} ${load.raw}: no such file in the site`); continue; }
      files.push(r.target);
      if (load.image && !images.has(r.target)) images.set(r.target, name);
    }
    loaded.set(name, files);
    if (student) {
      const later = [...f.prose.matchAll(/\blab[ _]?(\d+)/gi)].find((m) => Number(m[1]) > student);
      if (later) fail(name, `names a later lab in its text: "${f.prose.slice(Math.max(0, later.index - 60), later.index + 30).replace(/\s+/g, ' ')}"`);
    }
  }
  // The stylesheets' own url()s (KaTeX's fonts): each is there.
  for (const css of new Set([...loaded.values()].flat().filter((f) => f.endsWith('.css')))) {
    for (const m of fs.readFileSync(path.join(dir, css), 'utf8').matchAll(/url\(\s*(['"]?)([^'")]+)\1\s*\)/g)) {
      if (/^(data:|#)/.test(m[2])) continue;
      if (/^[a-z][a-z0-9+.-]*:/i.test(m[2])) { fail(css, `url(${m[2]}): another origin`); continue; }
      if (!fs.existsSync(path.join(dir, path.posix.dirname(css), m[2].split(/[?#]/)[0]))) fail(css, `url(${m[2]}): no such file`);
    }
  }

  const pagesJson = JSON.parse(fs.readFileSync(path.join(dir, 'pages.json'), 'utf8'));
  for (const p of pagesJson) {
    if (!facts.has(p.page)) fail(p.page, 'pages.json lists it, but it was not found');
    else if (p.source?.endsWith('.md') && !student && markdownHasMath(p.source) && !facts.get(p.page).katex) {
      fail(p.page, `${p.source} has math, but the page shows no KaTeX`);
    }
  }
  if (!student) {  // every README and doc is a page: the top README, each lab's, each gallery's, docs/*.md
    const markdownSources = ['README.md', ...labs.map((l) => `${l}/README.md`),
      ...fs.readdirSync(path.join(root, 'docs')).filter((f) => f.endsWith('.md')).map((f) => `docs/${f}`),
      ...labs.map((l) => `docs/images/${l}/README.md`).filter((f) => fs.existsSync(path.join(root, f)))];
    for (const source of markdownSources) if (!pagesJson.some((p) => p.source === source)) fail(source, 'has no page in the site');
  } else if (pagesJson.some((p) => p.source === 'docs/solutions.md') || facts.has('solutions.html')) fail('solutions.html', 'docs/solutions.md has a page in a student edition');

  // ------------------------------------------------------------ previous/next: lab 1 → lab N and back
  const follow = (start, rel) => {
    const chain = [];
    for (let at = start; at && chain.length <= labs.length; ) {
      chain.push(at);
      const href = facts.get(at)?.[rel];
      at = href ? path.posix.normalize(path.posix.join(path.posix.dirname(at), href.split('#')[0])) : null;
      if (at && !/^lab\d+_\w+\.html$/.test(at)) break;
    }
    return chain;
  };
  const labPages = editionLabs.map((l) => `${l}.html`);
  const indexNext = facts.get('index.html')?.next;
  if (indexNext !== labPages[0]) fail('index.html', `its "next" link is ${indexNext}, not ${labPages[0]}`);
  const forward = follow(labPages[0], 'next');
  const backward = follow(labPages.at(-1), 'prev');
  if (forward.join(' → ') !== labPages.join(' → ')) fail(labPages[0], `"next" chains ${forward.join(' → ')}, not ${labPages.join(' → ')}`);
  if (backward.join(' → ') !== [...labPages].reverse().join(' → ')) fail(labPages.at(-1), `"previous" chains ${backward.join(' → ')}`);

  // ------------------------------------------------------------ every lab file has a page the lab links
  let labFiles = 0;
  for (const lab of editionLabs) {
    const files = [...filesUnder(lab), ...filesUnder(`shaders/${lab}`)].filter((f) => f !== `${lab}/README.md`);
    const linked = new Set((facts.get(`${lab}.html`)?.links ?? []).map((l) => l.split('#')[0]));
    for (const f of files) {
      labFiles++;
      if (!facts.has(`src/${f}.html`)) fail(`${lab}.html`, `${f} has no page (src/${f}.html)`);
      else if (!linked.has(`src/${f}.html`)) fail(`${lab}.html`, `does not link ${f}'s page`);
    }
  }

  // ------------------------------------------------------------ the diff pages, as built
  const diffPages = [];
  for (const [name, f] of facts) {
    const m = /^diff-(lab\d+_\w+)-(lab\d+_\w+)\.html$/.exec(name);
    if (!m) continue;
    diffPages.push(name);
    const want = manifest(m[2]);
    const got = f.lessonFiles;
    if (want.length === 0) fail(name, `docs/diffs/lessons.md has no section for ${m[2]}`);
    if (got.map((x) => x.path).join('\n') !== want.map((e) => e.path).join('\n')) {
      fail(name, `files are not the manifest's, in its order:\n    page:     ${got.map((x) => x.path).join(', ')}\n    manifest: ${want.map((e) => e.path).join(', ')}`);
    }
    got.forEach((x, i) => {
      // diff2html's own file header, "{lab1 → lab2}/x.h" or "a → b" for a changed path: the new side.
      const shown = (x.shown[0] ?? '').replace(/\{[^{}]* → ([^{}]*)\}/g, '$1').replace(/^.* → /, '');
      if (x.shown.length !== 1 || shown !== x.path) fail(name, `file ${i + 1}: diff2html shows "${x.shown.join(', ')}", not ${x.path}`);
      if (want[i] && x.guide !== want[i].guide) fail(name, `file ${i + 1} (${x.path}): reading guide "${x.guide}" is not the manifest's "${want[i].guide}"`);
      const isNew = want[i] && !want[i].from && !fs.existsSync(path.join(root, want[i].path.replace(m[2], m[1])));
      if (isNew && (x.columns !== 1 || x.sides !== 0 || x.lines === 0)) fail(name, `file ${i + 1} (${x.path}) is new: not shown whole in one column (${x.columns} columns, ${x.sides} sides)`);
      if (!isNew && (x.sides !== 2 || x.lines === 0)) fail(name, `file ${i + 1} (${x.path}): not a side-by-side diff (${x.sides} sides, ${x.lines} lines)`);
    });
  }
  if (diffPages.length !== expectedDiffs) fail('diffs', `${diffPages.length} lesson diff pages, not ${expectedDiffs}`);

  // ------------------------------------------------------------ the pages to open, and why
  const open = new Map();  // page → why
  const twins = new Map();  // page → the reference edition's page it runs as
  const same = new Map();  // page → whether it is the reference edition's page of that name, frame aside
  const sameAsReference = (name) => {
    if (!same.has(name)) {
      const mine = loaded.get(name);
      const theirs = reference?.loaded.get(name) ?? [];
      same.set(name, Boolean(reference?.keys.get(name) === keys.get(name) && mine.length === theirs.length &&
        mine.every((f, i) => f === theirs[i] && sha(path.join(dir, f)) === sha(path.join(reference.dir, theirs[i])))));
    }
    return same.get(name);
  };
  const isTwin = (name) => Boolean(reference?.open.has(name)) && sameAsReference(name);
  for (const name of pages) {
    const f = facts.get(name);
    if (f.active.length) open.set(name, `it loads or runs ${f.active.slice(0, 3).join(', ')}`);
    else if (!name.startsWith('src/')) {
      if (isTwin(name)) twins.set(name, name);
      else open.set(name, reference ? 'a page other than src/ with no twin in the instructors\' edition' : 'a page other than src/');
    }
  }
  for (const [name, why] of [...open]) if (why.startsWith('it loads') && isTwin(name)) { open.delete(name); twins.set(name, name); }
  const sources = pages.filter((p) => p.startsWith('src/') && !open.has(p));
  const kindOf = (p) => (p.endsWith('/index.html') ? 'a folder' : `.${path.posix.basename(p, '.html').split('.').pop()}`);
  const byKind = new Map();
  for (const p of sources) {
    const kind = kindOf(p);
    const best = byKind.get(kind);
    const score = (q) => [sameAsReference(q) ? 0 : 1, q.length];
    if (!best || score(p)[0] > score(best)[0] || score(p)[0] === score(best)[0] && score(p)[1] > score(best)[1]) byKind.set(kind, p);
  }
  for (const [kind, p] of byKind) open.set(p, `the source page of the longest path of type ${kind}`);
  if (openAll) {
    twins.clear();
    for (const name of pages) if (!open.has(name)) open.set(name, 'every page (--all)');
  }
  // Over HTTP: the smallest page of each combination of loaded file types, and one source page.
  const httpOpen = new Map();
  if (!student) {
    const combos = new Map();
    for (const name of open.keys()) {
      if (name.startsWith('src/')) continue;
      const types = [...new Set(loaded.get(name).map((f) => path.posix.extname(f)))].sort();
      if (facts.get(name).katex) types.push('KaTeX fonts');
      const combo = types.join(' ');
      const size = fs.statSync(path.join(dir, name)).size;
      if (!combos.has(combo) || size < combos.get(combo).size) combos.set(combo, { name, size });
    }
    for (const [combo, { name }] of combos) httpOpen.set(name, `the smallest page loading ${combo}`);
    const src = [...byKind.values()].find((p) => !p.endsWith('/index.html'));
    if (src) httpOpen.set(src, 'a source page');
  }
  timing.static += performance.now() - t;
  timing.pages += pages.length;
  return { ...edition, tag, pages, facts, keys, loaded, open, twins, httpOpen, images, diffPages, labFiles, expectedNav };
}

// ---------------------------------------------------------------- the browser
let browser = null;
let noBrowser = null;
const servers = [];
process.on('exit', () => servers.forEach((s) => s.kill()));  // also when a step below throws
async function startBrowser() {
  if (browser || noBrowser) return;
  if (!fs.existsSync(chromiumPath)) { noBrowser = `${chromiumPath} is missing (scripts/setup.sh installs Debian's chromium)`; return; }
  const { chromium } = await import('playwright-core');
  try {
    browser = await chromium.launch({ executablePath: chromiumPath, args: ['--no-sandbox'] });
  } catch (error) {
    noBrowser = `Chromium (${chromiumPath}) cannot start here: ${String(error.message).split('\n')[0]}`;
  }
}
async function serve(dir) {
  const server = spawn('python3', ['-u', '-m', 'http.server', '--bind', '127.0.0.1', '--directory', dir, '0'], { stdio: ['ignore', 'pipe', 'pipe'] });
  servers.push(server);
  return new Promise((resolve, reject) => {
    server.stdout.on('data', (chunk) => { const m = /port (\d+)/.exec(String(chunk)); if (m) resolve(`http://127.0.0.1:${m[1]}/`); });
    server.on('exit', (code) => reject(new Error(`python3 -m http.server exited (${code})`)));
    setTimeout(() => reject(new Error('python3 -m http.server did not start in 20 s')), 20000);
  });
}

// What Chromium's DOM shows of a page (after its scripts ran), in the form of check_static.mjs's facts.
function domFacts() {
  const prose = new Map();  // block element → its text outside code, diffs and KaTeX
  const main = document.querySelector('main');
  if (main) {
    const walker = document.createTreeWalker(main, NodeFilter.SHOW_TEXT);
    for (let n = walker.nextNode(); n; n = walker.nextNode()) {
      if (n.parentElement.closest('code, pre, script, style, .katex, .katex-error, .lesson-diff')) continue;
      const block = n.parentElement.closest('p, li, td, th, h1, h2, h3, h4, h5, h6, dd, dt, blockquote, main');
      prose.set(block, (prose.get(block) ?? '') + n.textContent);
    }
  }
  return {
    title: document.title,
    nav: [...document.querySelectorAll('nav.site-nav a')].map((a) => a.textContent.trim()),
    prev: document.querySelector('a[rel=prev]')?.getAttribute('href') ?? null,
    next: document.querySelector('a[rel=next]')?.getAttribute('href') ?? null,
    links: [...document.querySelectorAll('a[href]')].map((a) => a.getAttribute('href')),
    images: [...document.querySelectorAll('img[src]')].map((i) => i.getAttribute('src')),
    broken: [...document.images].filter((i) => !(i.complete && i.naturalWidth > 0)).map((i) => i.getAttribute('src')),
    ids: [...document.querySelectorAll('[id]')].map((e) => e.id),
    katex: document.querySelectorAll('.katex').length,
    katexErrors: document.querySelectorAll('.katex-error').length,
    prose: [...prose.values()].join('\n'),
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
}
const COMPARED = ['title', 'nav', 'prev', 'next', 'links', 'images', 'ids', 'katex', 'katexErrors', 'prose', 'lessonFiles'];
function differences(mine, dom) {
  const out = [];
  for (const key of COMPARED) {
    let a = mine[key];
    let b = dom[key];
    if (key === 'lessonFiles') b = b.map(({ coloured, tokens, ...rest }) => rest);
    if (key === 'title') b = b.replace(/\s+/g, ' ').trim();
    if (JSON.stringify(a) === JSON.stringify(b)) continue;
    if (Array.isArray(a) && Array.isArray(b)) {
      const i = a.findIndex((x, k) => JSON.stringify(x) !== JSON.stringify(b[k]));
      const at = i < 0 ? Math.min(a.length, b.length) : i;
      a = `${a.length} (#${at + 1}: ${JSON.stringify(a[at])})`;
      b = `${b.length} (#${at + 1}: ${JSON.stringify(b[at])})`;
    } else if (typeof a === 'string' && typeof b === 'string') {
      let i = 0;
      while (i < a.length && a[i] === b[i]) i++;
      a = JSON.stringify(a.slice(Math.max(0, i - 30), i + 30));
      b = JSON.stringify(b.slice(Math.max(0, i - 30), i + 30));
    }
    out.push(`${key}: ${a} here, ${b} in Chromium`);
  }
  return out;
}

// Opens the given pages (name → why) of an edition from base, two tabs at a time; returns name → DOM facts.
async function openPages(ed, kind, base, list) {
  const fail = (name, what) => problems.push(`${name} (${ed.tag}, ${kind}): ${what}`);
  const doms = new Map();
  const context = await browser.newContext({ viewport: { width: 390, height: 844 } });
  context.setDefaultTimeout(120000);  // a loaded machine: the longest diff page takes 10-20 s; CTest's TIMEOUT guards a hang
  const current = new Map();  // tab → the page it shows
  // Nothing may come from another origin: every such request is aborted here and counted.
  await context.route((url) => !url.href.startsWith(base) && url.protocol !== 'data:', (route) => {
    let asker = '?';
    try { asker = current.get(route.request().frame().page()) ?? '?'; } catch { /* a worker's request: no frame */ }
    fail(asker, `asked another origin for ${route.request().url()} (blocked)`);
    return route.abort('blockedbyclient');
  });
  const queue = [...list.keys()];
  const tab = async () => {
    const page = await context.newPage();
    const on = (what) => fail(current.get(page), what);
    page.on('console', (m) => { if (m.type() === 'error' && !m.text().includes('ERR_BLOCKED_BY_CLIENT')) on(`console error: ${m.text()}`); });
    page.on('pageerror', (e) => on(`uncaught exception: ${e.message}`));
    page.on('requestfailed', (r) => { if (!r.failure()?.errorText.startsWith('net::ERR_BLOCKED_BY_CLIENT')) on(`request failed: ${r.url()} (${r.failure()?.errorText})`); });
    page.on('response', (r) => { if (r.status() >= 400) on(`HTTP ${r.status()} for ${r.url()}`); });
    for (let name; (name = queue.shift()) !== undefined; ) {
      const t0 = performance.now();
      current.set(page, name);
      try {
        const shot = shots && kind === 'file' && !ed.student && !name.startsWith('src/') && !planOnly;
        await page.setViewportSize(shot ? { width: 1280, height: 900 } : { width: 390, height: 844 });
        await page.goto(base + name, { waitUntil: 'load' });
        await page.evaluate(() => document.fonts.ready);
        if (shot) {
          await page.screenshot({ path: path.join(shots, name.replace(/\//g, '__').replace(/\.html$/, '.png')), fullPage: fullShots });
          await page.setViewportSize({ width: 390, height: 844 });
        }
        // A phone: the page may not scroll sideways (wide tables and diffs scroll in their own box).
        const width = await page.evaluate(() => document.documentElement.scrollWidth);
        if (width > 390) {
          const culprit = await page.evaluate(() => {
            const scrolls = (e) => ['auto', 'scroll', 'hidden'].includes(getComputedStyle(e).overflowX);
            const inBox = (e) => { for (let p = e.parentElement; p && p !== document.body; p = p.parentElement) if (scrolls(p)) return true; return false; };
            const all = [...document.body.querySelectorAll('*')].filter((e) => !inBox(e));
            // the outermost too-wide element not inside a scrolling box, else the innermost whose text sticks out
            const wide = all.find((e) => e.getBoundingClientRect().right > 391);
            if (wide) return wide.outerHTML.slice(0, 120);
            const spills = (e) => e.scrollWidth > e.clientWidth + 1 && !scrolls(e);
            let at = all.find(spills);
            for (let inner = at; inner; inner = [...at.children].find(spills)) at = inner;
            return at?.outerHTML.slice(0, 120);
          });
          on(`${width} px wide at a 390 px width (first too wide: ${culprit})`);
        }
        const dom = await page.evaluate(domFacts);
        for (const src of dom.broken) on(`image ${src} did not load`);
        for (const d of differences(ed.facts.get(name), dom)) on(`check_static.mjs reads the HTML otherwise than Chromium: ${d}`);
        doms.set(name, dom);
      } catch (error) {
        on(`could not be checked in the browser: ${String(error.message).split('\n')[0]}`);
      }
      if (showTimes) console.log(`  ${seconds(performance.now() - t0)} ${ed.tag} ${kind} ${name}`);
    }
    current.delete(page);
    await page.close();
  };
  await Promise.all([tab(), tab()]);
  await context.close();
  timing.opened += list.size;
  return doms;
}

// Every picture of the edition, each distinct file once over all editions: decoded in one page.
const decoded = new Set();
async function decodePictures(ed) {
  const todo = [...ed.images.keys()].filter((f) => { const h = sha(path.join(ed.dir, f)); if (decoded.has(h)) return false; decoded.add(h); return true; });
  if (!todo.length) return;
  const page = await browser.newPage();
  await page.goto(pathToFileURL(path.join(ed.dir, 'pages.json')).href);
  const bad = await page.evaluate((urls) => Promise.all(urls.map((u) => {
    const img = new Image();
    img.src = u;
    return img.decode().then(() => (img.naturalWidth > 0 ? null : u), () => u);
  })).then((r) => r.filter(Boolean)), todo.map((f) => pathToFileURL(path.join(ed.dir, f)).href));
  for (const u of bad) {
    const file = path.relative(ed.dir, fileURLToPath(u)).split(path.sep).join('/');
    problems.push(`${ed.images.get(file)} (${ed.tag}): picture ${file} does not decode`);
  }
  await page.close();
}

async function checkEdition(ed) {
  if (planOnly) {
    console.log(`${ed.tag}: ${ed.open.size} of ${ed.pages.length} pages opened (file://)${ed.httpOpen.size ? `, ${ed.httpOpen.size} over HTTP` : ''}, ${ed.twins.size} twin(s) of the instructors' pages`);
    for (const [name, why] of ed.open) console.log(`  open ${name}: ${why}`);
    for (const [name, why] of ed.httpOpen) console.log(`  http ${name}: ${why}`);
    return;
  }
  await startBrowser();
  if (!browser) return;
  const t = performance.now();
  const doms = await openPages(ed, 'file', pathToFileURL(ed.dir + '/').href, ed.open);
  if (ed.httpOpen.size) await openPages(ed, 'http', await serve(ed.dir), ed.httpOpen);
  const td = performance.now();
  await decodePictures(ed);
  if (showTimes) console.log(`  ${seconds(performance.now() - td)} ${ed.tag}: pictures decoded`);
  // The diff pages: diff2html's UI coloured every file (a twin: as its instructors' page did).
  for (const name of ed.diffPages) {
    const dom = doms.get(name) ?? ed.reference?.doms.get(ed.twins.get(name));
    if (!dom) { problems.push(`${name} (${ed.tag}): not opened in the browser`); continue; }
    dom.lessonFiles.forEach((f, i) => {
      if (f.coloured === 0 || f.tokens === 0) problems.push(`${name} (${ed.tag}): file ${i + 1} (${f.path}): no syntax colouring (${f.coloured} highlighted lines, ${f.tokens} tokens)`);
    });
  }
  ed.doms = doms;
  timing.browser += performance.now() - t;
}

let reference = null;
for (const edition of editions) {
  await edition.built;
  const ed = readEdition(edition, reference);
  ed.reference = reference;
  await checkEdition(ed);
  if (!ed.student) reference = ed;
  const mathPages = [...ed.facts.values()].filter((f) => f.katex > 0).length;
  summary.push(`${ed.tag}: ${ed.pages.length} pages (${ed.labFiles} lab files), ${ed.diffPages.length} diff pages, ${mathPages} with KaTeX; ` +
    `${browser ? 'opened' : 'to open'} ${ed.open.size}${ed.httpOpen.size ? ` (+${ed.httpOpen.size} over HTTP)` : ''}, ${ed.twins.size} twin(s) of the instructors'`);
}
if (planOnly) process.exit(0);

const version = browser?.version();
await browser?.close();
servers.forEach((s) => s.kill());
console.log(`site_browser: ${browser ? `Chromium ${version}` : 'no browser'}, every page read as HTML, ${timing.opened} opened in the browser at 390 px; ` +
  `${shots ? `screenshots in ${shots}` : 'no screenshots (no --shots)'}\n  ${summary.join('\n  ')}\n  time: ${seconds(performance.now() - started)} in all` +
  `${buildTimes.length ? `; builds (${jobs} at a time) ${buildTimes.join(', ')}` : ''}; HTML read ${seconds(timing.static)}; browser ${seconds(timing.browser)}`);
if (problems.length) {
  console.log(`site_browser: FAILED, ${problems.length} problem(s):`);
  for (const p of problems.slice(0, 200)) console.log(`  ${p}`);
  if (problems.length > 200) console.log(`  … and ${problems.length - 200} more`);
  process.exit(1);
}
if (noBrowser) skip(`${noBrowser}: only the checks without a browser ran (they passed)`);
console.log('site_browser: passed');
process.exit(0);
