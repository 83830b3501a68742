"""Where this copy of the package finds what it runs: the compiled extension, the data folder
(J1939 definitions, routes, vehicles) and the roadload program, all relative to the package, as
_layout.py (written by CMake) says for the build tree and for the installed package."""

import os
import shutil

from . import _layout

_HERE = os.path.dirname(os.path.abspath(__file__))


def _beside(path):
    return path if os.path.isabs(path) else os.path.normpath(os.path.join(_HERE, path))


def data_dir():
    return _beside(_layout.DATADIR)


def core():
    """The extension, once the C++ knows its data folder. ROADLOAD_DATADIR is the C++'s own
    setting (drivers/src/definitions.cpp); a user's value is kept. The C++ cannot find the folder
    beside the running program, as the CLI does: here the program is python3."""
    if not os.environ.get("ROADLOAD_DATADIR") and os.path.isfile(os.path.join(data_dir(), "j1939-core.dbc")):
        os.environ["ROADLOAD_DATADIR"] = data_dir()
    from . import _core

    return _core


def program():
    """The roadload program of this copy: $ROADLOAD_PROGRAM, else the one beside the package (the
    build tree's or the same install's), else the first on PATH."""
    given = os.environ.get("ROADLOAD_PROGRAM")
    if given:
        return given
    beside = _beside(_layout.PROGRAM)
    if os.access(beside, os.X_OK):
        return beside
    found = shutil.which("roadload")
    if found is None:
        raise FileNotFoundError("roadload: the program is neither beside the package (%s) nor on PATH" % beside)
    return found
