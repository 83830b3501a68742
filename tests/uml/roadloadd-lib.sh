# shellcheck shell=bash
# Helpers for the scripts that run the real roadloadd inside uml-run. Sourced after j1939-lib.sh.

# Starts roadloadd in the background on vcan0 with its files under $1; sets $daemon to its pid.
# Extra arguments go to roadloadd.
start_daemon() {
  local dir=$1
  shift
  "$roadloadd" --can vcan0 --no-gnss --data-dir "$dir/rec" --status "$dir/status.log" \
    --status-json "$dir/status.jsonl" "$@" 2>"$dir/daemon.err" &
  daemon=$!
  wait_status_lines "$dir" 1
}

# Waits until the status log holds at least N status lines (the start line does not count).
wait_status_lines() {
  local dir=$1 n=$2 i
  for ((i = 0; i < 300; i++)); do
    if [[ -f $dir/status.jsonl ]] && (($(wc -l <"$dir/status.jsonl") >= n)); then return 0; fi
    kill -0 "$daemon" 2>/dev/null || die "roadloadd exited early: $(cat "$dir/daemon.err")"
    sleep 0.1
  done
  die "roadloadd wrote fewer than $n status lines in 30 s"
}

# A numeric field of the last JSON status line, first occurrence (e.g. "lines_lost", "dropped").
last_status_field() {
  local dir=$1 field=$2 line
  line=$(tail -n 1 "$dir/status.jsonl")
  line=${line#*\"$field\":}
  echo "${line%%[,\}]*}"
}

# Waits until the daemon's status counts N items read, or the count has not moved for 3 s; at most 60 s.
wait_status_items() {
  local dir=$1 n=$2 i items last=-1 still=0
  for ((i = 0; i < 600; i++)); do
    items=$(last_status_field "$dir" items)
    ((items >= n)) && return 0
    if ((items == last)); then ((++still >= 30)) && return 0; else still=0; fi
    last=$items
    sleep 0.1
  done
}

# Frames the kernel's per-CPU receive backlogs dropped since boot (second column of softnet_stat).
softnet_dropped() {
  local total=0 _ dropped _rest
  while read -r _ dropped _rest; do total=$((total + 16#$dropped)); done </proc/net/softnet_stat
  echo "$total"
}

# The frames of a candump -L log without their stamps and interface: ID#DATA, one per line.
frames_of() {
  cut -d' ' -f3 "$@"
}

# SIGTERM and wait; returns the daemon's exit status.
stop_daemon() {
  kill -TERM "$daemon"
  local rc=0
  wait "$daemon" || rc=$?
  return "$rc"
}

# A candump -L log of N extended frames SPACING_US apart whose payloads count up from FIRST.
gen_frames() {
  local n=$1 spacing_us=$2 first=${3:-0}
  awk -v n="$n" -v s="$spacing_us" -v f="$first" 'BEGIN {
    for (i = 0; i < n; i++) {
      t = i * s
      printf "(%d.%06d) can0 %08X#%08X%08X\n", 1000 + int(t / 1e6), t % 1000000, 419299328 + (f + i) % 65536, f + i, (f + i) * 7 % 4294967296
    }
  }'
}

# Every frame the daemon recorded so far, across its segments, in order: its can.log.zst, each
# frame of which zstd reads back (a frame cut short fails the test), or a plain can.log.
recorded_frames() {
  local dir=$1
  shopt -s nullglob
  local logs=("$dir"/rec/*/can.log*)
  shopt -u nullglob
  ((${#logs[@]})) && { zstd -dcqf "${logs[@]}" || die "a recorded can.log does not decompress: ${logs[*]}"; } | frames_of
  return 0
}

# Waits (up to 20 s) until the status log's newest line matches the extended regex.
wait_status_match() {
  local dir=$1 pattern=$2 i
  for ((i = 0; i < 200; i++)); do
    tail -n 1 "$dir/status.log" | grep -Eq -- "$pattern" && return 0
    sleep 0.1
  done
  die "no status line matching '$pattern' within 20 s; last: $(tail -n 1 "$dir/status.log")"
}

# A drive replayed into roadloadd as a truck would deliver it: roadloadd on vcan0 with the sensor
# streams of $1/sim through its replay drivers, `roadload replay` sending the CAN frames at RATE
# (extra arguments go to roadload replay; roadloadd's own, if any, are in the array daemon_args),
# then a clean stop once the replayed accelerometer stream has ended. Results in $1/live, recording
# in $1/rec, status in $1/status.log.
replay_into_daemon() {
  local work=$1 replay_route=$2 replay_rate=$3
  shift 3
  "$roadloadd" --can vcan0 --no-gnss --replay "$work/sim" --replay-origin "$work/origin.toml" --route "$replay_route" \
    --results "$work/live" --data-dir "$work/rec" --status "$work/status.log" --status-json "$work/status.jsonl" \
    ${daemon_args[@]+"${daemon_args[@]}"} 2>"$work/daemon.err" &
  daemon=$!
  # The daemon opens vcan0 and then sleeps until the replay writes its origin: frames sent before
  # it owns its socket would be lost, and a fixed pause is too short on a loaded host.
  wait_listening "$daemon"
  "$roadload" replay "$work/sim" --iface vcan0 --rate "$replay_rate" --origin "$work/origin.toml" -q "$@" 2>"$work/replay.err" ||
    die "roadload replay failed with status $?: $(cat "$work/replay.err")"
  local i
  for ((i = 0; i < 300; i++)); do
    tail -n 1 "$work/status.jsonl" | grep -q '"name":"accel","kind":"accelerometer","state":"ended"' && break
    sleep 0.2
  done
  sleep 1
  kill -0 "$daemon" || die "roadloadd is gone before the end of the drive: $(cat "$work/daemon.err")"
  stop_daemon || die "roadloadd exited with status $?: $(cat "$work/daemon.err")"
}
