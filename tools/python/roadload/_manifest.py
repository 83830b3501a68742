"""A batch's manifest: a CSV with the header recording,vehicle,route (docs/python.md). Each row
is one drive: its segments joined by "+", an empty vehicle or route for the recording's
meta.toml or the road its own GNSS traces. An optional column `name` names the drive's results
folder (default: the first segment's folder name, with as many of its parents as it takes to
tell the drives apart); any further column is an option of `roadload analyze` (mass, cda,
engine_losses, ...) for that drive, empty where not given."""

import collections
import csv
import dataclasses
import os

from . import _errors, _paths

REQUIRED = ("recording", "vehicle", "route")


@dataclasses.dataclass
class Drive:
    name: str
    recordings: list
    vehicle: str = None
    route: str = None
    options: dict = dataclasses.field(default_factory=dict)
    line: int = 0


def _error(path, line, field, text):
    where = "%s:%d: %s" % (path, line, field) if field else "%s:%d" % (path, line)
    message = "%s: %s" % (where, text)
    return _errors.InputError(message, 65, [message])


def _path(base, value):
    """A file beside the manifest: relative paths are the manifest folder's. A built-in route or
    vehicle name (no "/" and no .toml) is left as the name."""
    if os.path.isabs(value) or ("/" not in value and not value.endswith(".toml")):
        return value
    return os.path.normpath(os.path.join(base, value))


def _tails(paths):
    """Each path's last folder name, joined with as many of its parents ("truck7-day2-rec") as
    it takes to tell it from the others' (fleets name every run's folder alike)."""
    parts = [p.strip(os.sep).split(os.sep) for p in paths]
    depth = [1] * len(parts)
    while True:
        names = ["-".join(p[-d:]) for p, d in zip(parts, depth)]
        count = collections.Counter(names)
        longer = [i for i, n in enumerate(names) if count[n] > 1 and depth[i] < len(parts[i])]
        if not longer:
            return names
        for i in longer:
            depth[i] += 1


def _option(path, line, key, text, flags):
    if key in flags:
        if text.lower() not in ("1", "true", "yes", "0", "false", "no"):
            raise _error(path, line, key, "%r is not a flag's value (1 or 0)" % text)
        return text.lower() in ("1", "true", "yes")
    return _path(os.path.dirname(path), text) if key in ("engine_losses", "grade", "truth", "dbc") else text


def read(path):
    """The drives of the manifest at `path`; a malformed one raises InputError naming its line
    and field, before any drive is analysed."""
    base = os.path.dirname(os.path.abspath(path))
    known = {n.replace("-", "_"): flag for n, flag in _paths.core().analyze_options() if n not in ("out", "help", "version")}
    flags = {k for k, flag in known.items() if flag}
    drives, seen = [], {}
    with open(path, newline="", encoding="utf-8") as f:
        rows = csv.DictReader(f)
        header = rows.fieldnames or []
        for column in REQUIRED:
            if column not in header:
                raise _error(path, 1, column, "missing: the header is recording,vehicle,route[,name][,option...]")
        for column in header:
            if column not in REQUIRED + ("name",) and column not in known:
                raise _error(path, 1, column, "neither recording, vehicle, route, name nor an option of roadload analyze")
        for row in rows:
            line = rows.line_num
            segments = [s.strip() for s in (row["recording"] or "").split("+") if s.strip()]
            if not segments:
                raise _error(path, line, "recording", "empty")
            options = {
                k: _option(path, line, k, v.strip(), flags)
                for k, v in row.items()
                if k not in REQUIRED + ("name",) and v is not None and v.strip()
            }
            drives.append(
                Drive(
                    (row.get("name") or "").strip(),
                    [os.path.normpath(os.path.join(base, s)) for s in segments],
                    _path(base, row["vehicle"].strip()) if (row["vehicle"] or "").strip() else None,
                    _path(base, row["route"].strip()) if (row["route"] or "").strip() else None,
                    options,
                    line,
                )
            )
    if not drives:
        raise _error(path, 1, "", "no drive in the manifest")
    first = {}
    for d in drives:
        line = first.setdefault(tuple(d.recordings), d.line)
        if line != d.line:
            raise _error(path, d.line, "recording", "the same drive as line %d's" % line)
    for d, tail in zip(drives, _tails([d.recordings[0] for d in drives])):
        d.name = d.name or tail
        if d.name in seen:
            raise _error(path, d.line, "name", "%r is line %d's drive too: give each its own name" % (d.name, seen[d.name]))
        seen[d.name] = d.line
    return drives
