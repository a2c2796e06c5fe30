// site/build.mjs — the course site, built from what the repository already has.
//
//   node site/build.mjs [--out DIR] [--student N]   (scripts/make_site.sh wraps it)
//
// Two editions. The instructors' (default DIR build/site) shows the whole project. The student
// edition of lab N (--student N, default DIR build/site-student-labN) is built from a real student
// copy of lab N (site/student.mjs: scripts/exercise.sh labN): lessons 1..N (the docs' answer spans
// replaced by their questions), the diffs of the labs before N (not the one into lab N: its reading
// guides state lab N's answers), lab N's exercises stubbed as the copy has them, the exercise rows linking to the stubbed
// lines, no page, link or picture of a later lab, the docs without their sections about later labs
// and without docs/solutions.md.
//
// Pages: index.html (the landing page: the course, the code, the two commands, the labs in order),
// each lab's README with its exercises and its files (labN_name.html), the repository README
// (readme.html), the docs (docs/X.md → X.html; docs.html lists them), each lesson diff of docs/diffs/
// (diff-A-B.html: diff2html, side by side, a new file whole in one column, the manifest
// docs/diffs/lessons.md's reading guide above each file), the galleries (gallery.html and
// gallery-<lab>.html), performance.html and tradeoffs.html (each plot with its CSV as a table), and
// a highlighted page (src/<path>.html, line anchors #L42) for every file of every lab folder and
// shader folder and every other file a page links. Lab pages, their diffs and galleries are chained
// by previous/next links; a long page gets a contents sidebar. Markdown is rendered by markdown-it,
// math by KaTeX at build time; diff2html's UI bundle colours the diffs in the browser. Every asset is
// copied into DIR: the site works from file:// and `python3 -m http.server` with no network.
// DIR/pages.json lists the pages and their sources (site/check.mjs, CTest site_browser).
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import MarkdownIt from 'markdown-it';
import anchor from 'markdown-it-anchor';
import GithubSlugger from 'github-slugger';
import katexModule from '@vscode/markdown-it-katex';
import * as Diff2Html from 'diff2html';
import { parse as parseCsv } from 'csv-parse/sync';
import { esc, relative, page as framePage } from './frame.mjs';
import { sourceBody } from './source_pages.mjs';
import { studentLab, prepareStudentTree, laterLabText, hasBody } from './student.mjs';

const usage = `usage: node site/build.mjs [--out DIR] [--student N]
       node site/build.mjs --exercises LAB
  --out DIR        where the site goes (default build/site, or build/site-student-labN)
  --student N      the student edition of lab N (1, lab1 or lab1_camera): built from a student copy
  --exercises LAB  print, as JSON, the exercises LAB's page lists (nothing is built)`;
const siteDir = path.dirname(fileURLToPath(import.meta.url));
const repo = path.resolve(siteDir, '..');
const args = process.argv.slice(2);
const die = (why) => { console.error(`make_site: ${why}`); process.exit(2); };
if (args.includes('--help') || args.includes('-h')) { console.log(usage); process.exit(0); }
const options = {};
for (let i = 0; i < args.length; i++) {
  if (!['--out', '--student', '--exercises'].includes(args[i])) die(`unknown argument '${args[i]}'\n${usage}`);
  if (i + 1 >= args.length) die(`${args[i]} needs a value`);
  options[args[i].slice(2)] = args[++i];
}
const started = performance.now();
const labsIn = (dir) => fs.readdirSync(dir).filter((d) => /^lab\d+_\w+$/.test(d) && fs.existsSync(path.join(dir, d, 'CMakeLists.txt')))
  .sort((a, b) => parseInt(a.slice(3), 10) - parseInt(b.slice(3), 10));

