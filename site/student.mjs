// site/student.mjs — the student edition's source tree and its rule for text about later labs.
//
// The student edition of lab N is built from a real student copy (`scripts/exercise.sh labN --out
// TMP`): common/, labs 1..N-1 complete, lab N with its exercises stubbed, no later lab, no
// docs/diffs/, no site/, no docs/solutions* (instructor material). Into that copy go:
//   - docs/diffs/lessons.md with the sections of labs 2..N-1 only, and the diffs made from it by the
//     copy's own scripts/make_diffs.sh: the lessons of the labs before N, whose answers are no secret
//     once lab N is handed out. Not the diff into lab N: its reading guides state lab N's answers
//     (lessons.md is the instructors' manifest), and lab N's README and files are the lesson.
//   The copy's Markdown has its answer spans replaced by their questions (exercise.sh runs
//   scripts/check_answers.py --rewrite), so the pages show the questions.
//
// Later labs in the text (laterLabText): a Markdown section whose heading mentions a later lab is
// left out together with the sections under it; elsewhere each block that mentions one is left out
// alone — a paragraph, a list item (with its indented lines), a table row, a fenced block — and the
// rest of its section stays. "Mentions" means a lab number above N ("lab 3", "Lab 3", "lab3",
// "labs 2-4", "lab3_textures", a picture named lab3_…). A page whose title mentions one is no page,
// nor is a page left with no text.
//
// The student copy trims alike: scripts/exercise.sh runs this file on the copy it writes, last of
// its Markdown steps (`node site/student.mjs --trim-later-labs COPY N`: trimLaterLabs below), so the
// copy's pages lose the sections its student site leaves out, by this one rule (the site, built from
// the copy, then finds nothing more to drop: the rule is idempotent). `--check-later-labs COPY N`
// (exercise.sh --check-copy) names each page of a copy that still holds such a section.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';

// The lab number a student edition is for: 1 | lab1 | lab1_camera → 1 (labs: folder names in order).
export function studentLab(want, labs) {
  const m = /^(?:lab)?(\d+)(?:_\w+)?$/.exec(String(want));
  const lab = m && labs.find((l) => parseInt(l.slice(3), 10) === parseInt(m[1], 10) && (!/_/.test(want) || l === want));
  if (!lab) return null;
  return parseInt(lab.slice(3), 10);
}

