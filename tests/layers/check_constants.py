#!/usr/bin/env python3
"""The MnROAD test truck lives in config/vehicles/mnroad-truck.toml, and only there.

Why: the seed report's truck (its mass, axle loads and positions, engine, driveline, VIN, CdA,
unsprung masses) is one vehicle among the ones roadload will meet. Written as constants in the code
it becomes the silent default of every other truck: a second truck would need a code edit, and a
recording whose metadata lacks a field would be analysed with the MnROAD value without anyone
noticing. So its numbers may appear in its vehicle file (and in tests, docs and config), never in
the source or build files of estimator/, drivers/, firmware/, sim/ or tools/. Comments count too:
a comment quoting the value is a second place the number lives and goes stale with it.

Usage: check_constants.py [--root DIR]
Prints `path:line: message` per occurrence; exit status 1 if any.
"""

import argparse
import os
import re
import sys

import layers_common as common

SCANNED_DIRS = ["estimator", "drivers", "firmware", "sim", "tools"]
SCANNED_NAMES = re.compile(r"(\.(cpp|hpp|h|cc|cxx|hh|cmake)|/CMakeLists\.txt)$")

# A number on its own: not part of a longer number, identifier or version (5.14 matches in
# "= 5.14," and "5.14 m", not in "15.14", "5.145" or "v5.14.2"); integers may carry a ".0".
L = r"(?<![\w.'])"
R = r"(?![\w'])(?!\.\d)"
INT0 = r"(?:\.0+)?"

# The truck as the seed report describes it, each number with the pattern that finds it. Earlier
# entries claim their text first: the 9.74 of `torque_bias_sigma_nm = 9.74` is the engine's torque
# rounding, not the centre of gravity.
MNROAD_TRUCK = [
    # (what it is, the value, pattern)
    ("EEC3 torque-rounding sigma", "9.74",                       # N m, from Table 6.1's 2,386 N m
     r"\b\w*torque\w*\s*(=|\{)\s*9\.740*" + R),
    ("gross mass", "36152", L + r"36[,']?152" + INT0 + R),       # kg, Table 6.1
    ("front axle load", "5307", L + r"5[,']?307" + INT0 + R),    # kg, Table 6.2
    ("drive axle load", "7734", L + r"7[,']?734" + INT0 + R),    # kg, Table 6.2
    ("trailer axle load", "7688.5", L + r"7[,']?688\.50*" + R),  # kg, Table 6.2
    ("first drive axle position", "5.14", L + r"5\.140*" + R),     # m behind the front axle, Table 6.2
    ("second drive axle position", "6.46", L + r"6\.460*" + R),    # m, Table 6.2
    ("first trailer axle position", "16.45", L + r"16\.450*" + R),  # m, Table 6.2
    ("second trailer axle position", "17.69", L + r"17\.690*" + R),  # m, Table 6.2
    ("centre of gravity", "9.74", L + r"9\.740*" + R),            # m behind the front axle (Table 6.2's loads)
    # 6.2 alone is everywhere (Figure 6.2, an SVG character width): only as CdA's value or default.
    ("CdA", "6.2",                                               # m^2, Table 6.1
     r"(?i)\bcda\w*\s*(=|\{|:)\s*6\.20*" + R + r"|\bdefault:?\s*6\.20*" + R
     + r"|\bcda\b[^\n]{0,40}?\b(prior|default)\W{0,3}6\.20*" + R),
    ("engine reference torque", "2386", L + r"2[,']?386" + INT0 + R),  # N m, Table 6.1 (EC1 SPN 544)
    ("engine inertia", "3.824", L + r"3\.8240*" + R),              # kg m^2, Table 6.1 (EC1 SPN 1794)
    ("final drive ratio", "3.36", L + r"3\.360*" + R),             # Table 6.1
    ("gear ratios", "12.80, 9.25", L + r"12\.80?\s*,\s*9\.250*" + R),  # Table 6.1, first two of ten
    ("VIN", "1HSGSSJT8CJ536729", r"1HSGSSJT8CJ536729"),          # Table 6.1
    ("wheel-inertia mass", "936.0", L + r"936\.00*" + R),          # kg, 18 wheel ends (Table 6.2)
    ("front unsprung mass", "421.0", L + r"421\.00*" + R),         # kg, Table 6.2's parts
    ("drive axle unsprung mass", "701.5", L + r"701\.50*" + R),    # kg, Table 6.2's parts
    ("trailer axle unsprung mass", "595.0", L + r"595\.00*" + R),  # kg, Table 6.2's parts
    ("front unsprung mass (report definition)", "178.6", L + r"178\.60*" + R),  # kg, Table 6.1
    ("tandem axle unsprung mass (report definition)", "321.1", L + r"321\.10*" + R),  # kg, Table 6.1
]
PATTERNS = [(what, value, re.compile(pattern)) for what, value, pattern in MNROAD_TRUCK]


def scanned_files(root):
    return common.walk_files(root, SCANNED_DIRS, lambda rel: SCANNED_NAMES.search(rel))


def find_constants(text):
    """(line number, what, value) of every MnROAD number in text, raw (comments included)."""
    found = []
    for number, line in enumerate(text.split("\n"), 1):
        claimed = []
        for what, value, pattern in PATTERNS:
            for m in pattern.finditer(line):
                if any(m.start() < end and start < m.end() for start, end in claimed):
                    continue
                claimed.append((m.start(), m.end()))
                if (number, what, value) not in found:  # once per line
                    found.append((number, what, value))
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    common.add_root_argument(parser)
    args = parser.parse_args()
    common.require_root(parser, args.root, SCANNED_DIRS, any_of=True)

    files = scanned_files(args.root)
    violations = []
    for rel in files:
        for line, what, value in find_constants(common.read_text(os.path.join(args.root, rel))):
            violations.append(f"{rel}:{line}: the MnROAD truck's {what} ({value}) belongs in "
                              "config/vehicles/mnroad-truck.toml")
    return common.report("check_constants", violations, f"{len(files)} source and build files",
                         "MnROAD truck number(s)")


if __name__ == "__main__":
    sys.exit(main())