// ---------------------------------------------------------------- the edition and its source tree
let student = null;  // the lab number of the student edition
let root = repo;     // where the pages' sources are read
let cleanup = () => {};
if (options.exercises !== undefined) {  // what a lab page's table lists (tests/exercise_tools_agree.py)
  console.log(JSON.stringify(exercisesOf(options.exercises), null, 1));
  process.exit(0);
}
if (options.student !== undefined) {
  if (fs.existsSync(path.join(repo, '.student-copy'))) die('this is a student copy: the student edition is built from the complete project');
  student = studentLab(options.student, labsIn(repo));
  if (student === null) die(`--student ${options.student}: no such lab; the labs are: ${labsIn(repo).join(' ')}`);
  ({ tree: root, cleanup } = prepareStudentTree(repo, labsIn(repo).find((l) => parseInt(l.slice(3), 10) === student), student));
}
process.on('exit', () => cleanup());
const out = path.resolve(options.out ?? path.join(repo, student ? `build/site-student-lab${student}` : 'build/site'));
const read = (p) => fs.readFileSync(path.join(root, p), 'utf8');
const exists = (p) => fs.existsSync(path.join(root, p));
const posix = path.posix;
const SITE = 'Vulkan labs';

// A fresh output folder: only one this script wrote (it has pages.json), or an empty one, is replaced.
if (fs.existsSync(out) && (!fs.statSync(out).isDirectory() || fs.readdirSync(out).length && !fs.existsSync(path.join(out, 'pages.json')))) {
  die(`${out} is not a folder this script built (nor an empty one): not touching it`);
}
fs.rmSync(out, { recursive: true, force: true });
fs.mkdirSync(out, { recursive: true });

// ---------------------------------------------------------------- what becomes a page
const labs = labsIn(root);
const labNumber = (lab) => parseInt(lab.slice(3), 10);
const diffs = labs.slice(1).map((b, i) => ({ a: labs[i], b, file: `docs/diffs/${labs[i]}-${b}.diff` }))
  .filter((d) => exists(d.file));
// The Markdown of a page, as the edition shows it (the student edition: without later labs).
const markdownText = new Map();
const markdown = (source) => {
  if (!markdownText.has(source)) markdownText.set(source, student ? laterLabText(read(source), student) : read(source));
  return markdownText.get(source);
};
const pageOf = new Map([['README.md', 'readme.html'], ['docs/diffs/README.md', 'diffs.html'],
  ['docs/diffs/lessons.md', 'lessons.html'], ['docs/performance.md', 'performance.html'],
  ['docs/tradeoffs.md', 'tradeoffs.html']]);
for (const lab of labs) if (exists(`${lab}/README.md`)) pageOf.set(`${lab}/README.md`, `${lab}.html`);
const docs = fs.readdirSync(path.join(root, 'docs')).filter((f) => f.endsWith('.md')).sort().map((f) => `docs/${f}`);
// The instructors' answers (docs/solutions/, which copies and so the student editions leave out).
if (exists('docs/solutions')) {
  docs.push(...fs.readdirSync(path.join(root, 'docs/solutions')).filter((f) => f.endsWith('.md')).sort().map((f) => `docs/solutions/${f}`));
}
for (const doc of docs) if (!pageOf.has(doc)) pageOf.set(doc, posix.basename(doc).replace(/\.md$/, '.html'));
for (const lab of labs) {
  if (exists(`docs/images/${lab}/README.md`)) pageOf.set(`docs/images/${lab}/README.md`, `gallery-${lab}.html`);
}
for (const d of diffs) pageOf.set(d.file, `diff-${d.a}-${d.b}.html`);
for (const [source] of [...pageOf]) {  // gone from this edition, or nothing left of it
  if (source.endsWith('.md') && (!exists(source) || !hasBody(markdown(source)))) pageOf.delete(source);
}

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
const isBinary = (p) => /\.(png|jpe?g|gif|svg|webp|spv|bin|ktx2?)$/i.test(p);
const isDir = (p) => fs.existsSync(path.join(root, p)) && fs.statSync(path.join(root, p)).isDirectory();
const warnings = [];
const filesUnder = (dir) => (isDir(dir) ? fs.readdirSync(path.join(root, dir), { withFileTypes: true }).flatMap((e) =>
  e.isDirectory() ? filesUnder(`${dir}/${e.name}`) : [`${dir}/${e.name}`]) : []).sort();
