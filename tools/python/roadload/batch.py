"""roadload batch: the analysis of many recordings on Dask distributed (docs/python.md).

    python3 -m roadload.batch MANIFEST --db URL [--scheduler ADDRESS | --workers N] [-o DIR]

is what `roadload batch` runs. Each drive is one Dask task on a worker process: roadload.analyze
in-process into DIR/<drive>/, then roadload.collect into the database. With --scheduler the
tasks go to a running scheduler whose workers were started apart (`dask worker ADDRESS
--nthreads 1`, on any machine that reads the recordings); with --workers N to a local cluster of
N processes of one thread. A failed drive is told with its error as it fails, and the run exits
non-zero at the end; the others go on.
"""

import argparse
import collections
import logging
import os
import socket
import sys
import time
import warnings

from . import _analysis, _collect, _errors, _manifest

EXIT_FAILED, EXIT_DATA, EXIT_UNAVAILABLE = 1, 65, 69


def analyze_drive(drive, out, db):
    """One task, on a worker: the drive's analysis into out/<name>/, then its results into the
    database. Returns what the client tells of it; a failure raises, with the C++'s message."""
    start = time.monotonic()
    folder = os.path.join(out, drive.name)
    input_errors = []
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always", _errors.Warning)
        try:
            result = _analysis.analyze(drive.recordings, drive.vehicle, drive.route, folder, **drive.options)
        except _errors.InputError as e:
            if e.result is None:  # nothing analysed: no results to collect
                raise
            result, input_errors = e.result, e.messages
    _collect.collect([folder], db)
    return {
        "name": drive.name,
        "seconds": time.monotonic() - start,
        "worker": "%s:%d" % (socket.gethostname(), os.getpid()),
        "crr": result.trip.get("crr"),
        "messages": [str(w.message) for w in said] if not input_errors else [],
        "input_errors": input_errors,
    }


class Progress:
    """Drives done of the total, failures and the time left, on standard error: one line a drive."""

    def __init__(self, total):
        self.total, self.done, self.failed, self.start = total, 0, 0, time.monotonic()

    def tell(self, failed=False):
        self.done += 1
        self.failed += failed
        wall = time.monotonic() - self.start
        left = wall * (self.total - self.done) / self.done
        print(
            "batch: %d/%d drives done, %d failed, %.0f s, about %.0f s left" % (self.done, self.total, self.failed, wall, left),
            file=sys.stderr,
            flush=True,
        )


def run(client, drives, out, db):
    """Submits every drive and tells each as it ends. Returns the exit status."""
    from distributed import as_completed

    futures = {client.submit(analyze_drive, d, out, db, key="roadload-%s-%d" % (d.name, i), pure=False): d for i, d in enumerate(drives)}
    progress = Progress(len(drives))
    failed, malformed, workers = [], [], collections.Counter()
    for future in as_completed(futures):
        drive = futures[future]
        if future.status != "finished":
            error = future.exception()
            failed.append(drive.name)
            print("batch: %s (manifest line %d) FAILED: %s" % (drive.name, drive.line, error), file=sys.stderr, flush=True)
            progress.tell(failed=True)
            continue
        done = future.result()
        workers[done["worker"]] += 1
        for m in done["messages"]:
            print("batch: %s: %s" % (drive.name, m), file=sys.stderr)
        if done["input_errors"]:
            malformed.append(drive.name)
            for m in done["input_errors"]:
                print("batch: %s: malformed input, analysed and collected: %s" % (drive.name, m), file=sys.stderr)
        progress.tell()
    wall = time.monotonic() - progress.start
    print(
        "batch: %d drives in %.1f s (%.3f drives/s); %d failed%s; %d with malformed input"
        % (len(drives), wall, len(drives) / wall, len(failed), ": " + ", ".join(failed) if failed else "", len(malformed)),
        file=sys.stderr,
    )
    print("batch: drives per worker: %s" % ", ".join("%s %d" % w for w in sorted(workers.items())), file=sys.stderr)
    return EXIT_FAILED if failed else EXIT_DATA if malformed else 0


def _arguments(argv):
    p = argparse.ArgumentParser(prog="roadload batch", description=__doc__.split("\n\n")[0])
    p.add_argument("manifest")
    p.add_argument("--db", required=True, help="an SQLite file, sqlite:///path or postgresql://...")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--scheduler", help="a running Dask scheduler, tcp://host:8786")
    where.add_argument("--workers", type=int, help="a local cluster of N worker processes (default: one per core)")
    p.add_argument("-o", "--out", default="batch-results", help="DIR/<drive>/ for each drive's results")
    a = p.parse_args(argv)
    if a.workers is not None and a.workers < 1:
        p.error("--workers: %d is not a whole number in 1..1024" % a.workers)
    return a


def _connect(a):
    """A client of the scheduler given, or of a local cluster of processes of one thread each:
    the analysis holds Python's lock only between drives, but one drive keeps a core busy."""
    from distributed import Client, LocalCluster

    if a.scheduler:
        return Client(a.scheduler, timeout="30s"), None
    # The workers' own warnings of a failed task are the lines run() prints, with the drive named.
    cluster = LocalCluster(
        n_workers=a.workers or os.cpu_count() or 1,
        threads_per_worker=1,
        processes=True,
        dashboard_address=None,
        silence_logs=logging.ERROR,
    )
    return Client(cluster), cluster


def main(argv=None):
    a = _arguments(argv)
    try:
        drives = _manifest.read(a.manifest)
    except (_errors.Error, OSError) as e:
        print("roadload batch: %s" % e, file=sys.stderr)
        return EXIT_DATA if isinstance(e, _errors.Error) else 66
    out = os.path.abspath(a.out)
    # A plain path is the client's; the workers get it whole. A URL is the database's own.
    db = a.db if "://" in a.db else os.path.abspath(a.db)
    try:
        client, cluster = _connect(a)
    except OSError as e:
        print("roadload batch: %s: %s" % (a.scheduler or "local cluster", e), file=sys.stderr)
        return EXIT_UNAVAILABLE
    try:
        workers = len(client.scheduler_info()["workers"])
        print("batch: %d drives on %d workers (%s), results in %s" % (len(drives), workers, a.scheduler or "local", out), file=sys.stderr)
        return run(client, drives, out, db)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


if __name__ == "__main__":
    sys.exit(main())
