// tests/site_check_fails.mjs — site/check.mjs (CTest site_browser) can fail: it reads every page as
// HTML and opens only a sample in Chromium, so this breaks built editions in the ways the browser-
// only check caught, most of them on pages the sample leaves out, and requires check.mjs to fail
// naming each broken page (CTest site_check_can_fail, label common).
//
//   node tests/site_check_fails.mjs [--work DIR] [--from DIR]
//
// It builds the instructors' edition and the student edition of lab 1 into DIR (default
// build/site-check-fails; --from DIR: copies DIR and DIR-student-lab1, e.g. site_browser's build/site,
// instead of building), asks check.mjs which pages it would open (--plan), breaks a copy of each
// edition, and runs check.mjs on each copy (--instructors, --student 1). Each breakage must be
// reported, naming its page; any other problem reported must name a broken page or file (nothing
// else of the edition fails). Exit 0: every breakage caught; 1: one was not (or a false alarm);
// 77: skipped, as check.mjs skips (no site/node_modules, no Chromium), with one line saying why.
import fs from 'node:fs';
import path from 'node:path';
import { spawnSync, spawn } from 'node:child_process';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const args = process.argv.slice(2);
if (args.includes('--help') || args.includes('-h')) {
  console.log('usage: node tests/site_check_fails.mjs [--work DIR] [--from DIR]   (CTest site_check_can_fail)');
  process.exit(0);
}
const opt = (name, fallback) => (args.includes(name) ? path.resolve(args[args.indexOf(name) + 1]) : fallback);
const work = opt('--work', path.join(root, 'build/site-check-fails'));
const from = opt('--from', null);
const check = path.join(root, 'site/check.mjs');
const started = performance.now();
if (!fs.existsSync(path.join(root, 'site/node_modules/playwright-core'))) {
  console.log('site_check_can_fail: SKIPPED: site/node_modules is missing (scripts/setup.sh runs `npm ci` in site/)');
  process.exit(77);
}
if (fs.existsSync(path.join(root, '.student-copy'))) { console.log('site_check_can_fail: SKIPPED: a student copy has no site'); process.exit(77); }

// ---------------------------------------------------------------- the two editions, pristine
const pristine = { instructors: path.join(work, 'pristine'), student: path.join(work, 'pristine-student-lab1') };
fs.rmSync(work, { recursive: true, force: true });
fs.mkdirSync(work, { recursive: true });
const build = (dir, extra) => new Promise((resolve) => {
  const child = spawn(process.execPath, [path.join(root, 'site/build.mjs'), '--out', dir, ...extra], { stdio: ['ignore', 'inherit', 'inherit'] });
  child.on('exit', (code) => { if (code !== 0) { console.log(`site_check_can_fail: FAILED: ${dir} did not build`); process.exit(1); } resolve(); });
});
if (from) {
  for (const [to, src] of [[pristine.instructors, from], [pristine.student, `${from}-student-lab1`]]) {
    if (!fs.existsSync(path.join(src, 'pages.json'))) { console.log(`site_check_can_fail: FAILED: ${src} holds no built site`); process.exit(1); }
    fs.cpSync(src, to, { recursive: true });
  }
} else {
  await Promise.all([build(pristine.instructors, []), build(pristine.student, ['--student', '1'])]);
}
const built = performance.now();

// ---------------------------------------------------------------- helpers
const runCheck = (dir, edition, extra = []) => spawnSync(process.execPath,
  [check, '--out', dir, ...(edition === 'student' ? ['--student', '1'] : ['--instructors']), ...extra],
  { encoding: 'utf8', maxBuffer: 64 << 20 });
function plan(dir, edition) {
  const r = runCheck(dir, edition, ['--plan']);
  if (r.status === 77) { console.log(r.stdout.trim()); process.exit(77); }
  if (r.status !== 0) { console.log(`site_check_can_fail: FAILED: check.mjs --plan failed:\n${r.stdout}${r.stderr}`); process.exit(1); }
  return new Set([...r.stdout.matchAll(/^ {2}(?:open|http) (\S+):/gm)].map((m) => m[1]));
}
const htmlFiles = (dir) => fs.readdirSync(dir, { withFileTypes: true }).flatMap((e) =>
  e.isDirectory() ? htmlFiles(path.join(dir, e.name)) : e.name.endsWith('.html') ? [path.join(dir, e.name)] : []);
