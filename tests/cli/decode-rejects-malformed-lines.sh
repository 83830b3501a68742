#!/usr/bin/env bash
# A malformed candump line is reported with file, line and field, the good lines still decode,
# and the exit status says the input was bad.
set -u
roadload=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
printf '%s\n' '(1635188455.029900) can0 0CF00400#607D844A1400F084' \
  '(1635188455.03990) can0 0CF00400#607D844A1400F084' \
  '(1635188455.049900) can0 0CF00400#607D844A1400F0' \
  '(1635188455.059900) can0 0CF00400#607D844A1400F084' >"$dir/can.log"
out=$("$roadload" decode "$dir/can.log" 2>"$dir/err")
status=$?
fail() { echo "FAIL: $*"; cat "$dir/err"; exit 1; }
[[ $status -eq 65 ]] || fail "exit status $status, expected 65"
grep -q "$dir/can.log:2: timestamp: fraction must have 6 or 9 digits" "$dir/err" || fail "line 2 not reported"
[[ $(grep -c 'EngineSpeed=649.25rpm' <<<"$out") -eq 3 ]] || fail "good lines not decoded: $out"
grep -q 'malformed_lines=1' "$dir/err" || fail "summary does not count the bad line"
"$roadload" decode /nonexistent.log 2>"$dir/err"; [[ $? -eq 66 ]] || fail "missing input must exit 66"
grep -q '/nonexistent.log' "$dir/err" || fail "missing input not named"
"$roadload" decode --pgn nope "$dir/can.log" 2>"$dir/err"; [[ $? -eq 64 ]] || fail "bad option must exit 64"
echo "ok"
