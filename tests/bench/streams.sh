#!/usr/bin/env bash
# The recorder's streams, plain and compressed, and the accelerometer layouts a recorder could
# write: a simulated highway drive (eight three-axis accelerometers with their noise) through
# bench_streams and accel_layout.py. ROADLOAD_BENCH_STREAM_SECONDS sizes the drive (default 120).
# usage: tests/bench/streams.sh BUILD_DIR
set -euo pipefail
build=${1:?usage: streams.sh BUILD_DIR}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
seconds=${ROADLOAD_BENCH_STREAM_SECONDS:-120}
work=$(mktemp -d "${TMPDIR:-/tmp}/bench-streams.XXXXXX")
trap 'rm -rf -- "$work"' EXIT
"$build/tools/roadload" simulate --scenario highway-1h --seed 1 --duration "$seconds" --out "$work/sim" -q
"$build/tests/bench/bench_streams" "$work/sim" "$seconds"
/usr/bin/python3 "$here/accel_layout.py" "$work/sim" "$seconds"
