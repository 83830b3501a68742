"""roadload.collect: results folders into the fleet database (docs/fleet.md), in-process."""

import os

from . import _errors, _paths


def collect(dirs, db):
    """Adds the drives of the results folders `dirs` (one folder or a list) to the database `db`
    (an SQLite file, sqlite:///path or postgresql://...), as `roadload collect DIR... --db URL`
    does, the C++ fleet library running with Python's lock released. Each drive is one
    transaction; a drive already there is unchanged, one analysed again replaced. Returns the
    counts: drives_added, drives_unchanged, drives_replaced, sections_added, section_results,
    schema_from. A folder that cannot be read raises InputError (65), a database that cannot be
    written OutputError (73), each naming the file or the database's error."""
    dirs = [dirs] if isinstance(dirs, (str, os.PathLike)) else list(dirs)
    status, messages, summary = _paths.core().collect([os.fspath(d) for d in dirs], os.fspath(db))
    _errors.check("collect", status, messages)
    return summary
