#!/usr/bin/env python3
"""Every report kind says the same on the terminal, in --json and on its page.

Usage: report_agreement.py SPREAD LOOKUP_BUILDER SOURCE_DIR WORK_DIR

For each kind — calibrate tray (at a given bout, at the bout it judges itself, failing, with the bout's
trays missing), the quick check, calibrate pattern, predict and chart — the command is run once with
--report (its text on the terminal, its page read back with poppler's pdftotext) and once with --json,
and it is required that
  - the verdicts (word and text) are the same three times, in the same order: the terminal's lines
    "WORD  text", the JSON's `verdicts`, the page's first lines;
  - every number with a unit on the page (%, m, m², g, kg/ha, rpm, km/h, deg) is a number of the JSON at
    the precision shown (the footer, the command line, and the date aside);
  - no CV above the target is printed onto or below it (15.05 % is not "15.0 %" against 15 %).
Prints "PASS: ..." or "FAIL: ..." lines (exit 1).
"""
import json
import os
import re
import shlex
import subprocess
import sys

WORDS = ("PASS", "MARGINAL", "FAIL", "NO CV")
TERMINAL_VERDICT = re.compile(r"^(PASS|MARGINAL|FAIL|NO CV) {2,}(\S.*)$")
PAGE_VERDICT = re.compile(r"^\s*(PASS|MARGINAL|FAIL|NO CV)\s{2,}\S")
NUMBER_WITH_UNIT = re.compile(
    r"(?<![\w.])([+-]?\d+(?:\.\d+)?)(?:-(\d+(?:\.\d+)?))?\s?(%|m²|kg/ha|km/h|rpm|deg|m|g)(?![\w/²])")


def run(argv, cwd):
    return subprocess.run(argv, cwd=cwd, capture_output=True, text=True,
                          env=dict(os.environ, SOURCE_DATE_EPOCH="1764000000"))


def collapse(text):
    return " ".join(text.split())


def json_numbers(value, out):
    if isinstance(value, bool) or value is None:
        return out
    if isinstance(value, (int, float)):
        out.append(float(value))
    elif isinstance(value, dict):
        for v in value.values():
            json_numbers(v, out)
    elif isinstance(value, list):
        for v in value:
            json_numbers(v, out)
    return out


def shown_matches(shown, numbers):
    decimals = len(shown.split(".")[1]) if "." in shown else 0
    x = float(shown)
    half = 0.5 * 10 ** -decimals + 1e-9
    # A magnitude may be printed with its direction in words ("28.6 % less" for -28.6) or its sign.
    return any(abs(v - x) <= half or abs(abs(v) - abs(x)) <= half for v in numbers)


def page_body(text):
    """The page's text without the footer (the command line and time), the date and the data file."""
    body = []
    for page in text.split("\f"):
        kept = []
        for line in page.splitlines():
            if line.strip().startswith("made by:"):
                break
            line = re.sub(r"date \d{4}-\d{2}-\d{2}", "", line)
            if line.strip().startswith("Data:"):
                continue
            kept.append(line)
        body.append("\n".join(kept))
    return "\n".join(body)


def check(kind, report_run, json_run, pdf, problems):
    if report_run.returncode != 0 or json_run.returncode != 0:
        problems.append(f"{kind}: exit {report_run.returncode} / {json_run.returncode}: {report_run.stderr}{json_run.stderr}")
        return
    data = json.loads(json_run.stdout)
    layout = run(["pdftotext", "-layout", pdf, "-"], ".").stdout
    raw = run(["pdftotext", pdf, "-"], ".").stdout
    terminal = [m.groups() for m in map(TERMINAL_VERDICT.match, report_run.stdout.splitlines()) if m]
    from_json = [(v["word"], v["text"]) for v in data.get("verdicts", [])]
    on_page = [m.group(1) for m in map(PAGE_VERDICT.match, layout.splitlines()) if m]
    if not from_json:
        problems.append(f"{kind}: no verdicts in --json")
    if terminal != from_json:
        problems.append(f"{kind}: terminal verdicts {terminal} differ from --json {from_json}")
    if on_page != [w for w, _ in from_json]:
        problems.append(f"{kind}: the page's verdict words {on_page} differ from --json {[w for w, _ in from_json]}")
    page_text = collapse(raw)
    for word, text in from_json:
        if collapse(text) not in page_text:
            problems.append(f"{kind}: the page does not state the verdict '{word}  {text}'")
    numbers = json_numbers(data, [])
    body = page_body(layout)
    checked = 0
    for match in NUMBER_WITH_UNIT.finditer(body):
        for shown in filter(None, match.group(1, 2)):
            checked += 1
            if not shown_matches(shown, numbers):
                line = next(l for l in body.splitlines() if match.group(0) in l)
                problems.append(f"{kind}: '{shown} {match.group(3)}' on the page is not in --json: {line.strip()}")
    target = data.get("cv_target_percent")
    if target is not None:
        for curve_point in data.get("cv_curve", []):
            cv = curve_point.get("cv_to_and_fro_percent")
            if cv is not None and target < cv < target + 0.05:
                shown = f"{cv:.1f}"
                if float(shown) <= target and re.search(rf"(?<![\d.]){re.escape(shown)} %", body):
                    problems.append(f"{kind}: the CV {cv} above the target {target} is shown as {shown} %")
    return checked


