#!/usr/bin/env python3
"""A report page is read by a farmer: no paths, no option names, no words of the code.

Usage: page_glossary.py SPREAD LOOKUP_BUILDER SOURCE_DIR WORK_DIR

Makes every report kind as tests/tools/report_agreement.py does and reads each page back with poppler's
pdftotext. Its text — the footer aside, which names the command that made the page so that the page can
be made again — must hold no file path (a word with a slash), no option name (--width), no command in
backticks, and none of the glossary's banned words below, each with the farmer's word to use instead.
Prints "PASS: ..." or a "FAIL: ..." line for each word found (exit 1).
"""
import os
import re
import sys

import report_agreement

# The banned words and what a page says instead.
BANNED = {
    "DEM": "the simulation (of the discs)",
    "pass(es)": "passes, or 1 pass",
    "McKay": "(the interval needs no name)",
    "standard error": "the 95 % interval, or how sure the fit is",
    "effects drag": "air drag",
    "launch sample": "simulated granules",
    "launches": "throw",
    "lookup_builder": "a launch table made for the machine",
    "spread calibrate": "a tray test, a catch test",
    "spread chart": "the setting chart",
    "analytic": "(how the table was made is not the farmer's)",
    "JSON": "(not on a page)",
}
PATH = re.compile(r"(?<![\w±])(?:\.{0,2}/)?[\w.-]+/[\w./-]+")
OPTION = re.compile(r"(?<![\w-])--[a-z][a-z-]*")
UNITS_WITH_SLASH = ("kg/ha", "km/h", "g/ha", "t/ha", "m/s", "2.50/3.50")


def body_of(layout):
    """The page's text without its footer (the command that made it, and when)."""
    kept = []
    for page in layout.split("\f"):
        for line in page.splitlines():
            if line.strip().startswith("made by:"):
                break
            kept.append(line)
    return "\n".join(kept)


def problems_of(kind, text):
    found = []
    flowing = " ".join(text.split())  # a phrase may be wrapped over two lines
    for word, instead in BANNED.items():
        at = flowing.find(word)
        if at >= 0:
            found.append(f"{kind}: '{word}' on the page (say: {instead}): ...{flowing[max(0, at - 60):at + 60]}...")
    for match in PATH.finditer(text):
        token = match.group(0)
        if any(unit in token for unit in UNITS_WITH_SLASH) or re.fullmatch(r"[\d.]+/[\d.]+", token):
            continue
        found.append(f"{kind}: a path on the page: {token}")
    for match in OPTION.finditer(text):
        found.append(f"{kind}: an option name on the page: {match.group(0)}")
    if "`" in text:
        found.append(f"{kind}: a command in backticks on the page: " +
                     next(l.strip() for l in text.splitlines() if "`" in l))
    return found


def main():
    reports = report_agreement.make_reports(*sys.argv[1:5])
    if isinstance(reports, str):
        print("FAIL: " + reports)
        return 1
    problems = []
    for kind, (report_run, _, pdf) in reports.items():
        if report_run.returncode != 0 or not os.path.exists(pdf):
            problems.append(f"{kind}: no page ({report_run.returncode}): {report_run.stderr}")
            continue
        layout = report_agreement.run(["pdftotext", "-layout", pdf, "-"], ".").stdout
        problems += problems_of(kind, body_of(layout))
    for p in problems:
        print("FAIL: " + p)
    if problems:
        return 1
    print(f"PASS: {len(reports)} pages in the farmer's words: no path, option name, command or banned word "
          f"({len(BANNED)} in the glossary)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
