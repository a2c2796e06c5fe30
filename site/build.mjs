// site/build.mjs — the course site, built from what the repository already has.
//
//   node site/build.mjs [--out DIR]      (scripts/make_site.sh wraps it; default DIR: build/site)
//
// Pages: the top README (index.html), each lab's README with its exercises (labN_name.html; the
// exercises come from `scripts/exercise.sh --list`), the docs (docs/X.md → X.html), each lesson
// diff of docs/diffs/ side by side (diff-A-B.html: diff2html, the manifest docs/diffs/lessons.md's
// reading guide above each file, in the diff's order), the galleries (gallery.html and
// gallery-<lab>.html from docs/images/<lab>/README.md), performance.html (docs/performance.md, the
// measurement log) and tradeoffs.html (docs/tradeoffs.md, then each plot of docs/tradeoffs/ with its
// CSV as a table). Markdown is rendered by markdown-it,
// `$…$` / `$$…$$` math by KaTeX at build time; diff2html's UI bundle colours the diffs' syntax in
// the browser. Links between Markdown files become links between pages, pictures are copied in,
// a linked source file gets a page that shows it. Every asset is copied into DIR, so the site
// works from file:// and from `python3 -m http.server` with no network. DIR/pages.json lists the
// pages and their sources (site/check.mjs, CTest site_browser, visits them in Chromium).
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import MarkdownIt from 'markdown-it';
import anchor from 'markdown-it-anchor';
import GithubSlugger from 'github-slugger';
import katexModule from '@vscode/markdown-it-katex';
import * as Diff2Html from 'diff2html';
import hljs from 'highlight.js';
import { parse as parseCsv } from 'csv-parse/sync';

