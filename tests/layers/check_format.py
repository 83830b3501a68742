#!/usr/bin/env python3
"""Every C++ file is formatted as .clang-format says.

Why: with one mechanical format, a diff shows what changed and nothing else, reviews do not
argue about spaces, and the other checks here (sizes, constants) count lines that mean something.
The style is the code's own (Google C++ with long lines, measured: see .clang-format), checked with
the clang-format it was tuned for: another major version may format a few constructs differently.

Files: git's tracked C++ files (*.cpp, *.hpp, *.h) and untracked ones it does not ignore, so that a
new file is checked before it is committed; not tests/data/.

Usage: check_format.py [--root DIR] [--clang-format PATH]
Prints `path:line: message` per file that needs formatting; exit status 1 if any, 77 (skipped)
without clang-format.
"""

import argparse
import os
import re
import shutil
import subprocess
import sys

import layers_common as common

SKIP_RETURN_CODE = 77
CXX_SUFFIXES = (".cpp", ".hpp", ".h")
BATCH = 50  # files per clang-format run
WARNING = re.compile(r"^(.+?):(\d+):\d+: (?:error|warning): code should be clang-formatted")


def cxx_files(root):
    return [rel for rel in common.repo_files(root) if rel.endswith(CXX_SUFFIXES) and not rel.startswith("tests/data/")]


def unformatted(clang_format, root, files):
    """{file: (first line to change, places)} for the files clang-format would change."""
    found = {}
    for at in range(0, len(files), BATCH):
        batch = files[at:at + BATCH]
        run = subprocess.run([clang_format, "--dry-run", "--Werror", "--style=file"] + batch,
                             cwd=root, capture_output=True, text=True)
        for line in run.stderr.splitlines():
            m = WARNING.match(line)
            if m:
                first, places = found.get(m.group(1), (int(m.group(2)), 0))
                found[m.group(1)] = (first, places + 1)
        if run.returncode != 0 and not any(f in found for f in batch):
            sys.exit(f"check_format: {clang_format} failed:\n{run.stderr}")
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    common.add_root_argument(parser)
    parser.add_argument("--clang-format", default=shutil.which("clang-format-14") or shutil.which("clang-format"),
                        help="the clang-format to run (default: clang-format-14 or clang-format on PATH)")
    args = parser.parse_args()
    common.require_root(parser, args.root)
    if not args.clang_format:
        print("check_format: skipped, no clang-format")
        return SKIP_RETURN_CODE
    if not os.path.isfile(os.path.join(args.root, ".clang-format")):
        print(f"{os.path.join(args.root, '.clang-format')}:1: missing: the style to check against")
        return 1

    files = cxx_files(args.root)
    if not files:
        parser.error(f"--root {args.root}: no C++ files")
    found = unformatted(args.clang_format, args.root, files)
    for rel in sorted(found):
        first, places = found[rel]
        print(f"{rel}:{first}: needs clang-format ({places} place(s))")
    version = subprocess.run([args.clang_format, "--version"], capture_output=True, text=True).stdout.strip()
    if found:
        print(f"check_format: {len(found)} of {len(files)} C++ files need formatting ({version}; "
              f"`{os.path.basename(args.clang_format)} -i FILE` formats one)")
        return 1
    print(f"check_format: OK, {len(files)} C++ files ({version})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