const rel = (dir, f) => path.relative(dir, f).split(path.sep).join('/');
const escape = (s) => s.replace(/[.*+?^${}()|[\]\\]/g, '\\$&');

// Breaks a copy of an edition: each breakage { what, page, edit(dir), expect: RegExp over one
// problem line, involves: [names a problem line may carry] }.
function breakCopy(edition, breakages) {
  const dir = path.join(work, edition === 'student' ? 'broken-student-lab1' : 'broken');
  fs.cpSync(pristine[edition], dir, { recursive: true });
  for (const b of breakages) b.edit(dir);
  return dir;
}
const edit = (dir, page, change) => {
  const file = path.join(dir, page);
  const before = fs.readFileSync(file, 'utf8');
  const after = change(before);
  if (after === before) throw new Error(`the breakage of ${page} changed nothing`);
  fs.writeFileSync(file, after);
};
const intoMain = (html, what) => html.replace(/<main class="[^"]*">\n/, (m) => `${m}${what}\n`);
const upTo = (page, target) => path.posix.relative(path.posix.dirname(page), target);

let failed = 0;
function verify(edition, dir, breakages) {
  const t = performance.now();
  const r = runCheck(dir, edition, ['--times']);
  const took = ((performance.now() - t) / 1000).toFixed(1);
  if (r.status === 77) { console.log(r.stdout.trim()); process.exit(77); }
  const lines = r.stdout.split('\n').filter((l) => /^ {2}\S/.test(l) && /\((instructors|student lab \d+)[,)]/.test(l));
  console.log(`\n${edition === 'student' ? 'the student edition of lab 1' : "the instructors' edition"}, broken in ${breakages.length} ways: check.mjs exit ${r.status} in ${took} s, ${lines.length} problem line(s)`);
  if (r.status !== 1) { console.log(`FAIL check.mjs should have failed (exit 1), it exited ${r.status}:\n${r.stdout}${r.stderr}`); failed++; }
  for (const b of breakages) {
    const hit = lines.find((l) => b.expect.test(l));
    if (hit) console.log(`  caught  ${b.what}\n          ${hit.trim().slice(0, 220)}`);
    else { console.log(`  MISSED  ${b.what} (${b.page}): no problem line matches ${b.expect}`); failed++; }
  }
  const names = breakages.flatMap((b) => [b.page, ...(b.involves ?? [])]);
  for (const l of lines) {
    if (!names.some((n) => l.includes(n))) { console.log(`  FALSE ALARM (names no broken page or file): ${l.trim()}`); failed++; }
  }
}