// Every file of a lab's folder and its shader folder gets a page (its README is the lab's page).
const labFiles = new Map(labs.map((lab) => [lab, [...filesUnder(lab), ...filesUnder(`shaders/${lab}`)]
  .filter((f) => f !== `${lab}/README.md`)]));

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
  if (csv && pageOf.has('docs/tradeoffs.md')) return `tradeoffs.html#data-${csv[1]}`;
  if (!exists(repoPath) || repoPath.endsWith('.md')) return null;  // a Markdown file without a page: gone from this edition
  if (isBinary(repoPath)) return copyIn(repoPath);
  sourcePages.set(repoPath, `src/${repoPath}.html`);
  return `src/${repoPath}.html${hash}`;
}
for (const files of labFiles.values()) for (const f of files) siteTarget(f, '');

// ---------------------------------------------------------------- Markdown
const katex = katexModule.default ?? katexModule;
const md = new MarkdownIt({ html: true })
  .use(katex, { enableFencedBlocks: true })
  .use(anchor, { tabIndex: false, slugifyWithState: (title, state) => state.env.slugger.slug(title) });

// Links and pictures point into the site: relative to the page, not to the Markdown file. A link
// to what this edition does not have becomes its text; a picture not inside a link opens full size.
md.core.ruler.push('site_links', (state) => {
  const { source, page } = state.env;
  if (!source) return;  // renderInline of a manifest line: no links to fix
  const fix = (token, attr) => {
    const url = token.attrGet(attr);
    if (!url || /^[a-z][a-z0-9+.-]*:/i.test(url) || url.startsWith('#')) return true;
    const [file, hash = ''] = url.split('#');
    const repoPath = posix.normalize(posix.join(posix.dirname(source), decodeURIComponent(file)));
    const target = siteTarget(repoPath, hash ? `#${hash}` : '');
    if (target === null) {
      if (!student) warnings.push(`${source} links to ${url}, which does not exist`);
      return false;
    }
    token.attrSet(attr, relative(page, target));
    return true;
  };
  for (const block of state.tokens) {
    const children = block.children ?? [];
    const open = [];  // link_open tokens, and whether each was kept
    for (let i = 0; i < children.length; i++) {
      const t = children[i];
      if (t.type === 'link_open') {
        const kept = fix(t, 'href');
        open.push(kept);
        if (!kept) children.splice(i--, 1);
      } else if (t.type === 'link_close') {
        if (!open.pop()) children.splice(i--, 1);
      } else if (t.type === 'image') {
        if (!fix(t, 'src')) { children.splice(i--, 1); continue; }
        if (open.length === 0) t.meta = { ...t.meta, fullSize: true };
      }
    }
  }
});
const renderImage = md.renderer.rules.image;
md.renderer.rules.image = (tokens, idx, opts, env, self) => {
  const html = renderImage(tokens, idx, opts, env, self);
  return tokens[idx].meta?.fullSize ? `<a class="full-size" href="${esc(tokens[idx].attrGet('src'))}">${html}</a>` : html;
};
function renderMarkdown(source, page) {
  const env = { source, page, slugger: new GithubSlugger() };
  const tokens = md.parse(markdown(source), env);
  const h1 = tokens.findIndex((t) => t.type === 'heading_open' && t.tag === 'h1');
  const title = h1 >= 0 ? tokens[h1 + 1].content : source;
  return { html: md.renderer.render(tokens, md.options, env), title };
}
const titleOf = (source) => (/^# (.*)$/m.exec(markdown(source))?.[1] ?? source).replace(/`/g, '');

// ---------------------------------------------------------------- the page frame
const docPages = docs.filter((d) => pageOf.has(d) && !['performance.html', 'tradeoffs.html'].includes(pageOf.get(d)));
const nav = [...labs.map((lab) => [`${lab}.html`, `lab ${labNumber(lab)}`]),
  ...(diffs.length ? [['diffs.html', 'diffs']] : []), ['docs.html', 'docs'], ['gallery.html', 'gallery'],
  ...(pageOf.has('docs/performance.md') ? [['performance.html', 'performance']] : [])];
const edition = student ? `Student edition for lab ${student}: labs 1–${student}, lab ${student}'s exercises cut out as in your copy` : null;
const pages = [];
function writePage(page, { title, body, section = null, source = null, wide = false, scripts = [], prev = null, next = null }) {
  const html = framePage(page, { site: SITE, title, body, nav, section, source, wide, scripts, prev, next, edition });
  fs.mkdirSync(path.dirname(path.join(out, page)), { recursive: true });
  fs.writeFileSync(path.join(out, page), html);
  pages.push({ page, title, source });
}
function markdownPage(source, section, { extra = '', prev = null, next = null } = {}) {
  if (!pageOf.has(source)) return;
  const page = pageOf.get(source);
  const { html, title } = renderMarkdown(source, page);
  writePage(page, { title, body: html + extra, section, source, prev, next });
}
// Lab pages chain lab 1 → lab N; a lab's diff and gallery sit between their labs.
const labLink = (lab) => (lab ? { href: `${lab}.html`, label: titleOf(`${lab}/README.md`) } : null);
const labAt = (i) => labs[i] ?? null;

// ---------------------------------------------------------------- labs and their exercises
// A lab's exercises as its table shows them: `exercise.py --list --json LAB` (the markers, read by
// scripts/course/exercises.py): [{ name, lab, file, line, hint, tests }], in the README's order.
function exercisesOf(lab) {
  const listing = execFileSync('python3', [path.join(root, 'scripts/exercise.py'), '--list', '--json', lab], { cwd: root, encoding: 'utf8' });
  return JSON.parse(listing).map((e) => ({ ...e, hint: e.hint.trim() }));
}
const fileList = (page, files) => `<ul class="files">\n${files.map((f) =>
  `<li><a href="${relative(page, sourcePages.get(f))}"><code>${esc(f)}</code></a></li>`).join('\n')}\n</ul>`;
labs.forEach((lab, i) => {
  const page = `${lab}.html`;
  const n = labNumber(lab);
  const diff = diffs.find((d) => d.b === lab);
  const gallery = pageOf.get(`docs/images/${lab}/README.md`);
  const facts = [
    diff ? `<a href="${pageOf.get(diff.file)}">the lesson as a diff: ${diff.a} → ${lab}</a>` : n === 1 ? 'the first lab: no diff before it' : 'its lesson diff: in the instructors\' edition only (it shows this lab\'s answers)',
    gallery ? `<a href="${gallery}">its gallery</a>` : 'no gallery yet',
    '<a href="#graded-exercises">its graded exercises</a>', '<a href="#the-files">its files</a>',
    exists(`docs/tradeoffs/${lab}.csv`) && pageOf.has('docs/tradeoffs.md') ? `<a href="tradeoffs.html#data-${lab}">its time-against-error data</a>` : null,
  ].filter(Boolean);
  const exercises = exercisesOf(lab);
  let table = `<h2 id="graded-exercises">Graded exercises</h2>\n`;
  if (exercises.length === 0) {
    table += `<p>Lab ${n} has no graded exercises of its own (<code>bash scripts/exercise.sh --list ${n}</code> lists none).</p>`;
  } else {
    table += `<p>From <code>bash scripts/exercise.sh --list ${n}</code>: ${student === n
      ? 'your copy has these cut out (each a <code>TODO EXERCISE</code> line: the links go to it)'
      : `<code>bash scripts/exercise.sh ${n}</code> writes a copy with these cut out`}, and <code>ctest --test-dir build -L lab${n}</code>
in it is the grader: the tests named here fail until the exercise is done.</p>
<div class="table-scroll"><table class="exercises"><thead><tr><th>exercise, where</th><th>hint</th><th>graded by</th></tr></thead><tbody>
${exercises.map((e) => `<tr><td><code>${esc(e.name)}</code><br><a href="${siteTarget(e.file, `#L${e.line}`)}">${esc(e.file)}:${e.line}</a></td>` +
  `<td>${esc(e.hint)}</td><td>${e.tests.map((t) => `<code>${esc(t)}</code>`).join('<br>')}</td></tr>`).join('\n')}
</tbody></table></div>`;
  }
  const files = labFiles.get(lab);
  table += `\n<h2 id="the-files">The files</h2>
<p>Lab ${n}'s folder and its shaders, each as a page with line numbers${diff ? ` (what changed since lab ${labNumber(diff.a)}: <a href="${pageOf.get(diff.file)}">the diff</a>)` : ''}.</p>
${fileList(page, files)}`;
  const { html, title } = renderMarkdown(`${lab}/README.md`, page);
  const box = `<aside class="lab-facts">Lab ${n}: ${facts.join(' · ')}</aside>\n`;
  const body = html.replace(/(<\/h1>\n)/, `$1${box}`) + table;
  writePage(page, { title, body, section: page, source: `${lab}/README.md`,
    prev: i === 0 ? { href: 'index.html', label: 'The course' } : labLink(labAt(i - 1)), next: labLink(labAt(i + 1)) });
});

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
// A changed file side by side; a new file whole, in one column (nothing on the left to compare).
const diffConfig = { outputFormat: 'side-by-side', drawFileList: false, matching: 'lines', colorScheme: 'light' };
const newFileConfig = { ...diffConfig, outputFormat: 'line-by-line' };
for (const d of diffs) {
  const page = pageOf.get(d.file);
  const files = Diff2Html.parse(read(d.file), diffConfig);
  const entries = manifestEntries(d.b);
  const sections = files.map((file, i) => {
    const e = entries.find((x) => x.path === file.newName) ?? { n: i + 1, path: file.newName, guide: '(not in the manifest)' };
    const isNew = file.oldName === '/dev/null';
    const from = isNew ? ' <span class="tag">new</span>' : e.from ? ` <small>← <code>${esc(e.from)}</code></small>` : '';
    const whole = sourcePages.has(e.path) ? ` <a class="whole" href="${sourcePages.get(e.path)}">the whole file</a>` : '';
    return `<section class="lesson-file${isNew ? ' new-file' : ''}" id="file-${e.n}" data-path="${esc(e.path)}">
<h2>${e.n}. <code>${esc(e.path)}</code>${from}${whole}</h2>
<div class="guide">${md.renderInline(e.guide)}</div>
<div class="lesson-diff">${Diff2Html.html([file], isNew ? newFileConfig : diffConfig)}</div>
</section>`;
  });
  const toc = files.map((f, i) => {
    const e = entries.find((x) => x.path === f.newName) ?? { n: i + 1 };
    return `<li><a href="#file-${e.n}"><code>${esc(f.newName)}</code></a> <span class="stat">+${f.addedLines} −${f.deletedLines}</span></li>`;
  }).join('\n');
  const body = `<h1>${d.a} → ${d.b}: the lesson, in reading order</h1>
<p>Lab ${labNumber(d.b)} is lab ${labNumber(d.a)} plus this lesson: the files it adds or changes, in the order of the manifest
${pageOf.has('docs/diffs/lessons.md') ? `<a href="lessons.html#${d.b}">docs/diffs/lessons.md</a>` : 'docs/diffs/lessons.md'}, each with its reading guide; a new file is shown whole.
Every other file of the lab is lab ${labNumber(d.a)}'s, byte for byte; <a href="${d.b}.html">the lab's README</a> explains in prose.${
  student === labNumber(d.b) ? ` Lab ${student}'s exercises are cut out here as in your copy.` : ''}</p>
<ol class="toc">\n${toc}\n</ol>\n${sections.join('\n')}`;
  writePage(page, { title: `${d.a} → ${d.b}`, body, section: 'diffs.html', source: d.file, wide: true,
    scripts: ['assets/diff2html/diff2html-ui.min.js', 'assets/diff.js'], prev: labLink(d.a), next: labLink(d.b) });
}
const diffList = `<h2 id="the-diffs">The diffs</h2>\n<ul>\n${diffs.map((d) =>
  `<li><a href="${pageOf.get(d.file)}">${d.a} → ${d.b}</a>: ${manifestEntries(d.b).length} files</li>`).join('\n')}\n</ul>`;
if (pageOf.has('docs/diffs/README.md')) markdownPage('docs/diffs/README.md', 'diffs.html', { extra: diffList });
else if (diffs.length) {
  writePage('diffs.html', { title: 'The lesson diffs', section: 'diffs.html', body: `<h1>The lesson diffs</h1>
<p>Lab N+1 is lab N plus one lesson: each diff shows the files the lesson adds or changes, in reading order, with a guide above each
(<a href="lessons.html">the manifest</a>).</p>\n${diffList}` });
}
markdownPage('docs/diffs/lessons.md', 'diffs.html');

// ---------------------------------------------------------------- galleries
const galleryCards = labs.map((lab, i) => {
  const readme = `docs/images/${lab}/README.md`;
  if (!pageOf.has(readme)) {
    return `<section class="gallery-card"><h2 id="${lab}">Lab ${labNumber(lab)}: ${lab}</h2>
<p class="none">No gallery yet: <code>${readme}</code> does not exist.</p></section>`;
  }
  markdownPage(readme, 'gallery.html', { prev: labLink(lab), next: labLink(labAt(i + 1)) });
  const thumb = exists(`docs/images/${lab}/default.png`) ? `<img src="${copyIn(`docs/images/${lab}/default.png`)}" alt="${lab}, default scene">` : '';
  return `<section class="gallery-card"><h2 id="${lab}">Lab ${labNumber(lab)}: ${lab}</h2>
<a href="${pageOf.get(readme)}">${thumb}<br>The pictures lab ${labNumber(lab)} must render, with their captions</a></section>`;
});
writePage('gallery.html', { title: 'Galleries', section: 'gallery.html', body: `<h1>Galleries</h1>
<p>Each lab's expected pictures, rendered headless by the lab itself (a ground truth beside them by the CPU reference; <code>bash scripts/make_gallery.sh</code>; the tests
<code>gallery_labN</code> fail when a lab no longer renders them).</p>
<div class="gallery-cards">${galleryCards.join('\n')}</div>` });

// ---------------------------------------------------------------- performance: time against error
const plots = !pageOf.has('docs/tradeoffs.md') ? [] : fs.readdirSync(path.join(root, 'docs/tradeoffs'))
  .filter((f) => /^lab\d+_\w+\.csv$/.test(f) && labs.includes(f.replace(/\.csv$/, ''))).sort();
const plotSections = plots.map((csvName) => {
  const name = csvName.replace(/\.csv$/, '');
  const rows = parseCsv(read(`docs/tradeoffs/${csvName}`), { columns: false, skip_empty_lines: true });
  const [head, ...body] = rows;
  const col = (c) => head.indexOf(c);
  const tr = body.map((r) => `<tr class="${r[col('on_front')] === 'yes' ? 'front' : ''}${r[col('default')] === 'yes' ? ' default' : ''}">` +
    r.map((v) => `<td${/^-?[\d.]+$/.test(v) ? ' class="num"' : ''}>${esc(v)}</td>`).join('') + '</tr>').join('\n');
  const png = `docs/tradeoffs/${name}.png`;
  return `<section class="plot" id="data-${name}"><h3>${name}</h3>
${exists(png) ? `<a class="full-size" href="${copyIn(png)}" title="open the plot full size"><img src="${png}" alt="${name}: time against error"></a>
<p class="hint">The plot full size: click it.</p>` : '<p class="none">No plot yet.</p>'}
<p>The data (<a href="${copyIn(`docs/tradeoffs/${csvName}`)}">${csvName}</a>): ${body.length} configurations; green rows are on the
Pareto front, the bold one is the lab's default.</p>
<div class="table-scroll"><table class="csv"><thead><tr>${head.map((h) => `<th>${esc(h)}</th>`).join('')}</tr></thead>
<tbody>\n${tr}\n</tbody></table></div></section>`;
});
markdownPage('docs/performance.md', 'performance.html');
markdownPage('docs/tradeoffs.md', 'performance.html', { extra: `<h2 id="the-plots-and-their-data">The plots and their data</h2>\n${plotSections.join('\n')}` });

// ---------------------------------------------------------------- the README, the docs
markdownPage('README.md', null);
for (const doc of docPages) if (doc !== 'docs/performance.md' && doc !== 'docs/tradeoffs.md') markdownPage(doc, 'docs.html');
const docItems = [['README.md'], ...docs.filter((d) => pageOf.has(d)).map((d) => [d])].filter(([d]) => pageOf.has(d))
  .map(([d]) => `<li><a href="${pageOf.get(d)}">${esc(titleOf(d))}</a> <small><code>${esc(d)}</code></small></li>`);
writePage('docs.html', { title: 'Docs', section: 'docs.html', body: `<h1>Docs</h1>
<p>What every lab shares and how the project is checked: the repository's README and every page of <code>docs/</code>.</p>
<ul class="doc-list">\n${docItems.join('\n')}\n</ul>` });

// ---------------------------------------------------------------- the landing page
const readme = read('README.md');
const commands = /## Two commands[^\n]*\n[\s\S]*?```sh\n([\s\S]*?)```/.exec(readme)?.[1]
  ?? 'bash scripts/run.sh    # installs packages, builds, runs the newest lab\nbash scripts/test.sh   # builds and runs the tests\n';
const teaches = (lab) => new RegExp(`^\\| \\[${lab}\\]\\([^)]*\\) \\| (.*) \\|$`, 'm').exec(readme)?.[1] ?? '';
const cards = labs.map((lab) => {
  const picture = exists(`docs/images/${lab}/default.png`) ? `<img src="${copyIn(`docs/images/${lab}/default.png`)}" alt="what lab ${labNumber(lab)} renders">` : '';
  const diff = diffs.find((d) => d.b === lab);
  return `<li class="lab-card"><a class="picture" href="${lab}.html">${picture}</a>
