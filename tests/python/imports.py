#!/usr/bin/env python3
"""The package imports from the build tree, as one folder: roadload and its compiled extension,
both from BUILD/python, of the version the build is.

usage: imports.py BUILD/python VERSION
"""

import os
import sys

import roadload
from roadload import _core

folder, version = os.path.realpath(sys.argv[1]), sys.argv[2]
fail = []
for module in (roadload, _core):
    where = os.path.realpath(module.__file__)
    if not where.startswith(folder + os.sep):
        fail.append("%s comes from %s, not %s" % (module.__name__, where, folder))
if roadload.__version__ != version:
    fail.append("roadload.__version__ is %r, the build's %r" % (roadload.__version__, version))
for name in ("decode", "analyze", "read_results", "collect", "Results", "InputError"):
    if not hasattr(roadload, name):
        fail.append("roadload.%s is missing" % name)
import roadload.batch  # noqa: E402,F401 (the Dask runner imports with the package)

if fail:
    sys.exit("imports: FAIL: " + "; ".join(fail))
print("imports: PASS (roadload %s from %s)" % (roadload.__version__, folder))
