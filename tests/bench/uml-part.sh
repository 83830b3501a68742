# Sourced by the benchmarks that run part of themselves in User-Mode Linux (a kernel with vcan).
# run_uml_part NAME WORK SCRIPT ARGS...: runs `SCRIPT --kernel-part WORK ARGS...` in UML; exits 0
# with a note when UML cannot run here (uml-run's 77), and 1 naming the daemon's error when the
# part fails.
run_uml_part() {
  local name=$1 work=$2 script=$3 rc=0
  shift 3
  "$(dirname "${BASH_SOURCE[0]}")/../uml/uml-run" --timeout 600 -- "$script" --kernel-part "$work" "$@" || rc=$?
  if ((rc == 77)); then
    echo "$name: skipped (uml-run: no UML kernel, or one this CPU cannot run)"
    exit 0
  fi
  ((rc == 0)) || { echo "$name: the UML part failed (status $rc): $(cat "$work/daemon.err" 2>/dev/null)" >&2; exit 1; }
}
