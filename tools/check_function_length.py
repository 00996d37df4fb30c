#!/usr/bin/env python3
"""No function longer than the limit in the folders named: long functions hide their stages.

Usage: check_function_length.py --root SOURCE_DIR [--max-lines N] FOLDER...

A function is a body `{ … }` opened at namespace or class scope after a parameter list (free functions,
member functions defined in or out of their class, constructors with their initialiser lists); lambdas and
local classes count as part of the function around them. Its length runs from the first line of its
signature to its closing brace. Exits 1 naming each function over N lines (file, line, length, name), and
prints how many functions were checked.
"""
import argparse
import os
import re
import sys

SOURCE_SUFFIXES = (".cpp", ".hpp", ".h", ".cc")
SCOPE_KEYWORDS = re.compile(r"\b(namespace|struct|class|union|enum)\b")
NAME = re.compile(r"([~\w:<>]+)\s*\(")
NOT_NAMES = {"__attribute__", "alignas", "decltype", "noexcept", "requires"}


def strip_comments_and_strings(text):
    """The text with comments, string and character literals blanked (newlines kept, so lines still count)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            end = text.find(")" + (m.group(1) if m else "") + '"', i)
            j = n if end < 0 else end + len(m.group(1) if m else "") + 2
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            # A digit separator (1'000) is not a character literal.
            if c == "'" and i > 0 and text[i - 1].isalnum() and j - i > 3:
                out.append(c)
                i += 1
                continue
            out.append(c + " " * (j - i - 2) + c if j - i >= 2 else c)
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def strip_preprocessor(code):
    """Preprocessor lines (and their continuations) blanked: `#if defined(X)` is no signature."""
    lines = code.split("\n")
    continued = False
    for k, line in enumerate(lines):
        if continued or line.lstrip().startswith("#"):
            continued = line.rstrip().endswith("\\")
            lines[k] = ""
    return "\n".join(lines)


def without_template_heads(head):
    """The head with its template parameter lists blanked: `template <class T> T f(...)` is a function, not a
    class (nested angle brackets counted)."""
    out, i = [], 0
    for m in re.finditer(r"\btemplate\s*<", head):
        if m.start() < i:
            continue
        out.append(head[i:m.start()])
        depth, j = 1, m.end()
        while j < len(head) and depth > 0:
            depth += {"<": 1, ">": -1}.get(head[j], 0)
            j += 1
        i = j
    out.append(head[i:])
    return " ".join(out)


def functions(text):
    """(first line, last line, name) of every function body at namespace or class scope."""
    code = strip_preprocessor(strip_comments_and_strings(text))
    found = []
    stack = []  # 'scope' (namespace, class, enum, initialiser) or ('function', start line, name)
    statement_start = 0  # index where the current declaration began
    i = 0
    while i < len(code):
        c = code[i]
        if c in ";":
            statement_start = i + 1
        elif c == "{":
            head = code[statement_start:i]
            in_function = any(isinstance(s, tuple) for s in stack)
            if not in_function and "(" in head and not SCOPE_KEYWORDS.search(without_template_heads(head).split("(")[0]) and \
                    not re.search(r"=\s*$", head) and not head.rstrip().endswith(","):
                first = code.count("\n", 0, statement_start + len(head) - len(head.lstrip())) + 1
                names = [n for n in NAME.findall(head) if n not in NOT_NAMES]
                stack.append(("function", first, names[0] if names else "?"))
            else:
                stack.append("scope")
            statement_start = i + 1
        elif c == "}":
            if stack:
                top = stack.pop()
                if isinstance(top, tuple) and not any(isinstance(s, tuple) for s in stack):
                    last = code.count("\n", 0, i) + 1
                    found.append((top[1], last, top[2]))
            statement_start = i + 1
        elif c == ":" and i + 1 < len(code) and code[i + 1] != ":" and (i == 0 or code[i - 1] != ":"):
            # "public:" and the like end a declaration; a constructor's initialiser list does not (its head
            # has a parameter list before the colon).
            head = code[statement_start:i].strip()
            if head in ("public", "private", "protected"):
                statement_start = i + 1
        i += 1
    return found


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--root", required=True)
    parser.add_argument("--max-lines", type=int, default=80)
    parser.add_argument("folders", nargs="+")
    args = parser.parse_args()
    checked, over = 0, []
    for folder in args.folders:
        for dirpath, _, files in os.walk(os.path.join(args.root, folder)):
            for name in sorted(files):
                if not name.endswith(SOURCE_SUFFIXES):
                    continue
                path = os.path.join(dirpath, name)
                with open(path, encoding="utf-8") as f:
                    text = f.read()
                for first, last, fname in functions(text):
                    checked += 1
                    length = last - first + 1
                    if length > args.max_lines:
                        over.append((os.path.relpath(path, args.root), first, length, fname))
    for path, first, length, fname in sorted(over):
        print(f"{path}:{first}: {fname} is {length} lines, over {args.max_lines}: split it into named stages")
    print(f"{checked} functions checked, {len(over)} over {args.max_lines} lines")
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main())
