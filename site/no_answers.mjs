// site/no_answers.mjs — no page of a student edition holds an answer (CTest site_student_no_answers).
//
//   node site/no_answers.mjs --out DIR [--labs 1,2,3,4] [--and-instructors]
//                                                            # build and check the student edition of each lab;
//                                                            # with --and-instructors the instructors' edition
//                                                            # too, where check_answers.py must find each lab's
//                                                            # declared answers (CTest: the check can fail)
//   node site/no_answers.mjs --out DIR --instructors N       # the instructors' edition against lab N's answers:
//                                                            # it must report hits (the check can fail)
//
// For lab N, the answers are `bash scripts/exercise.sh --solution-lines --json labN`: the substantive lines of
// the solutions of lab N's and every later lab's exercises, without whitespace. Every file of the
// built edition that a browser shows as text (*.html, *.js, *.json, *.md, *.txt, *.csv, source
// files) is read as the reader sees it — tags stripped, HTML entities decoded, whitespace removed,
// the way exercise.sh compares — and may not contain any of them. Exit 0: no answer anywhere;
// 1: answers found (each named: page, exercise, where the solution line is); 2: bad arguments;
// Each student edition must also pass scripts/check_answers.py DIR N: no answer of lab N or later in
// any of the forms docs/solutions/answers.json declares (a formula in prose, an enum, a phrase, a
// test's expected value), read as the page shows it (tags stripped, entities decoded, KaTeX and
// Unicode signs normalised).
// 77: skipped (site/node_modules missing, or this is a student copy), with one line saying why.
import fs from 'node:fs';
import path from 'node:path';
import { spawnSync, execFileSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';

const siteDir = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(siteDir, '..');
const args = process.argv.slice(2);
const usage = 'usage: node site/no_answers.mjs --out DIR [--labs 1,2,3,4 | --instructors N]';
const opt = (name) => (args.includes(name) ? args[args.indexOf(name) + 1] : undefined);
const skip = (why) => { console.log(`site_student_no_answers: SKIPPED: ${why}`); process.exit(77); };
if (args.includes('--help')) { console.log(usage); process.exit(0); }
if (!opt('--out')) { console.error(`site_student_no_answers: --out DIR is missing\n${usage}`); process.exit(2); }
if (fs.existsSync(path.join(root, '.student-copy'))) skip('this is a student copy: the site is built from the complete project');
if (!fs.existsSync(path.join(siteDir, 'node_modules/entities'))) skip('site/node_modules is missing (scripts/setup.sh runs `npm ci` in site/)');
const { decodeHTML } = await import('entities');

const out = path.resolve(opt('--out'));
const labs = fs.readdirSync(root).filter((d) => /^lab\d+_\w+$/.test(d) && fs.existsSync(path.join(root, d, 'CMakeLists.txt')))
  .sort((a, b) => parseInt(a.slice(3), 10) - parseInt(b.slice(3), 10));
const instructors = opt('--instructors');
const wanted = instructors ? [Number(instructors)] : (opt('--labs') ?? labs.map((l) => parseInt(l.slice(3), 10)).join(',')).split(',').map(Number);
for (const n of wanted) {
  if (!labs.some((l) => parseInt(l.slice(3), 10) === n)) { console.error(`site_student_no_answers: no lab ${n} here\n${usage}`); process.exit(2); }
}

const textFile = /\.(html|js|json|md|txt|csv|h|cpp|glsl|vert|frag|comp|sh|py|cmake)$/i;
const files = (dir) => fs.readdirSync(dir, { withFileTypes: true }).flatMap((e) =>
  e.isDirectory() ? files(path.join(dir, e.name)) : textFile.test(e.name) ? [path.join(dir, e.name)] : []);
// What a reader sees of a file, without whitespace: HTML without its tags, entities decoded.
const seen = (file) => {
  let text = fs.readFileSync(file, 'utf8');
  if (file.endsWith('.html')) text = decodeHTML(text.replace(/<script[\s\S]*?<\/script>|<style[\s\S]*?<\/style>/gi, '').replace(/<[^>]*>/g, ''));
  return text.replace(/\s+/g, '');
};

let failed = 0;
for (const n of wanted) {
  const lab = labs.find((l) => parseInt(l.slice(3), 10) === n);
  const dir = path.join(out, instructors ? 'instructors' : `student-lab${n}`);
  fs.rmSync(dir, { recursive: true, force: true });
  const built = spawnSync(process.execPath, [path.join(siteDir, 'build.mjs'), '--out', dir, ...(instructors ? [] : ['--student', String(n)])],
    { encoding: 'utf8' });
  if (built.status !== 0) { console.log(`FAIL the ${instructors ? "instructors'" : `lab ${n} student`} edition did not build:\n${built.stderr}`); failed++; continue; }
  const answers = JSON.parse(execFileSync('python3', [path.join(root, 'scripts/exercise.py'), '--solution-lines', '--json', lab],
    { cwd: root, encoding: 'utf8' }));  // [{ name, where, code }]
  if (answers.length === 0) { console.log(`FAIL exercise.sh --solution-lines ${lab} gave no lines: nothing to look for`); failed++; continue; }
  const pages = files(dir);
  let hits = 0;
  for (const file of pages) {
    const text = seen(file);
    for (const a of answers) {
      if (!text.includes(a.code)) continue;
      hits++;
      if (hits <= 20) console.log(`FAIL ${path.relative(dir, file)} shows a line of exercise ${a.name} (${a.where}): ${a.code}`);
    }
  }
  if (hits > 20) console.log(`… and ${hits - 20} more`);
  if (!instructors) {  // the declared answers (formulas, enums, phrases), in every text file of the edition
    const declared = spawnSync('python3', [path.join(root, 'scripts/check_answers.py'), dir, String(n)], { encoding: 'utf8' });
    process.stdout.write(declared.stdout + declared.stderr);
    if (declared.status !== 0) { hits++; console.log(`FAIL the student edition of lab ${n} states declared answers (check_answers.py)`); }
  }
  const what = instructors ? "the instructors' edition" : `the student edition of lab ${n}`;
  console.log(`${what}: ${pages.length} text files, ${answers.length} answer lines of ${lab} and later, ${hits} found`);
  if (hits) failed++;
}
if (args.includes('--and-instructors') && !instructors) {  // the check can fail: the instructors' edition states every answer
  const dir = path.join(out, 'instructors');
  fs.rmSync(dir, { recursive: true, force: true });
  const built = spawnSync(process.execPath, [path.join(siteDir, 'build.mjs'), '--out', dir], { encoding: 'utf8' });
  if (built.status !== 0) { console.log(`FAIL the instructors' edition did not build:\n${built.stderr}`); failed++; }
  else {
    for (const n of wanted) {
      const found = spawnSync('python3', [path.join(root, 'scripts/check_answers.py'), '--must-find', dir, String(n)], { encoding: 'utf8' });
      console.log(`the instructors' edition, lab ${n}'s answers and later: ${found.stdout.trim().split('\n').pop()}`);
      if (found.status !== 0) { console.log(`FAIL check_answers.py finds no answer of lab ${n} in the instructors' edition: it cannot fail`); failed++; }
    }
  }
}
if (failed) { console.log(`site_student_no_answers: FAILED (${failed} edition(s) with answers or not built)`); process.exit(1); }
console.log('site_student_no_answers: passed');