<div><h3><a href="${lab}.html">${esc(titleOf(`${lab}/README.md`))}</a></h3>
<p>${esc(teaches(lab))}</p>
<p class="more"><a href="${lab}.html">the lesson</a>${diff ? ` · <a href="${pageOf.get(diff.file)}">the diff from lab ${labNumber(diff.a)}</a>` : ''}${
  pageOf.has(`docs/images/${lab}/README.md`) ? ` · <a href="${pageOf.get(`docs/images/${lab}/README.md`)}">the pictures it must render</a>` : ''}</p></div></li>`;
});
const getCode = student
  ? `<p>You work in the <strong>student copy of lab ${student}</strong> your instructor hands out (written by
<code>bash scripts/exercise.sh lab${student}</code>): common/, the labs before lab ${student} complete, and lab ${student} with its exercises cut out.
Each exercise is a <code>TODO EXERCISE</code> line with a hint; <code>ctest --test-dir build -L lab${student} --output-on-failure</code> grades them.</p>`
  : `<p>Everything is in this repository: clone it (or unpack the archive you were given) on Debian 12. For a class,
<code>bash scripts/exercise.sh lab1</code> writes a student copy with lab 1's exercises cut out, and
<code>bash scripts/make_site.sh --student 1</code> this site without any answer (<a href="${pageOf.has('docs/solutions.md') ? 'solutions.html' : 'docs.html'}">what to hand out when</a>).</p>`;
writePage('index.html', { title: `${SITE} — a step-by-step course in C++`, section: null, source: null,
  next: labLink(labs[0]), body: `<h1>${SITE} — a step-by-step course in C++</h1>
