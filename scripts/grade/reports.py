"""reports.py — what a grade is written as: grades.csv, each student's results.json (the JSON
Gradescope-style autograders read) and report.html, and the class's index.html."""
import collections
import csv
import html
import io
import json
import os
import re

from sandbox import WORK

STUDENTS = "students"          # each student's report is in OUT/students/NAME/ (any name is safe there)


def compiler_errors(text):
    lines = [l.replace(WORK + "/", "") for l in text.splitlines()]
    errs = [l for l in lines if re.search(r"error|ERROR", l) and "make" not in l.split(":")[0]]
    return "\n".join((errs or lines[-15:])[:15])



def write_outputs(g, subs, out):
    names = [e["name"] for e in g.exercises]
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["student", *names, "score", "notes"])
    for s in subs:
        w.writerow([s.name, *[s.grades.get(n, 0) for n in names], sum(s.grades.get(n, 0) for n in names), "; ".join(s.notes)])
    with open(os.path.join(out, "grades.csv"), "w") as f:
        f.write(buf.getvalue())
    for s in subs:
        d = os.path.join(out, STUDENTS, s.name)
        os.makedirs(d, exist_ok=True)
        whole_ok = sorted(t for t, r in (s.whole or {}).get("tests", {}).items() if r["status"] == "ok")
        res = {"score": sum(s.grades.get(n, 0) for n in names),
               "max_score": len(names),
               "output": (f"{len(whole_ok)} of {len(g.all_tests)} graded tests pass with the code as handed in. " if s.whole else "") +
                         ("; ".join(s.notes)),
               "tests": [{"name": n, "score": s.grades.get(n, 0), "max_score": 1, "output": s.messages.get(n, "")} for n in names]}
        with open(os.path.join(d, "results.json"), "w") as f:
            json.dump(res, f, indent=2)
            f.write("\n")
        with open(os.path.join(d, "report.html"), "w") as f:
            f.write(report_html(g, s))
    with open(os.path.join(out, "index.html"), "w") as f:
        f.write(index_html(g, subs))


CSS = """body{font:14px/1.45 system-ui,sans-serif;margin:24px;color:#1d232b;max-width:1200px}
h1{font-size:22px}h2{font-size:17px;margin-top:28px}table{border-collapse:collapse;margin:8px 0}
td,th{border:1px solid #ccd3db;padding:4px 8px;text-align:left;vertical-align:top}th{background:#eef2f6}
.p{background:#d9f2df}.f{background:#f8d7d7}.m{color:#5a6573}pre{background:#f5f7f9;border:1px solid #dde3e9;padding:8px;
white-space:pre-wrap;font-size:12px;max-height:420px;overflow:auto}img{max-width:100%;border:1px solid #ccd3db;margin:4px 0}
.ex{border:1px solid #ccd3db;border-radius:6px;padding:4px 14px;margin:14px 0}.badge{font-weight:600;padding:1px 8px;border-radius:4px}
a{color:#0b5cad}"""


def page(title, body):
    return (f"<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{html.escape(title)}</title>"
            f"<style>{CSS}</style></head><body>\n{body}\n</body></html>\n")


