#!/usr/bin/env python3
"""The simulator (the plant) never uses the estimator's model, filter or spectra.

Why: the simulator is the truth the estimator is tested against. A plant that computed its forces,
its spectra or its filter with the estimator's own code would agree with the estimator whatever
that code got wrong: every model error would cancel out and every test would pass. The plant may
share only the core library (estimator/core/: time, samples, CAN frames, the J1939 codec, parse
errors), which describes the data both sides exchange rather than the physics.

Two parts:
  (a) no file under sim/ includes a header that lives under estimator/include/ (headers under
      estimator/core/include/ are allowed);
  (b) given both static libraries: no symbol the sim archive needs (nm -u) is defined by the
      estimator archive (nm --defined-only).

Usage: check_sim_independence.py [--root DIR] [--nm NM] [--estimator-lib A --sim-lib A]
Prints `path:line: message` or `archive: symbol` per violation; exit status 1 if any.
"""

import argparse
import os
import re
import subprocess
import sys

import layers_common as common

INCLUDE = re.compile(r'^[ \t]*#[ \t]*include[ \t]*([<"])([^>"\n]+)[>"]', re.MULTILINE)


def headers_under(root, folder):
    """Include names (paths relative to folder) of the headers under root/folder."""
    base = os.path.join(root, folder)
    names = set()
    for rel in common.walk_files(root, [folder], lambda r: r.endswith(common.CXX_EXTENSIONS)):
        names.add(os.path.relpath(os.path.join(root, rel), base).replace(os.sep, "/"))
    return names


def check_includes(root):
    estimator = headers_under(root, "estimator/include")
    core = headers_under(root, "estimator/core/include")
    sim_files = common.walk_files(root, ["sim"], lambda r: r.endswith(common.CXX_EXTENSIONS))
    violations = []
    for rel in sim_files:
        text = common.read_text(os.path.join(root, rel))
        for m in INCLUDE.finditer(common.blank_cxx(text, strings=False)):
            name = os.path.normpath(m.group(2).strip()).replace(os.sep, "/")
            if "estimator/core/include/" in name:  # a path into the source tree, to the core
                continue
            if "estimator/include/" in name:  # a path into the source tree, to the estimator
                name = name.split("estimator/include/", 1)[1]
            elif name not in estimator:
                continue
            also = " (one of that name is in estimator/core/include/ too)" if name in core else ""
            violations.append(f"{rel}:{common.line_of(text, m.start())}: includes the estimator's "
                              f"{name}{also}: the plant may use estimator/core/ only")
    return violations, len(sim_files)


def nm_lines(nm, args, archive):
    return subprocess.run([nm] + args + [archive], capture_output=True, text=True, check=True).stdout.splitlines()


def estimator_definitions(nm, archive):
    """Demangled global text and data symbols the archive defines. Weak ones (inline functions,
    template instances) only when they are the project's own: every archive has its own copies of
    the standard library's."""
    defined = set()
    for line in nm_lines(nm, ["-C", "--defined-only"], archive):
        parts = line.split(None, 2)
        if len(parts) != 3:
            continue
        kind, name = parts[1], parts[2]
        if kind in "TDBRGS":
            defined.add(name)
        elif kind in "WVu" and name.startswith("roadload::"):
            defined.add(name)
    return defined


def sim_undefined(nm, archive):
    undefined = set()
    for line in nm_lines(nm, ["-C", "-u"], archive):
        parts = line.split(None, 1)
        if len(parts) == 2 and parts[0] in ("U", "w", "v"):
            undefined.add(parts[1].split("@")[0].strip())
    return undefined


def check_symbols(nm, estimator_lib, sim_lib):
    shared = sorted(estimator_definitions(nm, estimator_lib) & sim_undefined(nm, sim_lib))
    return [f"{sim_lib}: {symbol}  (defined in {os.path.basename(estimator_lib)})" for symbol in shared]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    common.add_root_argument(parser)
    parser.add_argument("--nm", default="nm", help="nm for the archives' target (default: nm)")
    parser.add_argument("--estimator-lib", metavar="ARCHIVE", help="libroadload_estimator.a")
    parser.add_argument("--sim-lib", metavar="ARCHIVE", help="libroadload_sim.a")
    args = parser.parse_args()
    if bool(args.estimator_lib) != bool(args.sim_lib):
        parser.error("--estimator-lib and --sim-lib go together")
    common.require_root(parser, args.root, ["sim", "estimator"])

    violations, files = check_includes(args.root)
    checked = f"{files} files under sim/"
    if args.estimator_lib:
        violations += check_symbols(args.nm, args.estimator_lib, args.sim_lib)
        checked += " and the sim archive's undefined symbols"
    return common.report("check_sim_independence", violations, checked)


if __name__ == "__main__":
    sys.exit(main())