<p class="lead">Real-time rendering with Vulkan, one small program per lab on one shared framework. Each lab is the previous one
plus one lesson — cameras, lighting, textures, shadows — so the difference from one lab to the next <em>is</em> the lesson:
read its README, read its diff, do its exercises, and the tests tell you when they are right.</p>
<p><a class="start" href="${labs[0]}.html">Start with lab 1 →</a></p>
<h2 id="get-the-code">Get the code</h2>
${getCode}
<h2 id="build-and-run">Build and run</h2>
<p>Two commands on a fresh Debian 12 (they install the packages they need, then build):</p>
<pre><code>${esc(commands)}</code></pre>
<p>No display? Each lab then writes its picture to <code>out/&lt;lab&gt;.png</code>. More in <a href="readme.html">the README</a>.</p>
<h2 id="the-labs">The labs, in order</h2>
<ol class="lab-cards">\n${cards.join('\n')}\n</ol>
<h2 id="also">Also here</h2>
<ul>
${diffs.length ? '<li><a href="diffs.html">the lesson diffs</a>: each lab as the change from the one before</li>' : ''}
<li><a href="docs.html">the docs</a>: conventions, architecture, scene format, testing</li>
<li><a href="gallery.html">the galleries</a>: what each lab must render</li>
${pageOf.has('docs/performance.md') ? '<li><a href="performance.html">performance</a>: what each lab costs, and its time against error</li>' : ''}
</ul>` });

// ---------------------------------------------------------------- pages that show a file or a folder
const owner = (repoPath) => labs.find((lab) => repoPath.startsWith(`${lab}/`) || repoPath.startsWith(`shaders/${lab}/`));
for (const [repoPath, page] of [...sourcePages]) {  // folders first add their files to the list
  if (!isDir(repoPath)) continue;
  const items = fs.readdirSync(path.join(root, repoPath)).sort().map((f) => {
    const target = siteTarget(`${repoPath}/${f}`, '');
    return target === null ? '' : `<li><a href="${relative(page, target)}"><code>${esc(f)}</code></a></li>`;
  });
  writePage(page, { title: `${repoPath}/`, body: `<h1><code>${esc(repoPath)}/</code></h1>\n<ul>\n${items.join('\n')}\n</ul>` });
}
for (const [repoPath, page] of sourcePages) {
  if (isDir(repoPath)) continue;
  const lab = owner(repoPath);
  const siblings = lab ? labFiles.get(lab) : [];
  const at = siblings.indexOf(repoPath);
  const fileLink = (f) => (f ? { href: sourcePages.get(f), label: f.split('/').pop() } : null);
  const about = lab ? `A file of <a href="${relative(page, `${lab}.html`)}">lab ${labNumber(lab)}</a> (${at + 1} of ${siblings.length}).` : '';
  writePage(page, { title: repoPath, section: lab ? `${lab}.html` : null, source: repoPath, body: sourceBody(repoPath, read(repoPath), about),
    prev: lab ? fileLink(siblings[at - 1]) : null, next: lab ? fileLink(siblings[at + 1]) : null });
}

// ---------------------------------------------------------------- assets, the page list
const assets = [['site/style.css', 'assets/style.css'], ['site/diff.js', 'assets/diff.js'],
  ['site/node_modules/katex/dist/katex.min.css', 'assets/katex/katex.min.css'],
  ['site/node_modules/highlight.js/styles/github.min.css', 'assets/hljs/github.min.css'],
  ['site/node_modules/diff2html/bundles/css/diff2html.min.css', 'assets/diff2html/diff2html.min.css'],
  ['site/node_modules/diff2html/bundles/js/diff2html-ui.min.js', 'assets/diff2html/diff2html-ui.min.js']];
for (const [from, to] of assets) {
  fs.mkdirSync(path.dirname(path.join(out, to)), { recursive: true });
  fs.copyFileSync(path.join(repo, from), path.join(out, to));
}
fs.cpSync(path.join(repo, 'site/node_modules/katex/dist/fonts'), path.join(out, 'assets/katex/fonts'), { recursive: true });
const labFilePages = Object.fromEntries([...labFiles].map(([lab, files]) => [lab, files.map((f) => sourcePages.get(f))]));
fs.writeFileSync(path.join(out, 'edition.json'), JSON.stringify({ student, labs, labFilePages }, null, 1) + '\n');
fs.writeFileSync(path.join(out, 'pages.json'), JSON.stringify(pages, null, 1) + '\n');
for (const w of warnings) console.error(`make_site: warning: ${w}`);
console.log(`make_site: ${student ? `student edition of lab ${student}, ` : ''}${pages.length} pages in ${out} (${((performance.now() - started) / 1000).toFixed(1)} s)`);
