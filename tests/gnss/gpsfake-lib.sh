# Shared by the gpsfake tests: the skip when gpsd is missing, a work folder, free ports, and gpsfake
# runs (each with its gpsd, in a process group of their own) and other background processes that
# are ended on exit.
# usage: . gpsfake-lib.sh NAME   (NAME prefixes messages and the work folder)
gf_name=${1:?gpsfake-lib.sh needs a test name}
fail() { echo "$gf_name: FAIL: $*" >&2; exit 1; }
# gpsfake looks for gpsd on PATH and in /usr/sbin, which a user's PATH may lack.
if ! command -v gpsfake >/dev/null || ! PATH=$PATH:/usr/sbin command -v gpsd >/dev/null; then
  [[ ${ROADLOAD_REQUIRE_GPSD:-0} == 1 ]] && fail "gpsd or gpsfake missing (Debian: gpsd, gpsd-clients) and ROADLOAD_REQUIRE_GPSD=1"
  echo "$gf_name: SKIP: gpsd or gpsfake not installed" >&2
  exit 77
fi
work=$(mktemp -d "${TMPDIR:-/tmp}/$gf_name.XXXXXX")
fake_groups=()  # gpsfake runs, each the leader of its process group
background=()   # other processes a test starts in the background
# gpsfake catches SIGTERM and may hang in its handler: a group still there after 2 s is killed.
end_background() {
  local g p
  for p in "${background[@]}"; do kill -TERM "$p" 2>/dev/null || true; done
  for g in "${fake_groups[@]}"; do
    if kill -TERM -- "-$g" 2>/dev/null; then
      for _ in $(seq 20); do
        kill -0 -- "-$g" 2>/dev/null || break
        sleep 0.1
      done
      kill -KILL -- "-$g" 2>/dev/null || true
    fi
    # Its control socket: left behind when it is killed, and when it exits on its own.
    rm -f -- "${TMPDIR:-/tmp}/gpsfake-$g.sock"
  done
  wait 2>/dev/null || true
}
trap 'end_background; rm -rf -- "$work"' EXIT

listening() { [[ -n $(ss -Htln "sport = :$1") ]]; }

free_port() {
  local p
  for _ in $(seq 50); do
    p=$((20000 + RANDOM % 40000))
    listening "$p" || { echo "$p"; return; }
  done
  fail "no free TCP port found"
}

# start_gpsfake PORT LOG: gpsd opens the pty at once (-n) and gets the log once (-1), a sentence every
# 3 ms plus gpsfake's own 1-2 ms; gpsfake stops gpsd and exits 1 s after the last sentence (-W 1).
start_gpsfake() {
  local port=$1 log=$2 out="$work/gpsfake-$1-${#fake_groups[@]}.out"
  setsid gpsfake -1 -n -W 1 -P "$port" -c 0.003 -s 115200 -q "$log" >"$out" 2>&1 &
  fake_groups+=("$!")
  for _ in $(seq 100); do
    listening "$port" && return
    sleep 0.1
  done
  fail "gpsd did not listen on port $port within 10 s; gpsfake said: $(cat "$out")"
}
