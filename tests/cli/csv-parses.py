#!/usr/bin/python3
"""Every CSV the project writes reads back as written: each row as many fields as the header, by
Python's csv module (RFC 4180) and by pandas, and pandas sees the header's columns and no others.
usage: csv-parses.py FILE...  (a folder stands for every *.csv in it)"""
import csv
import pathlib
import sys

import pandas


def files(args):
    for a in args:
        p = pathlib.Path(a)
        yield from sorted(p.glob("*.csv")) if p.is_dir() else [p]


def check(path):
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    if not rows:
        return f"{path}: no header"
    header = rows[0]
    for n, row in enumerate(rows[1:], start=2):
        if len(row) != len(header):
            return f"{path}: data row {n}: {len(row)} fields, the header has {len(header)}"
    frame = pandas.read_csv(path, comment="#", dtype=str, keep_default_na=False)
    if list(frame.columns) != header:
        return f"{path}: pandas reads columns {list(frame.columns)[:6]}..., the header is {header[:6]}..."
    if len(frame) != len(rows) - 1:
        return f"{path}: pandas reads {len(frame)} rows, csv {len(rows) - 1}"
    return None


checked, errors = 0, []
for path in files(sys.argv[1:]):
    checked += 1
    if (e := check(path)) is not None:
        errors.append(e)
for e in errors:
    print(e, file=sys.stderr)
if checked == 0:
    print("csv-parses: no CSV file given", file=sys.stderr)
    sys.exit(1)
print(f"csv-parses: {checked} files, {len(errors)} bad")
sys.exit(1 if errors else 0)