def make_reports(spread, builder, source, work):
    """Every report kind, made twice: {kind: (run with --report, run with --json, the PDF's path)}, or a
    string saying why they could not be made."""
    os.makedirs(work, exist_ok=True)
    example = os.path.join(source, "scenes/field/tray_test_3passes.csv")
    quick = os.path.join(source, "scenes/field/quick_check_5trays.csv")
    table = os.path.join(work, "urea.sqlite")
    if os.path.exists(table):
        os.remove(table)
    made = run([builder, os.path.join(source, "scenes/default.toml"), "--output", table,
                "--set", "sweep.source=analytic", "--set", 'sweep.materials=["Urea"]',
                "--set", "sweep.samples_per_run=256", "--set", "inlet.radius_m=0.0145",
                "--set", "inlet.offset_m=0.1", "--set", "inlet.angle_rad=1.0"], work)
    if made.returncode != 0:
        return f"lookup_builder: {made.stderr}"
    # The example with the trays of its middle 10.5 m missing: no CV at a 10 m bout.
    with open(example, encoding="utf-8") as f:
        rows = [l.rstrip("\n") for l in f if not l.startswith("#")]
    missing = os.path.join(work, "missing.csv")
    with open(missing, "w", encoding="utf-8") as f:
        f.write(rows[0] + "\n")
        for row in rows[1:]:
            x = float(row.split(",")[0])
            f.write((f"{row.split(',')[0]},NA,NA,NA" if abs(x) < 5.3 else row) + "\n")
    header = "--machine 'Twin disc' --material Urea --rpm 600 --speed 12"
    kinds = {
        "tray": f"calibrate tray {example} --width 3.5 {header} --tray-area 0.25 --rate-kg-ha 850",
        "tray_judged": f"calibrate tray {example}",
        "tray_fail": f"calibrate tray {example} --width 6 --tray-area 0.25 --rate-kg-ha 400",
        "tray_missing": f"calibrate tray {missing} --width 10",
        "quick_check": f"calibrate tray {quick} --quick-check --tray-area 0.25 --rate-kg-ha 400 --speed 12",
        "pattern": f"calibrate pattern --tables {table} --material Urea --rpm 600 --trays {example} "
                   "--output {output} --fit friction,drag --samples 128 --width 3.5 --tray-area 0.25 --rate-kg-ha 850",
        "predict": f"predict --tables {table} --material Urea --rpm 600 --width 3.5 --speed 12",
        "chart": f"chart --tables {table} --material Urea --widths 3,4,12 --speed 12",
    }
    reports = {}
    for kind, command in kinds.items():
        pdf = os.path.join(work, kind + ".pdf")
        argv = lambda suffix: [spread] + shlex.split(command.replace(
            "{output}", os.path.join(work, f"{kind}_{suffix}.sqlite"))) + (
            ["--report", pdf] if suffix == "report" else ["--json"])
        for suffix in ("report", "json"):
            out = os.path.join(work, f"{kind}_{suffix}.sqlite")
            if os.path.exists(out):
                os.remove(out)
        if os.path.exists(pdf):
            os.remove(pdf)
        reports[kind] = (run(argv("report"), work), run(argv("json"), work), pdf)
    return reports


def main():
    reports = make_reports(*sys.argv[1:5])
    if isinstance(reports, str):
        print("FAIL: " + reports)
        return 1
    problems, checked = [], 0
    for kind, (report_run, json_run, pdf) in reports.items():
        checked += check(kind, report_run, json_run, pdf, problems) or 0
    for p in problems:
        print("FAIL: " + p)
    if problems:
        return 1
    print(f"PASS: {len(reports)} reports; verdicts alike on the terminal, in --json and on the page; "
          f"{checked} numbers of the pages found in --json")
    return 0


if __name__ == "__main__":
    sys.exit(main())
