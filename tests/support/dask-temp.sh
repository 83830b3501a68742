# A throw-away Dask cluster for a test, started as a user starts one: a scheduler and N workers,
# each its own process (Debian's dask-scheduler and dask-worker), on a port the system picks.
# Source this file, then:  address=$(dask_temp_start DIR N)  ...  dask_temp_stop DIR
# No nanny: each worker is the one process started here, so stopping it leaves nothing behind.

dask_temp_start() {
  local dir=$1 n=$2 address w
  mkdir -p "$dir"
  (cd "$dir" && exec dask-scheduler --host 127.0.0.1 --port 0 --no-dashboard --scheduler-file "$dir/scheduler.json" \
    >"$dir/scheduler.log" 2>&1) &
  echo $! >>"$dir/pids"
  for _ in $(seq 200); do [[ -s $dir/scheduler.json ]] && break; sleep 0.1; done
  address=$(sed -n 's/.*"address": "\([^"]*\)".*/\1/p' "$dir/scheduler.json" 2>/dev/null)
  [[ $address == tcp://127.0.0.1:* ]] || { echo "dask_temp_start: no scheduler: $(cat "$dir/scheduler.log")" >&2; return 1; }
  for ((w = 1; w <= n; w++)); do
    (cd "$dir" && exec dask-worker "$address" --nthreads 1 --no-nanny --no-dashboard --name "w$w" \
      --local-directory "$dir/w$w" >"$dir/worker$w.log" 2>&1) &
    echo $! >>"$dir/pids"
  done
  for _ in $(seq 300); do
    (($(cat "$dir"/worker*.log | grep -c "Registered to") == n)) && break
    sleep 0.1
  done
  (($(cat "$dir"/worker*.log | grep -c "Registered to") == n)) ||
    { echo "dask_temp_start: workers did not register: $(cat "$dir"/worker*.log)" >&2; return 1; }
  echo "$address"
}

dask_temp_stop() {
  local dir=$1 p
  [[ -f $dir/pids ]] || return 0
  while read -r p; do kill "$p" 2>/dev/null || true; done <"$dir/pids"
  while read -r p; do
    for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
  done <"$dir/pids"
  rm -f "$dir/pids"
}
