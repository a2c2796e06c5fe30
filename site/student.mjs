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
// Later labs in the text (laterLabText): a Markdown section — a heading and its text up to the next
// heading — that mentions a later lab is left out together with the sections under it. "Mentions"
// means a lab number above N ("lab 3", "Lab 3", "lab3", "labs 2-4", "lab3_textures", a picture
// named lab3_…). The top heading's own intro counts as a section, the rest of the page stays. A page
// left with no text is no page. Simple and on the safe side: a section that names lab N+1 in passing
// goes too.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';

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

// The Markdown text without its sections about later labs (the rule at the top of this file).
export function laterLabText(text, n) {
  const lines = text.split('\n');
  const sections = [];  // { level, lines }
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
    if (!mentionsLaterLab(s.lines.join('\n'), n)) { kept.push(...s.lines); continue; }
    if (s.level <= 1) {  // the page's title (or the text before it): keep the heading line alone
      if (s.level === 1 && !mentionsLaterLab(s.lines[0], n)) kept.push(s.lines[0], '');
      else if (s.level === 1) return '';
      continue;
    }
    droppedAt = s.level;
  }
  return kept.join('\n');
}

// Has the Markdown more than its title?
export function hasBody(text) {
  return text.split('\n').some((l) => l.trim() !== '' && !/^# /.test(l));
}
