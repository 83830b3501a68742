"""roadload.analyze and roadload.read_results: the C++ analysis of `roadload analyze`, run
in-process, and its results folder as pandas frames."""

import dataclasses
import json
import os
import shutil
import tempfile

import pandas as pd

from . import _errors, _paths


@dataclasses.dataclass
class Results:
    """A drive's results: `trip` is trip.json (the trip's CRR, fuel breakdown, provenance, the
    pavements and spectra), `cells` is cells.csv (one row per cell), `pavements` pavements.csv
    (one row per pavement type); `dir` the folder they were read from (None when analyze wrote
    them to a temporary folder, since removed); `messages` what the analysis said of the drive."""

    trip: dict
    cells: pd.DataFrame
    pavements: pd.DataFrame
    dir: str = None
    messages: list = dataclasses.field(default_factory=list)


def read_results(dir):
    """The results folder of `roadload analyze` (or roadload.analyze(out=...)) as Results.
    A missing or unreadable file raises InputError naming it."""
    dir = os.fspath(dir)
    try:
        with open(os.path.join(dir, "trip.json"), encoding="utf-8") as f:
            trip = json.load(f)
        cells = pd.read_csv(os.path.join(dir, "cells.csv"))
        pavements = pd.read_csv(os.path.join(dir, "pavements.csv"))
    except OSError as e:
        raise _errors.InputError("%s: %s" % (e.filename, e.strerror), 66, ["%s: %s" % (e.filename, e.strerror)]) from e
    except (ValueError, pd.errors.ParserError) as e:
        raise _errors.InputError("%s: %s" % (dir, e), 65, ["%s: %s" % (dir, e)]) from e
    return Results(trip, cells, pavements, dir)


def _option_words(options):
    """Keywords as `roadload analyze`'s options: cda_sigma=0.3 is --cda-sigma 0.3, estimate_cda=True
    is --estimate-cda, dbc=[a, b] is --dbc a --dbc b. Unknown keywords are refused here, naming
    the options there are."""
    known = dict(_paths.core().analyze_options())
    words = []
    for key, value in options.items():
        name = key.replace("_", "-")
        if name not in known or name in ("out", "help", "version"):
            raise _errors.UsageError(
                "roadload.analyze: unknown keyword %r; the options of `roadload analyze` are: %s"
                % (key, ", ".join(sorted(n.replace("-", "_") for n in known if n not in ("out", "help", "version")))),
                64,
            )
        if value is None or value is False:
            continue
        if known[name]:  # a flag
            if value is not True:
                raise _errors.UsageError("roadload.analyze: %s is a flag: True or False, not %r" % (key, value), 64)
            words.append("--" + name)
            continue
        for v in value if isinstance(value, (list, tuple)) else [value]:
            words += ["--" + name, repr(v) if isinstance(v, float) else os.fspath(v) if isinstance(v, os.PathLike) else str(v)]
    return words


def analyze(recordings, vehicle=None, route=None, out=None, *, progress=False, **options):
    """Analyses one drive as `roadload analyze RECORDING... [--vehicle V] [--route R] -o OUT` with
    the same options as keywords (mass=36000, cda=6.2, estimate_cda=True, dbc=[...]; see
    `roadload analyze --help`), in this process, Python's lock released while it runs.

    `recordings`: a recording folder or can.log, or a list of one drive's segments. `out`: the
    results folder; None analyses into a temporary folder, read and removed. `progress`: how far
    along a long drive is, on standard error. Returns Results. Errors raise UsageError (a bad
    option), InputError (a missing or malformed input; on malformed lines the results are made
    all the same, in the error's `result`) or OutputError; what the analysis says of a drive it
    analysed (an assumed vehicle, a sensor mounted upside down) is warned as roadload.Warning
    and kept in Results.messages."""
    if isinstance(recordings, (str, os.PathLike)):
        recordings = [recordings]
    # The command line takes a word starting with "-" for an option, not a folder.
    recordings = ["./" + r if r.startswith("-") else r for r in map(os.fspath, recordings)]
    words = _option_words(dict(options, vehicle=vehicle, route=route))
    temporary = tempfile.mkdtemp(prefix="roadload-") if out is None else None
    folder = temporary or os.fspath(out)
    try:
        status, messages = _paths.core().analyze(recordings + words + ["--out", folder], progress)
        result = None
        if status in (0, 65):
            result = read_results(folder)
            result.dir = None if temporary else folder
            result.messages = messages
    finally:
        if temporary:
            shutil.rmtree(temporary, ignore_errors=True)
    _errors.check("analyze", status, messages, result)
    return result
