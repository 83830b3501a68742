# Shared by the CLI test scripts: a work folder removed on exit, failure with a message, and
# running a command while checking its exit status (stdout in $work/out, stderr in $work/err).
# usage: . cli-lib.sh NAME   (NAME prefixes messages and the work folder)
cli_name=${1:?cli-lib.sh needs a test name}
work=$(mktemp -d "${TMPDIR:-/tmp}/$cli_name.XXXXXX")
trap 'rm -rf -- "$work"' EXIT
fail() { echo "$cli_name: FAIL: $*" >&2; exit 1; }
# Each CSV file (or every *.csv of a folder) reads back with Python's csv module and pandas.
# $work/out and $work/err stay the last command's.
expect_csv() {
  /usr/bin/python3 "$(dirname "${BASH_SOURCE[0]}")/csv-parses.py" "$@" >"$work/csv.out" 2>"$work/csv.err" ||
    fail "CSV that does not read back: $(cat "$work/csv.err")"
}
expect_status() {
  local want=$1; shift
  local got=0
  "$@" >"$work/out" 2>"$work/err" || got=$?
  ((got == want)) || fail "'$*' exited $got, expected $want; stderr: $(cat "$work/err")"
}
