"""roadload.collect: results folders into the fleet database (docs/python.md)."""

import subprocess

from . import _errors, _paths


def collect(dirs, db):
    """Adds the drives of the results folders `dirs` to the database `db` (an SQLite file, or
    sqlite:///path, or postgresql://...), as `roadload collect DIR... --db URL` does; a drive
    already there is left unchanged. Raises Error with the command's messages when it fails.

    SWITCH TO THE BINDING: until the C++ fleet library (tools/fleet, roadload::fleet::collect)
    is on this branch, this runs the command; then it calls _core.collect in-process."""
    dirs = [dirs] if isinstance(dirs, str) else list(dirs)
    run = subprocess.run(
        [_paths.program(), "collect", *dirs, "--db", db], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    messages = [line.split(": ", 1)[1] if line.startswith("roadload collect: ") else line for line in run.stderr.splitlines()]
    _errors.check("collect", run.returncode, messages)
    return run.stdout
