#!/usr/bin/env python3
"""The dependency direction of tools/layers.txt, checked on the sources and the build's target links.

Usage: check_layers.py --root SOURCE_DIR [--layers FILE] [--links BUILD_DIR/layer_links.txt]

A module lives in its layer's folder, libspread/LAYER/MODULE (a module named like its layer is the layer's
folder itself: libspread/core). Every #include "…" in libspread/, capi/, isobus/, lcm_link/, firmware_sim/, tools/
and lookup_builder/ that names a folder of the table (libspread/LAYER/MODULE/…, capi/…, lookup_builder/…, a
`header` line) is a use of that unit; so is every link between our targets the build recorded
(cmake/SpreadLayers.cmake). A module may use the modules of lower layers and those before it in its own layer;
a program what its line lists. Exits 1 naming each use against the table (file and line, or the two targets),
each source file under libspread/ outside the module folders, and each `allow` line whose use is gone.
"""
import argparse
import os
import re
import sys

SCANNED = ("libspread", "capi", "isobus", "lcm_link", "firmware_sim", "tools", "lookup_builder")
SOURCE_SUFFIXES = (".c", ".cpp", ".h", ".hpp")
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')


class Table:
    def __init__(self, path):
        self.path = path
        self.layers = []      # (layer name, [modules]) lowest first
        self.rank = {}        # module -> (layer index, position in layer)
        self.layer_of = {}    # module -> layer name
        self.folder = {}      # module -> its folder, libspread/LAYER/MODULE
        self.programs = {}    # folder -> set of units it may use
        self.headers = {}     # include path -> unit
        self.allowed = {}     # (from, to) -> line number
        raw_programs = {}
        with open(path, encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                words = line.split()
                if not words or words[0].startswith("#"):
                    continue
                kind = words[0]
                if kind == "layer" and len(words) >= 3:
                    for position, module in enumerate(words[2:]):
                        if module in self.rank:
                            self.fail(number, f"module {module} listed twice")
                        self.rank[module] = (len(self.layers), position)
                        self.layer_of[module] = words[1]
                        self.folder[module] = module_folder(words[1], module)
                    self.layers.append((words[1], words[2:]))
                elif kind == "program" and len(words) >= 2:
                    raw_programs[words[1]] = words[2:]
                elif kind == "header" and len(words) == 3:
                    self.headers[words[1]] = words[2]
                elif kind == "allow" and len(words) >= 5 and words[2] == "->":
                    self.allowed[(words[1], words[3])] = number
                else:
                    self.fail(number, f"cannot read: {line.strip()}")
        layer_names = {name: modules for name, modules in self.layers}
        for folder, uses in raw_programs.items():
            expanded = {folder}
            for use in uses:
                if use == "libspread":
                    expanded.update(self.rank)
                elif use in layer_names:
                    expanded.update(layer_names[use])
                else:
                    expanded.add(use)
            self.programs[folder] = expanded
        for (a, b), number in self.allowed.items():
            for unit in (a, b):
                if unit not in self.rank:
                    self.fail(number, f"allow: {unit} is not a module of a layer")

    def fail(self, number, message):
        sys.exit(f"{self.path}:{number}: {message}")

    def unit_of(self, path):
        """The unit a path (source file or include, relative to the root) belongs to, or None."""
        if path in self.headers:
            return self.headers[path]
        parts = path.split("/")
        if len(parts) >= 3 and parts[0] == "libspread":
            for module, folder in self.folder.items():
                if path.startswith(folder + "/"):
                    return module
            # Not a module folder: the folder named as deep as a module's would be.
            depth = 3 if parts[1] in {name for name, _ in self.layers} and len(parts) >= 4 else 2
            return "/".join(parts[:depth])
        best = None
        for folder in list(self.programs) + ["tests", "bench", "fuzz"]:
            if path == folder or path.startswith(folder + "/"):
                if best is None or len(folder) > len(best):
                    best = folder
        return best

    def misplaced(self, rel):
        """Why a source file under libspread/ is outside every module folder, or None when it is inside one."""
        if self.unit_of(rel) in self.rank:
            return None
        parts = rel.split("/")
        for module, folder in self.folder.items():
            if module in parts[1:-1]:
                return f"{rel}: outside the module folders of the layer table: {module} lives in {folder}/"
        return (f"{rel}: outside the module folders of the layer table: a module lives in libspread/LAYER/MODULE "
                f"and is listed on its layer's `layer` line")

    def describe(self, unit):
        if unit in self.layer_of:
            return f"{unit} ({self.layer_of[unit]})"
        return unit

    def verdict(self, source, target):
        """None when `source` may use `target`, else why not."""
        if source == target:
            return None
        for unit in (source, target):
            if unit.startswith("libspread/"):
                return f"{unit} is a module folder of no layer: add it to a `layer` line"
        if source in self.rank:
            if target in self.rank:
                if self.rank[target] < self.rank[source] or (source, target) in self.allowed:
                    return None
                return (f"{self.describe(source)} may not use {self.describe(target)}: a module uses lower layers "
                        f"and the modules before it in its own layer")
            return f"{self.describe(source)} may not use the program folder {target}"
        program = self.program_of(source)
        if program is not None:
            allowed = self.programs[program]
            if target in allowed or any(target == a or target.startswith(a + "/") for a in allowed):
                return None
            return f"{source} may not use {self.describe(target)} (its `program` line lists what it may use)"
        return None

    def program_of(self, unit):
        best = None
        for folder in self.programs:
            if unit == folder or unit.startswith(folder + "/"):
                if best is None or len(folder) > len(best):
                    best = folder
        return best


def module_folder(layer, module):
    """Where a module's sources live: libspread/LAYER/MODULE; the layer's own folder for a module named like it."""
    return f"libspread/{module}" if module == layer else f"libspread/{layer}/{module}"


def source_files(root):
    for top in SCANNED:
        for folder, dirs, files in os.walk(os.path.join(root, top)):
            dirs.sort()
            for name in sorted(files):
                if name.endswith(SOURCE_SUFFIXES):
                    yield os.path.relpath(os.path.join(folder, name), root)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", required=True, help="the source tree")
    parser.add_argument("--layers", help="the layer table (default: ROOT/tools/layers.txt)")
    parser.add_argument("--links", help="the build's target links (BUILD_DIR/layer_links.txt)")
    args = parser.parse_args()
    table = Table(args.layers or os.path.join(args.root, "tools", "layers.txt"))

    problems = []
    used_exceptions = set()
    counts = {"include": 0, "link": 0}

    def check(kind, source, target, where):
        if source is None or target is None or source == target:
            return
        counts[kind] += 1
        if (source, target) in table.allowed:
            used_exceptions.add((source, target))
        why = table.verdict(source, target)
        if why:
            problems.append(f"{where}: {why}")

    for rel in source_files(args.root):
        if rel.startswith("libspread/"):
            why = table.misplaced(rel)
            if why:
                problems.append(why)
        source = table.unit_of(rel)
        if source is None:
            continue
        with open(os.path.join(args.root, rel), encoding="utf-8", errors="replace") as f:
            for number, line in enumerate(f, 1):
                match = INCLUDE.match(line)
                if match:
                    check("include", source, table.unit_of(match.group(1)),
                          f"{rel}:{number}: #include \"{match.group(1)}\"")
    if args.links:
        with open(args.links, encoding="utf-8") as f:
            for line in f:
                words = line.split()
                if len(words) == 4:
                    check("link", table.unit_of(words[0] + "/x"), table.unit_of(words[1] + "/x"),
                          f"target {words[2]} ({words[0]}) links {words[3]} ({words[1]})")
    for pair, number in sorted(table.allowed.items()):
        if pair not in used_exceptions:
            problems.append(f"{table.path}:{number}: allow {pair[0]} -> {pair[1]}: no longer used; remove the line")
    for problem in problems:
        print(problem)
    print(f"layers: {counts['include']} includes and {counts['link']} links across units checked, "
          f"{len(problems)} against the table ({len(used_exceptions)} allowed exceptions in use)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
