#!/usr/bin/env python3
"""roadload.decode's frame says what `roadload decode` prints, signal by signal: the same stamps,
interfaces, source addresses, messages and values to the printed digits, in the same order; its
messages per PGN are `decode --pgn-stats`'s frame counts. A malformed line raises InputError
naming file, line and field, with the rest decoded in its `result`.

usage: decode-matches-cli.py ROADLOAD_BIN TRACE...
"""

import csv
import io
import os
import subprocess
import sys
import tempfile

import roadload

roadload_bin, traces = sys.argv[1], sys.argv[2:]
fail = []


def cli_tokens(trace):
    out = subprocess.run([roadload_bin, "decode", trace], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True).stdout
    tokens = []
    for line in out.splitlines():
        words = line.split(" ")
        tokens += [tuple(words[:4]) + (w,) for w in words[4:]]
    return tokens


def frame_tokens(frame):
    stamps = ["(%010d.%06d)" % (ns // 1_000_000_000, ns % 1_000_000_000 // 1000) for ns in frame["t_ns"]]
    tokens = []
    for stamp, row in zip(stamps, frame.itertuples(index=False)):
        value = "%.10g%s" % (row.value, row.unit) if row.state == "valid" else row.state
        tokens.append((stamp, row.iface, "%02X" % row.sa, row.message, "%s=%s" % (row.signal, value)))
    return tokens


for trace in traces:
    name = os.path.basename(trace)
    frame = roadload.decode(trace)
    want, got = cli_tokens(trace), frame_tokens(frame)
    if len(want) < 1000 or want != got:
        first = next((i for i, (w, g) in enumerate(zip(want, got)) if w != g), min(len(want), len(got)))
        fail.append("%s: %d signals printed, %d in the frame; first difference at %d: %s vs %s"
                    % (name, len(want), len(got), first, want[first:first + 1], got[first:first + 1]))
        continue
    stats = subprocess.run([roadload_bin, "decode", "--pgn-stats", trace], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    messages = frame.groupby(["pgn"], observed=True)[["t_ns", "sa"]].apply(lambda g: len(g.drop_duplicates()))
    compared = 0
    for row in csv.DictReader(io.StringIO(stats.stdout)):
        pgn = int(row["pgn"])
        if not row["name"] or int(row["tp_messages"]) > 0:
            continue  # unknown to the definitions, or reassembled from several frames
        compared += 1
        if messages.get(pgn, 0) != int(row["frames"]):
            fail.append("%s: PGN %d (%s): %d messages in the frame, %s frames in --pgn-stats"
                        % (name, pgn, row["name"], messages.get(pgn, 0), row["frames"]))
    print("%s: %d signals equal to decode's, %d PGNs' counts equal to --pgn-stats" % (name, len(got), compared))
    if compared < 5:
        fail.append("%s: only %d PGNs compared" % (name, compared))

only = roadload.decode(traces[0], pgn=[61444])
if set(only["message"]) != {"EEC1"} or len(only) == 0:
    fail.append("pgn=[61444] gave messages %s" % sorted(set(only["message"])))

with tempfile.TemporaryDirectory() as work:
    bad = os.path.join(work, "bad.log")
    with open(traces[0]) as f:
        lines = f.readlines()
    lines[4] = "(1600000000.000000) can0 18FEF1XX#FFFFFFFFFFFFFFFF\n"
    with open(bad, "w") as f:
        f.writelines(lines)
    try:
        roadload.decode(bad)
        fail.append("a malformed line raised nothing")
    except roadload.InputError as e:
        if e.status != 65 or "bad.log:5:" not in str(e) or e.result is None or len(e.result) < 1000:
            fail.append("malformed line: status %d, %r, result %s" % (e.status, str(e), None if e.result is None else len(e.result)))
    try:
        roadload.decode(os.path.join(work, "none"))
        fail.append("a missing recording raised nothing")
    except roadload.InputError as e:
        if e.status != 66 or "none" not in str(e):
            fail.append("missing recording: status %d, %r" % (e.status, str(e)))

if fail:
    sys.exit("decode-matches-cli: FAIL:\n  " + "\n  ".join(fail))
print("decode-matches-cli: PASS")