const siteDir = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(siteDir, '..');
const args = process.argv.slice(2);
const out = args.includes('--out') ? path.resolve(args[args.indexOf('--out') + 1]) : path.join(root, 'build/site');
const started = performance.now();
const read = (p) => fs.readFileSync(path.join(root, p), 'utf8');
const exists = (p) => fs.existsSync(path.join(root, p));
const esc = (s) => String(s).replace(/[&<>"']/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;', "'": '&#39;' })[c]);
const posix = path.posix;

// A fresh output folder: only one this script wrote (it has pages.json), or an empty one, is replaced.
if (fs.existsSync(out) && (!fs.statSync(out).isDirectory() || fs.readdirSync(out).length && !fs.existsSync(path.join(out, 'pages.json')))) {
  console.error(`make_site: ${out} is not a folder this script built (nor an empty one): not touching it`);
  process.exit(2);
}
fs.rmSync(out, { recursive: true, force: true });
fs.mkdirSync(out, { recursive: true });

// ---------------------------------------------------------------- what becomes a page
const labs = fs.readdirSync(root).filter((d) => /^lab\d+_\w+$/.test(d) && exists(`${d}/CMakeLists.txt`))
  .sort((a, b) => parseInt(a.slice(3), 10) - parseInt(b.slice(3), 10));
const labNumber = (lab) => parseInt(lab.slice(3), 10);
const diffs = labs.slice(1).map((b, i) => ({ a: labs[i], b, file: `docs/diffs/${labs[i]}-${b}.diff` }))
  .filter((d) => exists(d.file));
const pageOf = new Map([['README.md', 'index.html'], ['docs/diffs/README.md', 'diffs.html'],
  ['docs/diffs/lessons.md', 'lessons.html'], ['docs/performance.md', 'performance.html'],
  ['docs/tradeoffs.md', 'tradeoffs.html']]);
for (const lab of labs) if (exists(`${lab}/README.md`)) pageOf.set(`${lab}/README.md`, `${lab}.html`);
for (const f of fs.readdirSync(path.join(root, 'docs'))) {
  if (f.endsWith('.md') && !pageOf.has(`docs/${f}`)) pageOf.set(`docs/${f}`, f.replace(/\.md$/, '.html'));
}
for (const lab of labs) {
  if (exists(`docs/images/${lab}/README.md`)) pageOf.set(`docs/images/${lab}/README.md`, `gallery-${lab}.html`);
}
for (const d of diffs) pageOf.set(d.file, `diff-${d.a}-${d.b}.html`);

// ---------------------------------------------------------------- files copied in, source pages
const copied = new Set();
function copyIn(repoPath) {  // a repository file into the site at the same relative path
  if (copied.has(repoPath)) return repoPath;
  fs.mkdirSync(path.dirname(path.join(out, repoPath)), { recursive: true });
  fs.copyFileSync(path.join(root, repoPath), path.join(out, repoPath));
  copied.add(repoPath);
  return repoPath;
}
const sourcePages = new Map();  // repository path → site page that shows it (written at the end)
const isBinary = (p) => /\.(png|jpe?g|gif|svg|webp|spv|bin)$/i.test(p);
const isDir = (p) => fs.existsSync(path.join(root, p)) && fs.statSync(path.join(root, p)).isDirectory();
const warnings = [];

// Where a repository path (file or folder) lives in the site; hash is kept or replaced.
function siteTarget(repoPath, hash) {
  repoPath = repoPath.replace(/\/$/, '');
  if (pageOf.has(repoPath)) return pageOf.get(repoPath) + hash;
  if (isDir(repoPath)) {
    if (pageOf.has(`${repoPath}/README.md`)) return pageOf.get(`${repoPath}/README.md`) + hash;
    sourcePages.set(repoPath, `src/${repoPath}/index.html`);
    return `src/${repoPath}/index.html`;
  }
  const csv = repoPath.match(/^docs\/tradeoffs\/(\w+)\.csv$/);
  if (csv) return `tradeoffs.html#data-${csv[1]}`;
  if (!exists(repoPath)) return null;
  if (isBinary(repoPath)) return copyIn(repoPath);
  sourcePages.set(repoPath, `src/${repoPath}.html`);
  return `src/${repoPath}.html${hash}`;
}
function relative(fromPage, to) {  // a site path as seen from a page
  const [file, hash] = to.split('#');
  const rel = posix.relative(posix.dirname(fromPage), file) || posix.basename(file);
  return hash === undefined ? rel : `${rel}#${hash}`;
}

// ---------------------------------------------------------------- Markdown
const katex = katexModule.default ?? katexModule;
const md = new MarkdownIt({ html: true })
  .use(katex, { enableFencedBlocks: true })
  .use(anchor, { tabIndex: false, slugifyWithState: (title, state) => state.env.slugger.slug(title) });

// Links and pictures point into the site: relative to the page, not to the Markdown file.
md.core.ruler.push('site_links', (state) => {
  const { source, page } = state.env;
  if (!source) return;  // renderInline of a manifest line: no links to fix
  const fix = (token, attr) => {
    const url = token.attrGet(attr);
    if (!url || /^[a-z][a-z0-9+.-]*:/i.test(url) || url.startsWith('#')) return;
    const [file, hash = ''] = url.split('#');
    const repoPath = posix.normalize(posix.join(posix.dirname(source), decodeURIComponent(file)));
    const target = siteTarget(repoPath, hash ? `#${hash}` : '');
    if (target === null) warnings.push(`${source} links to ${url}, which does not exist`);
    else token.attrSet(attr, relative(page, target));
  };
  for (const block of state.tokens) {
    for (const t of block.children ?? []) {
      if (t.type === 'link_open') fix(t, 'href');
      if (t.type === 'image') fix(t, 'src');
    }
  }
});
function renderMarkdown(source, page) {
  const env = { source, page, slugger: new GithubSlugger() };
  const tokens = md.parse(read(source), env);
  const h1 = tokens.findIndex((t) => t.type === 'heading_open' && t.tag === 'h1');
  const title = h1 >= 0 ? tokens[h1 + 1].content : source;
  return { html: md.renderer.render(tokens, md.options, env), title };
}

// ---------------------------------------------------------------- the page frame
const nav = [...labs.map((lab) => [`${lab}.html`, `lab ${labNumber(lab)}`]),
  ['diffs.html', 'diffs'], ['gallery.html', 'gallery'], ['performance.html', 'performance']];
const pages = [];
function writePage(page, { title, body, section, source = null, wide = false, scripts = [] }) {
  const up = (p) => relative(page, p);
  const links = nav.map(([href, label]) =>
    `<a href="${up(href)}"${href === section ? ' class="current" aria-current="page"' : ''}>${label}</a>`).join('\n    ');
  const html = `<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>${esc(title)} — Vulkan labs</title>
<link rel="icon" href="data:,">
<link rel="stylesheet" href="${up('assets/katex/katex.min.css')}">
<link rel="stylesheet" href="${up('assets/hljs/github.min.css')}">
<link rel="stylesheet" href="${up('assets/diff2html/diff2html.min.css')}">
<link rel="stylesheet" href="${up('assets/style.css')}">
</head>
<body>
<nav class="site-nav">
  <a class="brand" href="${up('index.html')}">Vulkan labs</a>
  <div class="links">
    ${links}
  </div>
</nav>
<main class="${wide ? 'wide' : 'text'}">
${body}
</main>
<footer>Built by <code>scripts/make_site.sh</code>${source ? ` from <code>${esc(source)}</code>` : ''}.</footer>
${scripts.map((s) => `<script src="${up(s)}"></script>`).join('\n')}
</body>
</html>
`;
  fs.mkdirSync(path.dirname(path.join(out, page)), { recursive: true });
  fs.writeFileSync(path.join(out, page), html);
  pages.push({ page, title, source });
}
function markdownPage(source, section, extra = '') {
  const page = pageOf.get(source);
  const { html, title } = renderMarkdown(source, page);
  writePage(page, { title, body: html + extra, section, source });
}

// ---------------------------------------------------------------- labs and their exercises
function exercisesOf(lab) {  // from the script's own listing: "  name  file:line  (tests: …)" + hint line
  const listing = execFileSync('bash', [path.join(root, 'scripts/exercise.sh'), '--list', lab], { cwd: root, encoding: 'utf8' });
  const lines = listing.split('\n');
  const list = [];
  lines.forEach((line, i) => {
    const m = line.match(/^ {2}(\S+)\s+(\S+):(\d+)\s+\(tests: (.*)\)$/);
    if (m) list.push({ name: m[1], file: m[2], line: m[3], tests: m[4] === 'none' ? [] : m[4].split(' '), hint: (lines[i + 1] ?? '').trim() });
  });
  return list;
}
for (const lab of labs) {
  const page = `${lab}.html`;
  const n = labNumber(lab);
  const diff = diffs.find((d) => d.b === lab);
  const facts = [
    diff ? `<a href="${pageOf.get(diff.file)}">the lesson as a diff: ${diff.a} → ${lab}</a>` : 'the first lab: no diff before it',
    pageOf.has(`docs/images/${lab}/README.md`) ? `<a href="${pageOf.get(`docs/images/${lab}/README.md`)}">its gallery</a>` : 'no gallery yet',
    '<a href="#graded-exercises">its graded exercises</a>',
    exists(`docs/tradeoffs/${lab}.csv`) ? `<a href="tradeoffs.html#data-${lab}">its time-against-error data</a>` : null,
  ].filter(Boolean);
  const exercises = exercisesOf(lab);
  let table = `<h2 id="graded-exercises">Graded exercises</h2>\n`;
  if (exercises.length === 0) {
    table += `<p>Lab ${n} has no graded exercises of its own (<code>bash scripts/exercise.sh --list ${n}</code> lists none).</p>`;
  } else {
    table += `<p>From <code>bash scripts/exercise.sh --list ${n}</code>: <code>bash scripts/exercise.sh ${n}</code> writes a copy with
these cut out, and <code>ctest --test-dir build -L lab${n}</code> in it is the grader: the tests named here fail until the exercise is done.</p>
<div class="table-scroll"><table class="exercises"><thead><tr><th>exercise, where</th><th>hint</th><th>graded by</th></tr></thead><tbody>
${exercises.map((e) => `<tr><td><code>${esc(e.name)}</code><br><a href="${siteTarget(e.file, `#L${e.line}`)}">${esc(e.file)}:${e.line}</a></td>` +
  `<td>${esc(e.hint)}</td><td>${e.tests.map((t) => `<code>${esc(t)}</code>`).join('<br>')}</td></tr>`).join('\n')}
</tbody></table></div>`;
  }
  const { html, title } = renderMarkdown(`${lab}/README.md`, page);
  const box = `<aside class="lab-facts">Lab ${n}: ${facts.join(' · ')}</aside>\n`;
  const body = html.replace(/(<\/h1>\n)/, `$1${box}`) + table;
  writePage(page, { title, body, section: page, source: `${lab}/README.md` });
}

// ---------------------------------------------------------------- the lesson diffs
function manifestEntries(lab) {  // docs/diffs/lessons.md: "N. `path` [← `from`] — what it teaches"
  const entries = [];
  let inLab = false;
  for (const line of read('docs/diffs/lessons.md').split('\n')) {
    if (line.startsWith('## ')) inLab = line.slice(3).trim() === lab;
    const m = inLab && line.match(/^(\d+)\. `([^`]+)`(?: ← `([^`]+)`)? — (.*)$/);
    if (m) entries.push({ n: m[1], path: m[2], from: m[3], guide: m[4] });
  }
  return entries;
}
const diffConfig = { outputFormat: 'side-by-side', drawFileList: false, matching: 'lines', colorScheme: 'light' };
for (const d of diffs) {
  const page = pageOf.get(d.file);
  const files = Diff2Html.parse(read(d.file), diffConfig);
  const entries = manifestEntries(d.b);
  const sections = files.map((file, i) => {
    const e = entries.find((x) => x.path === file.newName) ?? { n: i + 1, path: file.newName, guide: '(not in the manifest)' };
    const from = file.oldName === '/dev/null' ? ' <span class="tag">new</span>' : e.from ? ` <small>← <code>${esc(e.from)}</code></small>` : '';
    return `<section class="lesson-file" id="file-${e.n}" data-path="${esc(e.path)}">
<h2>${e.n}. <code>${esc(e.path)}</code>${from}</h2>
<div class="guide">${md.renderInline(e.guide)}</div>
<div class="lesson-diff">${Diff2Html.html([file], diffConfig)}</div>
</section>`;
  });
  const toc = files.map((f, i) => {
    const e = entries.find((x) => x.path === f.newName) ?? { n: i + 1 };
    return `<li><a href="#file-${e.n}"><code>${esc(f.newName)}</code></a> <span class="stat">+${f.addedLines} −${f.deletedLines}</span></li>`;
  }).join('\n');
  const body = `<h1>${d.a} → ${d.b}: the lesson, in reading order</h1>
<p>Lab ${labNumber(d.b)} is lab ${labNumber(d.a)} plus this lesson: the files it adds or changes, in the order of the manifest
<a href="lessons.html#${d.b}">docs/diffs/lessons.md</a>, each with its reading guide. Every other file of the lab is lab ${labNumber(d.a)}'s,
byte for byte; <a href="${d.b}.html">the lab's README</a> explains in prose. Source: <code>${d.file}</code>.</p>
<ol class="toc">\n${toc}\n</ol>\n${sections.join('\n')}`;
  writePage(page, { title: `${d.a} → ${d.b}`, body, section: 'diffs.html', source: d.file, wide: true,
    scripts: ['assets/diff2html/diff2html-ui.min.js', 'assets/diff.js'] });
}
markdownPage('docs/diffs/README.md', 'diffs.html', `<h2 id="the-diffs">The diffs</h2>\n<ul>\n${diffs.map((d) =>
  `<li><a href="${pageOf.get(d.file)}">${d.a} → ${d.b}</a>: ${manifestEntries(d.b).length} files</li>`).join('\n')}\n</ul>`);
markdownPage('docs/diffs/lessons.md', 'diffs.html');

// ---------------------------------------------------------------- galleries
const galleryCards = labs.map((lab) => {
  const readme = `docs/images/${lab}/README.md`;
  if (!pageOf.has(readme)) {
    return `<section class="gallery-card"><h2 id="${lab}">Lab ${labNumber(lab)}: ${lab}</h2>
<p class="none">No gallery yet: <code>${readme}</code> does not exist.</p></section>`;
  }
  markdownPage(readme, 'gallery.html');
  const thumb = exists(`docs/images/${lab}/default.png`) ? `<img src="${copyIn(`docs/images/${lab}/default.png`)}" alt="${lab}, default scene">` : '';
  return `<section class="gallery-card"><h2 id="${lab}">Lab ${labNumber(lab)}: ${lab}</h2>
<a href="${pageOf.get(readme)}">${thumb}<br>The pictures lab ${labNumber(lab)} must render, with their captions</a></section>`;
});
writePage('gallery.html', { title: 'Galleries', section: 'gallery.html', body: `<h1>Galleries</h1>
<p>Each lab's expected pictures, rendered headless by the lab itself (a ground truth beside them by the CPU reference; <code>bash scripts/make_gallery.sh</code>; the tests
<code>gallery_labN</code> fail when a lab no longer renders them).</p>
<div class="gallery-cards">${galleryCards.join('\n')}</div>` });

// ---------------------------------------------------------------- performance: time against error
const plots = fs.readdirSync(path.join(root, 'docs/tradeoffs')).filter((f) => /^lab\d+_\w+\.csv$/.test(f)).sort();
const plotSections = plots.map((csvName) => {
  const name = csvName.replace(/\.csv$/, '');
  const rows = parseCsv(read(`docs/tradeoffs/${csvName}`), { columns: false, skip_empty_lines: true });
  const [head, ...body] = rows;
  const col = (c) => head.indexOf(c);
  const tr = body.map((r) => `<tr class="${r[col('on_front')] === 'yes' ? 'front' : ''}${r[col('default')] === 'yes' ? ' default' : ''}">` +
    r.map((v) => `<td${/^-?[\d.]+$/.test(v) ? ' class="num"' : ''}>${esc(v)}</td>`).join('') + '</tr>').join('\n');
  const png = `docs/tradeoffs/${name}.png`;
  return `<section class="plot" id="data-${name}"><h3>${name}</h3>
${exists(png) ? `<a href="${copyIn(png)}"><img src="${png}" alt="${name}: time against error"></a>` : '<p class="none">No plot yet.</p>'}
<p>The data (<a href="${copyIn(`docs/tradeoffs/${csvName}`)}">${csvName}</a>): ${body.length} configurations; green rows are on the
Pareto front, the bold one is the lab's default.</p>
<div class="table-scroll"><table class="csv"><thead><tr>${head.map((h) => `<th>${esc(h)}</th>`).join('')}</tr></thead>
<tbody>\n${tr}\n</tbody></table></div></section>`;
});
markdownPage('docs/performance.md', 'performance.html');
markdownPage('docs/tradeoffs.md', 'performance.html', `<h2 id="the-plots-and-their-data">The plots and their data</h2>\n${plotSections.join('\n')}`);

// ---------------------------------------------------------------- the top README and the docs
markdownPage('README.md', null);
for (const [source, page] of pageOf) {
  if (source.startsWith('docs/') && source.split('/').length === 2 && !['performance.html', 'tradeoffs.html'].includes(page)) {
    markdownPage(source, null);
  }
}

// ---------------------------------------------------------------- pages that show a linked file or folder
const languageOf = (p) => ({ h: 'cpp', cpp: 'cpp', vert: 'glsl', frag: 'glsl', comp: 'glsl', glsl: 'glsl', json: 'json',
  sh: 'bash', py: 'python', cmake: 'cmake', txt: 'cmake', md: 'markdown' })[p.split('.').pop()] ?? 'plaintext';
for (const [repoPath, page] of [...sourcePages]) {  // folders first add their files to the list
  if (!isDir(repoPath)) continue;
  const items = fs.readdirSync(path.join(root, repoPath)).sort().map((f) => {
    const target = siteTarget(`${repoPath}/${f}`, '');
    return `<li><a href="${relative(page, target)}"><code>${esc(f)}</code></a></li>`;
  });
  writePage(page, { title: `${repoPath}/`, section: null, body: `<h1><code>${esc(repoPath)}/</code></h1>\n<ul>\n${items.join('\n')}\n</ul>` });
}
for (const [repoPath, page] of sourcePages) {
  if (isDir(repoPath)) continue;
  const text = read(repoPath);
  const code = hljs.highlight(text, { language: languageOf(repoPath) }).value;
  const gutter = text.split('\n').slice(0, text.endsWith('\n') ? -1 : undefined).map((_, i) => `<a id="L${i + 1}" href="#L${i + 1}">${i + 1}</a>`).join('\n');
  writePage(page, { title: repoPath, section: null, source: repoPath, body: `<h1><code>${esc(repoPath)}</code></h1>
<div class="source"><pre class="gutter">${gutter}</pre><pre class="code"><code class="hljs">${code}</code></pre></div>` });
}

// ---------------------------------------------------------------- assets, the page list
const assets = [['site/style.css', 'assets/style.css'], ['site/diff.js', 'assets/diff.js'],
  ['site/node_modules/katex/dist/katex.min.css', 'assets/katex/katex.min.css'],
  ['site/node_modules/highlight.js/styles/github.min.css', 'assets/hljs/github.min.css'],
  ['site/node_modules/diff2html/bundles/css/diff2html.min.css', 'assets/diff2html/diff2html.min.css'],
  ['site/node_modules/diff2html/bundles/js/diff2html-ui.min.js', 'assets/diff2html/diff2html-ui.min.js']];
for (const [from, to] of assets) {
  fs.mkdirSync(path.dirname(path.join(out, to)), { recursive: true });
  fs.copyFileSync(path.join(root, from), path.join(out, to));
}
fs.cpSync(path.join(root, 'site/node_modules/katex/dist/fonts'), path.join(out, 'assets/katex/fonts'), { recursive: true });
fs.writeFileSync(path.join(out, 'pages.json'), JSON.stringify(pages, null, 1) + '\n');
for (const w of warnings) console.error(`make_site: warning: ${w}`);
console.log(`make_site: ${pages.length} pages in ${out} (${((performance.now() - started) / 1000).toFixed(1)} s)`);