def report_html(g, s):
    e_ = html.escape
    names = [e["name"] for e in g.exercises]
    score = sum(s.grades.get(n, 0) for n in names)
    b = [f"<h1>{e_(g.lab)}: {e_(s.name)} — {score} / {len(names)}</h1>", "<p><a href=\"../../index.html\">← class summary</a></p>"]
    if s.notes:
        b.append("<p><b>Notes:</b> " + e_("; ".join(s.notes)) + "</p>")
    whole = (s.whole or {}).get("tests", {})
    for e in g.exercises:
        n = e["name"]
        ok = s.grades.get(n, 0)
        b.append(f"<div class=\"ex\"><h2><span class=\"badge {'p' if ok else 'f'}\">{ok}</span> {e_(n)} "
                 f"<span class=\"m\">{e_(e['file'])}{':' + str(s.line[n]) if n in s.line else ''}</span></h2>")
        b.append(f"<pre>{e_(s.messages.get(n, ''))}</pre>")
        if n in s.code:
            b.append(f"<details><summary>the student's code for {e_(n)}</summary><pre>{e_(s.code[n])}</pre></details>")
        r = s.isolated.get(n)
        if r and r.get("tests"):
            b.append("<table><tr><th>test</th><th>this exercise alone</th><th>as handed in</th></tr>")
            for t in e["tests"]:
                st = r["tests"].get(t, {}).get("status", "—")
                wst = whole.get(t, {}).get("status", "—" if not s.whole or s.whole["build"] == "ok" else "did not compile")
                b.append(f"<tr><td>{e_(t)}</td><td class=\"{'p' if st == 'ok' else 'f'}\">{e_(st)}</td>"
                         f"<td class=\"{'p' if wst == 'ok' else 'f'}\">{e_(wst)}</td></tr>")
            b.append("</table>")
            for t in e["tests"]:
                for pic in s.kept.get((n, t), []):
                    b.append(f"<p>{e_(t)} — expected | actual | difference:<br><img src=\"{e_(pic)}\" alt=\"{e_(t)}\"></p>")
        b.append("</div>")
    if s.outside:
        b.append("<h2>Changed outside the exercises (ignored by the grade)</h2><ul>" +
                 "".join(f"<li>{e_(p)}</li>" for p in s.outside[:200]) + "</ul>")
    return page(f"{s.name}: {g.lab}", "\n".join(b))


def first_message(msg):
    """The line of a message that says most (the hint's blame first), numbers as # to group alike ones."""
    lines = msg.splitlines()
    for want in ("[ exercise ]", "does not compile", "not done", "not graded", "Failure"):
        for l in lines:
            if want in l:
                return re.sub(r"(?<![A-Za-z_])\d+(\.\d+)?", "#", l.strip())[:160]
    return lines[0][:160] if lines else ""


def index_html(g, subs):
    e_ = html.escape
    names = [e["name"] for e in g.exercises]
    b = [f"<h1>{e_(g.lab)}: class summary, {len(subs)} submissions</h1>"]
    b.append("<h2>Per exercise</h2><table><tr><th>exercise</th><th>passed</th><th>most common failing tests</th><th>most common messages</th></tr>")
    for e in g.exercises:
        n = e["name"]
        passed = sum(s.grades.get(n, 0) for s in subs)
        tests, msgs = collections.Counter(), collections.Counter()
        for s in subs:
            if s.grades.get(n, 0) or s.fatal:
                continue
            for t, r in (s.isolated.get(n) or {}).get("tests", {}).items():
                if r["status"] != "ok":
                    tests[t] += 1
            msgs[first_message(s.messages.get(n, ""))] += 1
        top = lambda c: "<br>".join(f"{k} <span class=\"m\">×{v}</span>" for k, v in sorted(c.items(), key=lambda kv: (-kv[1], kv[0]))[:3])
        b.append(f"<tr><td>{e_(n)}</td><td>{passed} / {len(subs)}</td><td>{top(collections.Counter({e_(k): v for k, v in tests.items()}))}</td>"
                 f"<td>{top(collections.Counter({e_(k): v for k, v in msgs.items() if k}))}</td></tr>")
    b.append("</table><h2>Students</h2><table><tr><th>student</th>" + "".join(f"<th>{e_(n)}</th>" for n in names) +
             "<th>score</th><th>notes</th></tr>")
    for s in subs:
        cells = "".join(f"<td class=\"{'p' if s.grades.get(n, 0) else 'f'}\">{s.grades.get(n, 0)}</td>" for n in names)
        b.append(f"<tr><td><a href=\"{STUDENTS}/{e_(s.name)}/report.html\">{e_(s.name)}</a></td>{cells}"
                 f"<td>{sum(s.grades.get(n, 0) for n in names)}</td><td>{e_('; '.join(s.notes))}</td></tr>")
    b.append("</table>")
    return page(f"{g.lab} grades", "\n".join(b))
