#!/usr/bin/env python3
"""No source file over 400 lines, no C++ function over 80 lines unless it says why.

Why: a file or function that keeps growing is where the layers blur: the 600-line file mixes
parsing with physics with output, the 200-line function is the one nobody can test in parts.
The limits make a split the default; a function that is clearer in one piece (a table, a state
machine read top to bottom) keeps its length by saying so in the comment directly above it (or on
its signature's line): "Long because ...".

Files: C++ sources and headers, Python, shell scripts (by extension or #! line), CMake files,
among git's tracked and untracked-but-not-ignored files; not tests/data/, config/, docs/ or data
(*.md, *.toml, *.dbc, *.csv, *.log, ...). Functions: found by cxx_functions.py, counted from the
first line of the signature to the closing brace.

Usage: check_sizes.py [--root DIR] [--max-file-lines N] [--max-function-lines N]
Prints `path:line: message` per violation; exit status 1 if any.
"""

import argparse
import os
import re
import sys

import cxx_functions
import layers_common as common

MAX_FILE_LINES = 400
MAX_FUNCTION_LINES = 80
SKIPPED_DIRS = ("tests/data/", "config/", "docs/")
SCRIPT_SUFFIXES = (".py", ".sh", ".bash", ".cmake")
SHEBANG = re.compile(r"^#!.*\b(sh|bash|dash|python3?)\b")
EXCUSE = re.compile(r"long\s+because", re.IGNORECASE)


def is_source(root, rel):
    if rel.startswith(SKIPPED_DIRS):
        return False
    name = os.path.basename(rel)
    if name == "CMakeLists.txt" or rel.endswith(common.CXX_EXTENSIONS + SCRIPT_SUFFIXES):
        return True
    if "." in name:  # data, documentation, configuration
        return False
    try:
        with open(os.path.join(root, rel), "rb") as f:
            first = f.readline(200).decode("utf-8", "replace")
    except OSError:
        return False
    return bool(SHEBANG.match(first))


def count_lines(text):
    return text.count("\n") + (1 if text and not text.endswith("\n") else 0)


def split_comments(text):
    """(code lines, comment lines): text's lines with the comments blanked, and with everything but
    the comments (and their // /* */ markers) blanked."""
    code = common.blank_cxx(text, strings=False)
    kept = "".join(t if t != c else (t if t == "\n" else " ") for t, c in zip(text, code))
    comments = re.sub(r"//+|/\*+|\*+/|^\s*\*", " ", kept, flags=re.MULTILINE)
    return code.split("\n"), comments.split("\n")


def excused(function, code_lines, comment_lines):
    """Whether the comment block directly above the function, or a comment on its signature's
    lines, says "Long because"."""
    said = [comment_lines[n - 1] for n in range(function.start_line, function.brace_line + 1)]
    n = function.start_line - 1
    while n >= 1 and not code_lines[n - 1].strip() and comment_lines[n - 1].strip():
        said.insert(0, comment_lines[n - 1])
        n -= 1
    return bool(EXCUSE.search(" ".join(" ".join(said).split())))


def long_functions(text, limit):
    code_lines, comment_lines = split_comments(text)
    for f in cxx_functions.find_functions(text):
        if f.lines > limit and not excused(f, code_lines, comment_lines):
            yield f


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    common.add_root_argument(parser)
    parser.add_argument("--max-file-lines", type=int, default=MAX_FILE_LINES)
    parser.add_argument("--max-function-lines", type=int, default=MAX_FUNCTION_LINES)
    args = parser.parse_args()
    common.require_root(parser, args.root)

    files = [rel for rel in common.repo_files(args.root) if is_source(args.root, rel)]
    if not files:
        parser.error(f"--root {args.root}: no source files")
    long_files = long_bodies = 0
    for rel in files:
        text = common.read_text(os.path.join(args.root, rel))
        lines = count_lines(text)
        if lines > args.max_file_lines:
            long_files += 1
            print(f"{rel}:1: file is {lines} lines (limit {args.max_file_lines})")
        if rel.endswith(common.CXX_EXTENSIONS):
            for f in long_functions(text, args.max_function_lines):
                long_bodies += 1
                what = f"lambda '{f.name}'" if f.lambda_ else f"function '{f.name}'"
                print(f"{rel}:{f.start_line}: {what} is {f.lines} lines (limit {args.max_function_lines})")
    if long_files or long_bodies:
        print(f"check_sizes: {long_files} file(s) over {args.max_file_lines} lines, {long_bodies} function(s) "
              f"over {args.max_function_lines} lines, in {len(files)} source files")
        return 1
    print(f"check_sizes: OK, {len(files)} source files")
    return 0


if __name__ == "__main__":
    sys.exit(main())
