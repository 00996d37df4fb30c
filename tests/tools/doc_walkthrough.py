#!/usr/bin/env python3
"""Runs the walkthrough of docs/field-calibration.md and requires every output line it quotes.

Usage: doc_walkthrough.py DOC SPREAD LOOKUP_BUILDER SOURCE_DIR WORK_DIR DEFAULT_TABLE

The section "## Walkthrough..." holds fenced blocks. In a block, a line starting with `spread `,
`lookup_builder ` or `mkdir ` begins a command (continued by lines ending in a backslash); every other
line is output that one of the block's commands must print, verbatim; `...` lines stand for lines left
out. Commands run from WORK_DIR, where `scenes` is the source tree's. The doc's lookup_builder command
must be the one the DEFAULT_TABLE fixture ran (tests/capi/CMakeLists.txt): the table is copied from it
instead of built again. Prints "PASS" or "FAIL: why" (exit 1).
"""
import os
import re
import shlex
import shutil
import subprocess
import sys

import doc_blocks

FIXTURE_COMMAND = ["scenes/default.toml", "--output", "default.sqlite", "--jobs", "2"]


def blocks_of_walkthrough(text):
    match = re.search(r"^## Walkthrough.*?$(.*?)^## ", text, re.S | re.M)
    if not match:
        raise SystemExit("FAIL: no '## Walkthrough' section in the doc")
    return re.findall(r"^```\n(.*?)^```", match.group(1), re.S | re.M)


def commands_and_expected(block):
    return doc_blocks.commands_and_expected(block, ("spread ", "lookup_builder ", "mkdir "))


def main():
    doc, spread, builder, source, work, table = sys.argv[1:7]
    os.makedirs(work, exist_ok=True)
    for name in ("default.sqlite", "default-calibrated.sqlite"):
        if os.path.exists(os.path.join(work, name)):
            os.remove(os.path.join(work, name))
    if os.path.islink(os.path.join(work, "scenes")):
        os.remove(os.path.join(work, "scenes"))
    os.symlink(os.path.join(source, "scenes"), os.path.join(work, "scenes"))
    env = dict(os.environ, SOURCE_DATE_EPOCH="1795564800")  # 2026-11-25: dates in reports fixed
    with open(doc, encoding="utf-8") as f:
        blocks = blocks_of_walkthrough(f.read())
    checked = 0
    for block in blocks:
        commands, expected = commands_and_expected(block)
        output = ""
        for command in commands:
            argv = shlex.split(command)
            if argv[0] == "lookup_builder":
                if argv[1:] != FIXTURE_COMMAND:
                    print(f"FAIL: the doc's table command {argv[1:]} is not the fixture's {FIXTURE_COMMAND}")
                    return 1
                shutil.copyfile(table, os.path.join(work, "default.sqlite"))
                continue
            if argv[0] == "spread":
                argv[0] = spread
            run = subprocess.run(argv, cwd=work, env=env, capture_output=True, text=True)
            if run.returncode != 0:
                print(f"FAIL: '{command}' exited {run.returncode}\n{run.stdout}\n{run.stderr}")
                return 1
            output += run.stdout
        printed = [line.rstrip() for line in output.splitlines()]
        for line in expected:
            if line not in printed:
                print(f"FAIL: the doc quotes\n  {line}\nwhich the commands\n  " + "\n  ".join(commands) +
                      "\ndid not print; they printed:\n" + output)
                return 1
            checked += 1
    print(f"PASS: {len(blocks)} blocks, {checked} quoted lines reproduced")
    return 0


if __name__ == "__main__":
    sys.exit(main())
