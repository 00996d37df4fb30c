#!/usr/bin/env python3
"""Every document the tree cites is in the tree.

Scans the sources, build files, scripts and docs for names of Markdown files ("docs/metrics.md",
"bench/peers/README.md", "design.md §7", a link "(c-api.md#opening)") and fails when one names no file: relative
to the repository's root or to the citing file's folder. In C and C++ only comments cite. A citation of a numbered section of docs/design.md
("docs/design.md §7") must name a section that page has ("## 7. ..."). URLs are not citations of the tree.

Usage: check_doc_citations.py --root SOURCE_DIR     prints "N citations of M documents checked, 0 missing"
and exits 0, or lists each miss as FILE:LINE: CITATION and exits 1.
"""
import argparse
import os
import re
import sys

SCANNED = (".cpp", ".hpp", ".h", ".c", ".py", ".sh", ".md", ".txt", ".cmake", ".toml", ".lcm", ".yml", ".json")
C_FAMILY = (".cpp", ".hpp", ".h", ".c")
SKIPPED_DIRS = {".git", "node_modules", "out", "__pycache__"}
CITATION = re.compile(r"(?<![A-Za-z0-9_./:-])((?:\.\./|\./)?[A-Za-z0-9_][A-Za-z0-9_./-]*\.md)\b(?:\s*§\s*(\d+))?")
URL = re.compile(r"[a-z]+://\S+")
DESIGN = "docs/design.md"


def scanned_files(root):
    for folder, dirs, files in os.walk(root):
        dirs[:] = [d for d in dirs if d not in SKIPPED_DIRS and not d.startswith("build")]
        for name in files:
            if (name.endswith(SCANNED) or name == "CMakeLists.txt") and name != os.path.basename(__file__):
                yield os.path.join(folder, name)


def cited_text(path, line):
    """The part of a line that can cite: in C and C++ its comment (a string literal names a file a program
    writes, such as a report.md), elsewhere all of it."""
    if not path.endswith(C_FAMILY):
        return line
    if "//" in line:
        return line[line.index("//"):]
    stripped = line.lstrip()
    return line if stripped.startswith(("/*", "*")) else ""


def design_sections(root):
    path = os.path.join(root, DESIGN)
    if not os.path.exists(path):
        return set()
    with open(path, encoding="utf-8") as f:
        return {m.group(1) for m in re.finditer(r"^## (\d+)\.", f.read(), re.MULTILINE)}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--root", required=True)
    root = os.path.abspath(parser.parse_args().root)
    sections = design_sections(root)
    misses, count, documents = [], 0, set()
    for path in scanned_files(root):
        folder = os.path.dirname(path)
        try:
            with open(path, encoding="utf-8") as f:
                lines = f.read().splitlines()
        except UnicodeDecodeError:
            continue
        for number, line in enumerate(lines, 1):
            for match in CITATION.finditer(URL.sub("", cited_text(path, line))):
                cited, section = match.group(1), match.group(2)
                where = [os.path.normpath(os.path.join(folder, cited))]
                if not cited.startswith("."):
                    where.insert(0, os.path.normpath(os.path.join(root, cited)))
                found = next((w for w in where if os.path.isfile(w)), None)
                count += 1
                relative = os.path.relpath(path, root)
                if found is None:
                    misses.append(f"{relative}:{number}: {cited}: no such document in the tree")
                    continue
                documents.add(found)
                if section and os.path.relpath(found, root) == DESIGN and section not in sections:
                    misses.append(f"{relative}:{number}: {cited} §{section}: {DESIGN} has no section {section}")
    for miss in misses:
        print(miss)
    print(f"{count} citations of {len(documents)} documents checked, {len(misses)} missing")
    return 1 if misses else 0


if __name__ == "__main__":
    sys.exit(main())
