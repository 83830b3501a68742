#!/usr/bin/env bash
# Smoke test for uml-run's guest: cangen writes N frames on vcan0 while
# candump -L records them; every frame must arrive, in the log format the
# project's tools read.
# usage (inside UML): vcan-smoke.sh [N]   (default 500)
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=j1939-lib.sh source-path=SCRIPTDIR
. "$here/j1939-lib.sh"

n=${1:-500}
[[ $n =~ ^[1-9][0-9]*$ ]] || die "frame count must be a positive integer, got '$n'"
require_vcan vcan0

log=$(mktemp "${TMPDIR:-/tmp}/vcan-smoke.XXXXXX")
trap 'rm -f -- "$log"' EXIT

candump -L vcan0 >"$log" &
dump=$!
wait_listening "$dump"
# -g 1 -p 100: pace the frames and wait out ENOBUFS instead of dropping them.
cangen -n "$n" -g 1 -p 100 -e vcan0 || die "cangen failed with status $?"
sleep 0.2
stop_and_wait "$dump"

got=$(grep -cE '^\([0-9]+\.[0-9]{6}\) vcan0 [0-9A-F]{8}#[0-9A-F]{0,16}$' "$log" || true)
lines=$(wc -l <"$log")
((got == n && lines == n)) ||
  die "sent $n frames, candump logged $lines lines of which $got are well-formed extended frames"
note "PASS: $n frames sent and recorded on vcan0"
