#!/usr/bin/env python3
"""Runs the commands docs/field-calibration.md (or another doc given, as docs/field.md) shows outside its
walkthrough and requires every output line it quotes.

Usage: doc_commands.py DOC SPREAD LOOKUP_BUILDER SOURCE_DIR WORK_DIR [MAIN_TABLE]

Every fenced block of the doc outside "## Walkthrough..." (which tests/tools/doc_walkthrough.py runs on
the main job's table) is read as doc_walkthrough.py reads its blocks: a line starting with `spread `,
`mkdir ` begins a command (continued by lines ending in a backslash), `...` stands for lines left out,
every other line is output one of the block's commands must print — on stdout, or on stderr for a
refusal (`spread CMD: error: ...`, when the command may exit 2). A block without a command (a file
format, a figure quoted from elsewhere) is not run. A block whose commands read a table is run only when
the doc says in its text, just before the block, which `lookup_builder ...` command made that table
from the source tree (an analytic table: built here in a second or so); a block on the main job's table
(default.sqlite, out/default.sqlite and what is calibrated from it) is left to the walkthrough's test,
whose table fixture makes it. With MAIN_TABLE (the main job's table, the `capi.fixture.default_scene`
fixture) only the blocks outside the walkthrough that read out/default.sqlite are run — the setting chart's
and the border's, which the doc shows on the main job's table — with that file as out/default.sqlite.
Commands run from WORK_DIR, where `scenes` is the source tree's.
Prints "PASS: ..." or "FAIL: why" (exit 1).
"""
import os
import re
import shlex
import subprocess
import sys

import doc_blocks

MAIN_JOB_TABLES = ("default.sqlite", "default-calibrated.sqlite")
MAIN_TABLE_OUTSIDE_WALKTHROUGH = "out/default.sqlite"
REFUSAL = re.compile(r"^spread [a-z ]+: error: ")


def blocks_outside_walkthrough(text):
    """(block, text before it) for every fenced block outside the walkthrough section."""
    walkthrough = re.search(r"^## Walkthrough.*?$(.*?)^## ", text, re.S | re.M)
    skip = (walkthrough.start(), walkthrough.end()) if walkthrough else (0, 0)
    out = []
    # Every fence with its language tag (```sh, ```toml, ...), so that a tagged block's closing fence is
    # never taken for the opening of the next; only untagged blocks are commands and their output.
    for match in re.finditer(r"^```([a-z]*)\n(.*?)^```", text, re.S | re.M):
        if match.group(1) or skip[0] <= match.start() < skip[1]:
            continue
        out.append((match.group(2), text[:match.start()]))
    return out


def commands_and_expected(block):
    return doc_blocks.commands_and_expected(block, ("spread ", "mkdir "), lambda line: not REFUSAL.match(line))


def tables_read(commands):
    tables = []
    for command in commands:
        argv = shlex.split(command)
        tables += [argv[k + 1] for k, a in enumerate(argv[:-1]) if a == "--tables"]
    return tables


def builder_command_before(prose):
    """The last `lookup_builder ...` command quoted inline (it may span lines) in the text before a block."""
    found = re.findall(r"`(lookup_builder [^`]+)`", prose)
    return " ".join(found[-1].split()) if found else None


def main():
    doc, spread, builder, source, work = sys.argv[1:6]
    main_table = sys.argv[6] if len(sys.argv) > 6 else None
    os.makedirs(work, exist_ok=True)
    if main_table:
        os.makedirs(os.path.join(work, "out"), exist_ok=True)
        linked = os.path.join(work, MAIN_TABLE_OUTSIDE_WALKTHROUGH)
        if os.path.lexists(linked):
            os.remove(linked)
        os.symlink(os.path.abspath(main_table), linked)
    if os.path.islink(os.path.join(work, "scenes")):
        os.remove(os.path.join(work, "scenes"))
    os.symlink(os.path.join(source, "scenes"), os.path.join(work, "scenes"))
    env = dict(os.environ, SOURCE_DATE_EPOCH="1795564800")  # dates in reports fixed
    with open(doc, encoding="utf-8") as f:
        blocks = blocks_outside_walkthrough(f.read())
    run_blocks, left, checked = 0, 0, 0
    for block, prose in blocks:
        commands, expected = commands_and_expected(block)
        if not commands:
            continue
        tables = tables_read(commands)
        on_main_table = MAIN_TABLE_OUTSIDE_WALKTHROUGH in tables
        if main_table and not on_main_table:
            left += 1
            continue
        if not main_table and any(os.path.basename(t) in MAIN_JOB_TABLES for t in tables):
            left += 1
            continue
        for table in set(tables) - ({MAIN_TABLE_OUTSIDE_WALKTHROUGH} if main_table else set()):
            build = builder_command_before(prose)
            if build is None:
                print(f"FAIL: the block running\n  {commands[0]}\nreads {table} but the doc does not say before it "
                      "which lookup_builder command made it")
                return 1
            argv = [builder] + shlex.split(build)[1:] + ["--output", table]
            if os.path.exists(os.path.join(work, table)):
                os.remove(os.path.join(work, table))
            made = subprocess.run(argv, cwd=work, env=env, capture_output=True, text=True)
            if made.returncode != 0:
                print(f"FAIL: '{build} --output {table}' exited {made.returncode}\n{made.stderr}")
                return 1
        refusal_expected = any(REFUSAL.match(line) for line in expected)
        stdout, stderr = "", ""
        for command in commands:
            argv = shlex.split(command)
            if argv[0] == "spread":
                argv[0] = spread
            result = subprocess.run(argv, cwd=work, env=env, capture_output=True, text=True)
            if result.returncode != 0 and not (refusal_expected and result.returncode == 2):
                print(f"FAIL: '{command}' exited {result.returncode}\n{result.stdout}\n{result.stderr}")
                return 1
            stdout += result.stdout
            stderr += result.stderr
        printed = set(line.rstrip() for line in (stdout + stderr).splitlines())
        for line in expected:
            if line not in printed:
                print(f"FAIL: the doc quotes\n  {line}\nwhich the commands\n  " + "\n  ".join(commands) +
                      "\ndid not print; they printed:\n" + stdout + stderr)
                return 1
            checked += 1
        run_blocks += 1
    if run_blocks == 0:
        print("FAIL: no block of the doc was run")
        return 1
    if main_table:
        print(f"PASS: {run_blocks} blocks on the main job's table run, {checked} quoted lines reproduced; {left} "
              "others left to the test without it")
    else:
        print(f"PASS: {run_blocks} blocks run, {checked} quoted lines reproduced; {left} on the main job's table "
              "left to the walkthrough's test and the main-table run")
    return 0


if __name__ == "__main__":
    sys.exit(main())