// Writes the student copy of lab n into a fresh temporary folder and returns its path.
export function prepareStudentTree(root, lab, n) {
  const tmp = fs.mkdtempSync(path.join(os.tmpdir(), `site-student-lab${n}-`));
  const tree = path.join(tmp, 'copy');
  const run = (what, cmd, cwd) => {
    try { execFileSync('bash', cmd, { cwd, stdio: ['ignore', 'ignore', 'inherit'] }); } catch {
      fs.rmSync(tmp, { recursive: true, force: true });
      console.error(`make_site: ${what} failed (bash ${cmd.join(' ')}): no student edition`);
      process.exit(1);
    }
  };
  run('the student copy', [path.join(root, 'scripts/exercise.sh'), lab, '--out', tree], root);
  // The manifest, cut to the labs before lab n; the copy's make_diffs.sh writes their diffs.
  const kept = [];
  let keep = true;
  for (const line of fs.readFileSync(path.join(root, 'docs/diffs/lessons.md'), 'utf8').split('\n')) {
    const m = /^## lab(\d+)_/.exec(line);
    if (m) keep = parseInt(m[1], 10) < n;
    if (keep) kept.push(line);
  }
  fs.mkdirSync(path.join(tree, 'docs/diffs'), { recursive: true });
  fs.writeFileSync(path.join(tree, 'docs/diffs/lessons.md'), kept.join('\n'));
  if (kept.some((l) => /^## lab\d+_/.test(l))) run('the lesson diffs of the copy', [path.join(tree, 'scripts/make_diffs.sh')], tree);
  // make_diffs.sh writes a diff (empty: no section) into every lab the copy has: not the one into lab n.
  for (const f of fs.readdirSync(path.join(tree, 'docs/diffs'))) {
    const m = /-lab(\d+)_\w+\.diff$/.exec(f);
    if (m && parseInt(m[1], 10) >= n) fs.rmSync(path.join(tree, 'docs/diffs', f));
  }
  return { tree, cleanup: () => fs.rmSync(tmp, { recursive: true, force: true }) };
}

// Does a piece of text name a lab after n?
export function mentionsLaterLab(text, n) {
  const numbers = [];
  for (const m of text.matchAll(/\blabs?[ _-]?(\d+)(?:\s*(?:-|–|—|to|and|,|…|\.\.)\s*(\d+))*/gi)) {
    for (const x of m[0].matchAll(/\d+/g)) numbers.push(parseInt(x[0], 10));
  }
  return numbers.some((k) => k > n);
}

// The blocks of a section's body lines: paragraphs, list items with their indented lines, table
// rows, fenced blocks (whole), blank lines (each its own block).
function blocks(lines) {
  const out = [];
  let fence = null;
  for (const line of lines) {
    const f = /^\s*(```|~~~)/.exec(line);
    const last = out[out.length - 1];
    if (fence !== null) {
      last.push(line);
      if (f && f[1] === fence) fence = null;
      continue;
    }
    if (f) { fence = f[1]; out.push([line]); continue; }
    const blank = line.trim() === '';
    const starts = blank || /^\s*\|/.test(line) || /^\s*([-*+]|\d+[.)])\s/.test(line) || /^\s*<!--/.test(line);
    const continues = last && !blank && last[0].trim() !== '' && !/^\s*```|^\s*~~~/.test(last[0]) && !/^\s*\|/.test(last[0]);
    if (!starts && continues) last.push(line);
    else if (/^\s+\S/.test(line) && last && last[0].trim() !== '' && /^\s*([-*+]|\d+[.)])\s/.test(last[0]) && !blank) last.push(line);
    else out.push([line]);
  }
  return out;
}

// The Markdown text without its text about later labs (the rule at the top of this file).
export function laterLabText(text, n) {
  const lines = text.split('\n');
  const sections = [];  // { level, lines }: a heading line and its body
  let fence = null;
  for (const line of lines) {
    const f = /^\s*(```|~~~)/.exec(line);
    if (f) fence = fence === null ? f[1] : fence === f[1] ? null : fence;
    const h = fence === null && !f && /^(#{1,6}) /.exec(line);
    if (h || sections.length === 0) sections.push({ level: h ? h[1].length : 0, lines: [] });
    sections[sections.length - 1].lines.push(line);
  }
  const kept = [];
  let droppedAt = Infinity;  // the level of a dropped heading: its subsections go with it
  for (const s of sections) {
    if (s.level > droppedAt) continue;
    droppedAt = Infinity;
    const heading = s.level > 0 ? s.lines[0] : null;
    if (heading !== null && mentionsLaterLab(heading, n)) {
      if (s.level === 1) return '';  // the page is about a later lab
      droppedAt = s.level;
      continue;
    }
    if (heading !== null) kept.push(heading);
    const body = blocks(heading !== null ? s.lines.slice(1) : s.lines);
    for (const b of body) if (!mentionsLaterLab(b.join('\n'), n)) kept.push(...b);
  }
  return kept.join('\n');
}

// Has the Markdown more than its title?
export function hasBody(text) {
  return text.split('\n').some((l) => l.trim() !== '' && !/^# /.test(l));
}

// The Markdown files of a tree that the student edition shows as pages, laterLabText applied
// (site/build.mjs, pageOf): the top README, each lab's README, docs/*.md, each gallery's README and
// docs/diffs/'s README and lessons.md (the site's own: not in a copy). Paths relative to root.
export function studentPages(root) {
  const labs = fs.readdirSync(root).filter((d) => /^lab\d+_\w+$/.test(d) && fs.existsSync(path.join(root, d, 'CMakeLists.txt')));
  const docs = fs.existsSync(path.join(root, 'docs')) ? fs.readdirSync(path.join(root, 'docs')).filter((f) => f.endsWith('.md')).map((f) => `docs/${f}`) : [];
  return ['README.md', 'docs/diffs/README.md', 'docs/diffs/lessons.md', ...labs.map((l) => `${l}/README.md`), ...docs,
    ...labs.map((l) => `docs/images/${l}/README.md`)]
    .filter((f, i, all) => all.indexOf(f) === i && fs.existsSync(path.join(root, f)) && fs.statSync(path.join(root, f)).isFile()).sort();
}

// Applies laterLabText to every page of a student copy of lab n, in place (a page that keeps only
// its title keeps its file: links to it still resolve). Returns the pages it changed.
export function trimLaterLabs(root, n) {
  const changed = [];
  for (const page of studentPages(root)) {
    const file = path.join(root, page);
    const text = fs.readFileSync(file, 'utf8');
    const trimmed = laterLabText(text, n);
    if (trimmed !== text) {
      fs.writeFileSync(file, trimmed);
      changed.push(page);
    }
  }
  return changed;
}

// The pages of a student copy of lab n that still hold a section about a later lab.
export function untrimmedPages(root, n) {
  return studentPages(root).filter((page) => {
    const text = fs.readFileSync(path.join(root, page), 'utf8');
    return laterLabText(text, n) !== text;
  });
}

// The command line (scripts/exercise.sh): node site/student.mjs --trim-later-labs | --check-later-labs DIR N
if (process.argv[1] && path.resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const [mode, dir, lab] = process.argv.slice(2);
  const n = /^(?:lab)?(\d+)(?:_\w+)?$/.exec(lab ?? '');
  if (!['--trim-later-labs', '--check-later-labs'].includes(mode) || !dir || !fs.existsSync(dir) || !n) {
    console.error('usage: node site/student.mjs --trim-later-labs | --check-later-labs COPY_DIR N');
    process.exit(2);
  }
  if (mode === '--trim-later-labs') {
    const changed = trimLaterLabs(dir, parseInt(n[1], 10));
    console.log(`student.mjs: ${changed.length} page(s) of ${dir} without their sections about labs after ${n[1]}${changed.length ? `: ${changed.join(' ')}` : ''}`);
  } else {
    const left = untrimmedPages(dir, parseInt(n[1], 10));
    for (const page of left) console.log(`FAIL ${page}: a section that names a lab after ${n[1]} (the student site leaves it out: site/student.mjs, laterLabText)`);
    process.exit(left.length ? 1 : 0);
  }
}