// ---------------------------------------------------------------- the instructors' edition
{
  const opened = plan(pristine.instructors, 'instructors');
  const pages = htmlFiles(pristine.instructors).map((f) => rel(pristine.instructors, f)).sort();
  // Source pages of the labs that check.mjs does not open: the breakages below that need no browser go there.
  const unopened = pages.filter((p) => /^src\/lab\d+_\w+\/[^/]+\.(cpp|h|txt)\.html$/.test(p) && !opened.has(p));
  if (unopened.length < 9) { console.log(`site_check_can_fail: FAILED: only ${unopened.length} unopened source pages to break`); process.exit(1); }
  const [a, b, c, d, e, f, g, h, i] = unopened;
  const gallery = 'gallery-lab2_lighting.html';
  const pictures = [...fs.readFileSync(path.join(pristine.instructors, gallery), 'utf8').matchAll(/<img src="(docs\/images\/lab2_lighting\/[^"]+\.png)"/g)].map((m) => m[1]);
  const [gone, garbled] = pictures.slice(-2);
  const lab3Files = pages.filter((p) => p.startsWith('src/lab3_textures/') && !opened.has(p));
  const lost = lab3Files[Math.floor(lab3Files.length / 2)];
  const breakages = [
    { what: 'a dangling link on an unopened source page', page: a,
      edit: (dir) => edit(dir, a, (s) => intoMain(s, '<p><a href="no-such-page.html">gone</a></p>')),
      expect: new RegExp(`^ {2}${escape(a)} \\(instructors\\): link no-such-page\\.html → .*no-such-page\\.html: no such file`) },
    { what: 'a link to a missing anchor on an unopened source page', page: b,
      edit: (dir) => edit(dir, b, (s) => intoMain(s, `<p><a href="${upTo(b, 'index.html')}#no-such-anchor">here</a></p>`)),
      expect: new RegExp(`^ {2}${escape(b)} \\(instructors\\): link .*index\\.html#no-such-anchor: index\\.html has no #no-such-anchor`) },
    { what: 'a picture loaded from another origin on an unopened source page', page: c,
      edit: (dir) => edit(dir, c, (s) => intoMain(s, '<p><img src="https://example.com/pixel.png" alt=""></p>')),
      expect: new RegExp(`^ {2}${escape(c)} \\(instructors\\): <img> asks another origin for https://example\\.com/pixel\\.png`) },
    { what: 'a navigation bar without "docs" on an unopened source page', page: d,
      edit: (dir) => edit(dir, d, (s) => s.replace(/\n\s*<a href="[./]*docs\.html">docs<\/a>/, '')),
      expect: new RegExp(`^ {2}${escape(d)} \\(instructors\\): navigation bar is "Vulkan labs \\| lab 1 .*diffs \\| gallery`) },
    { what: 'raw $…$ math in the text of an unopened source page', page: e,
      edit: (dir) => edit(dir, e, (s) => intoMain(s, '<p>The area is $\\pi r^2$.</p>')),
      expect: new RegExp(`^ {2}${escape(e)} \\(instructors\\): raw math left in the text: \\$\\\\pi r\\^2\\$`) },
    { what: 'a console error from a script on a source page the sample left out (the script gets it opened)', page: f,
      edit: (dir) => edit(dir, f, (s) => s.replace('</body>', "<script>console.error('planted error')</script>\n</body>")),
      expect: new RegExp(`^ {2}${escape(f)} \\(instructors, file\\): console error: planted error`) },
    { what: 'an uncaught exception on an opened page', page: 'docs.html',
      edit: (dir) => edit(dir, 'docs.html', (s) => s.replace('</body>', "<script>throw new Error('planted exception')</script>\n</body>")),
      expect: /^ {2}docs\.html \(instructors, file\): uncaught exception: planted exception/ },
    { what: 'a page wider than 390 px (a long word in the text of an opened page, no markup of its own)', page: 'readme.html',
      edit: (dir) => edit(dir, 'readme.html', (s) => intoMain(s, `<p>${'unbreakable'.repeat(12)}</p>`)),
      expect: /^ {2}readme\.html \(instructors, file\): \d+ px wide at a 390 px width \(first too wide: <p>unbreakableunbreakable/ },
    { what: 'a page wider than 390 px by markup, on a source page the sample left out (its style attribute gets it opened)', page: i,
      edit: (dir) => edit(dir, i, (s) => intoMain(s, '<div style="width: 800px">a wide box</div>')),
      expect: new RegExp(`^ {2}${escape(i)} \\(instructors, file\\): \\d+ px wide at a 390 px width \\(first too wide: <div style="width: 800px">`) },
    { what: 'a missing picture (deleted from the site)', page: gallery, involves: [gone],
      edit: (dir) => fs.rmSync(path.join(dir, gone)),
      expect: new RegExp(`^ {2}${escape(gallery)} \\(instructors\\): <img> ${escape(gone)}: no such file in the site`) },
    { what: 'a picture that does not decode', page: gallery, involves: [garbled],
      edit: (dir) => fs.writeFileSync(path.join(dir, garbled), 'not a PNG at all'),
      expect: new RegExp(`^ {2}\\S+ \\(instructors\\): picture ${escape(garbled)} does not decode`) },
    { what: 'a diff page whose scripts do not run (no colouring)', page: 'diff-lab1_camera-lab2_lighting.html',
      edit: (dir) => edit(dir, 'diff-lab1_camera-lab2_lighting.html', (s) => s.replace('<script src="assets/diff.js"></script>', '')),
      expect: /^ {2}diff-lab1_camera-lab2_lighting\.html \(instructors\): file 1 \(.*\): no syntax colouring/ },
    { what: 'a diff page with two files out of the manifest\'s order', page: 'diff-lab2_lighting-lab3_textures.html',
      edit: (dir) => edit(dir, 'diff-lab2_lighting-lab3_textures.html', (s) => {
        const sections = [...s.matchAll(/<section class="lesson-file[\s\S]*?<\/section>\n/g)];
        const [one, two] = sections;
        return s.slice(0, one.index) + two[0] + one[0] + s.slice(two.index + two[0].length);
      }),
      expect: /^ {2}diff-lab2_lighting-lab3_textures\.html \(instructors\): files are not the manifest's, in its order/ },
    { what: 'a lab file without its page', page: 'lab3_textures.html', involves: [lost, 'pages.json lists it'],
      edit: (dir) => fs.rmSync(path.join(dir, lost)),
      expect: new RegExp(`^ {2}lab3_textures\\.html \\(instructors\\): ${escape(lost.replace(/^src\//, '').replace(/\.html$/, ''))} has no page`) },
    { what: 'lab 2\'s "next" link skipping lab 3', page: 'lab2_lighting.html', involves: ['lab1_camera.html', 'lab4_shadows.html'],
      edit: (dir) => edit(dir, 'lab2_lighting.html', (s) => s.replace(/<a rel="next" href="lab3_textures\.html">/, '<a rel="next" href="lab4_shadows.html">')),
      expect: /^ {2}lab1_camera\.html \(instructors\): "next" chains lab1_camera\.html → lab2_lighting\.html → lab4_shadows\.html/ },
    { what: 'a link to a dangling line anchor in a source page, from an unopened source page', page: g,
      edit: (dir) => edit(dir, g, (s) => intoMain(s, `<p><a href="${upTo(g, h)}#L99999">far</a></p>`)),
      expect: new RegExp(`^ {2}${escape(g)} \\(instructors\\): link .*#L99999: ${escape(h)} has no #L99999`) },
  ];
  verify('instructors', breakCopy('instructors', breakages), breakages);
}

// ---------------------------------------------------------------- the student edition of lab 1
{
  const opened = plan(pristine.student, 'student');
  const pages = htmlFiles(pristine.student).map((f) => rel(pristine.student, f)).sort();
  const unopened = pages.filter((p) => p.startsWith('src/') && !p.endsWith('/index.html') && !opened.has(p));
  if (unopened.length < 2) { console.log(`site_check_can_fail: FAILED: only ${unopened.length} unopened source pages in the student edition`); process.exit(1); }
  const [a, b] = unopened;
  const later = 'docs/images/lab2_lighting/default.png';
  const breakages = [
    { what: 'a later lab named in the text of an unopened source page', page: a,
      edit: (dir) => edit(dir, a, (s) => intoMain(s, '<p>Next week, lab 2 adds the lights.</p>')),
      expect: new RegExp(`^ {2}${escape(a)} \\(student lab 1\\): names a later lab in its text: ".*lab 2 adds the lights`) },
    { what: 'a later lab\'s picture shown on an unopened source page', page: b,
      edit: (dir) => {
        fs.mkdirSync(path.join(dir, path.dirname(later)), { recursive: true });
        fs.copyFileSync(path.join(dir, 'docs/images/lab1_camera/default.png'), path.join(dir, later));
        edit(dir, b, (s) => intoMain(s, `<p><img src="${upTo(b, later)}" alt="lab 2"></p>`));
      },
      expect: new RegExp(`^ {2}${escape(b)} \\(student lab 1\\): links a later lab's file: .*${escape(later)}`) },
    { what: 'docs/solutions.md as a page of the student edition', page: 'solutions.html',
      edit: (dir) => {
        fs.copyFileSync(path.join(dir, 'conventions.html'), path.join(dir, 'solutions.html'));
        const list = JSON.parse(fs.readFileSync(path.join(dir, 'pages.json'), 'utf8'));
        list.push({ page: 'solutions.html', title: 'Solutions', source: 'docs/solutions.md' });
        fs.writeFileSync(path.join(dir, 'pages.json'), JSON.stringify(list, null, 1));
      },
      expect: /^ {2}solutions\.html \(student lab 1\): docs\/solutions\.md has a page in a student edition/ },
    { what: 'a console error on an opened page of the student edition', page: 'index.html',
      edit: (dir) => edit(dir, 'index.html', (s) => s.replace('</body>', "<script>console.error('planted student error')</script>\n</body>")),
      expect: /^ {2}index\.html \(student lab 1, file\): console error: planted student error/ },
  ];
  verify('student', breakCopy('student', breakages), breakages);
}

const took = ((performance.now() - started) / 1000).toFixed(1);
console.log(`\nsite_check_can_fail: ${failed ? `FAILED (${failed})` : 'passed'} in ${took} s (editions ${from ? 'copied' : 'built'} in ${((built - started) / 1000).toFixed(1)} s)`);
process.exit(failed ? 1 : 0);
