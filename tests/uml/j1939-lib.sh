# shellcheck shell=bash
# Helpers shared by the kernel-J1939 scripts that run inside uml-run.
# Sourced, not executed; callers use `set -euo pipefail`.

j1939_prog=${0##*/}

die() {
  echo "$j1939_prog: FAIL: $*" >&2
  exit 1
}

note() {
  echo "$j1939_prog: $*"
}

# The scripts need the guest's vcan0; on the host there is none and every
# socket call would fail with a confusing ENODEV.
require_vcan() {
  local dev=${1:-vcan0}
  ip link show "$dev" >/dev/null 2>&1 ||
    die "no CAN interface $dev here; run this through tests/uml/uml-run"
  local t
  for t in candump cangen j1939cat; do
    if ! command -v "$t" >/dev/null; then
      # Same verdict as a missing linux.uml: this machine cannot run the test.
      echo "$j1939_prog: SKIP: $t not found (install can-utils)" >&2
      exit 77
    fi
  done
}

# A listener started in the background is ready once it owns a socket and
# sleeps in the kernel: candump then waits in select(), j1939cat -r in recv().
# Without this, the first frames of a transfer could go unrecorded, and an RTS
# to a not yet bound address would simply go unanswered. Only builtins in the
# loop: every fork costs tens of milliseconds under UML.
# usage: wait_listening PID...
wait_listening() {
  local pid i fd stat ready
  local -a f
  for ((i = 0; i < 750; i++)); do
    ready=1
    for pid in "$@"; do
      if ! read -r stat 2>/dev/null <"/proc/$pid/stat"; then
        die "listener pid $pid exited before it was ready"
      fi
      read -r -a f <<<"${stat##*) }"
      if [[ ${f[0]} != S ]]; then ready=0; break; fi
      for fd in /proc/"$pid"/fd/*; do
        [[ -S $fd ]] && continue 2
      done
      ready=0
      break
    done
    ((ready)) && return 0
    sleep 0.02
  done
  die "listeners $* did not start listening within 15 s"
}

# can-utils 2020.11's j1939cat reads the socket error queue into a 100-byte
# buffer; kernel 6.1 sends more, so after the transfer has completed (the
# kernel reports TX ACK) it exits 1 with "recvmsg error notification:
# truncated". That exit is a success; anything else is a real error.
j1939_send() {
  local errfile=$1
  shift
  local rc=0
  j1939cat "$@" 2>"$errfile" || rc=$?
  if ((rc == 0)); then
    return 0
  fi
  if ((rc == 1)) && grep -q 'recvmsg error notification: truncated' "$errfile" &&
    [[ $(wc -l <"$errfile") -eq 1 ]]; then
    return 0
  fi
  echo "$j1939_prog: j1939cat $* failed with status $rc:" >&2
  sed 's/^/  | /' "$errfile" >&2
  return 1
}

# Lowercase hex of a whole file, no separators.
hex_of() {
  local hex
  hex=$(od -An -v -tx1 -w65536 "$1")
  echo "${hex// /}"
}

# SIGTERM makes candump leave its loop and flush stdout; j1939cat -r writes
# unbuffered, so TERM loses nothing there either.
stop_and_wait() {
  local pid
  for pid in "$@"; do kill -TERM "$pid" 2>/dev/null || true; done
  for pid in "$@"; do wait "$pid" 2>/dev/null || true; done
}
