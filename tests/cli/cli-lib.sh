# Shared by the CLI test scripts: a work folder removed on exit, failure with a message, and
# running a command while checking its exit status (stdout in $work/out, stderr in $work/err).
# usage: . cli-lib.sh NAME   (NAME prefixes messages and the work folder)
cli_name=${1:?cli-lib.sh needs a test name}
work=$(mktemp -d "${TMPDIR:-/tmp}/$cli_name.XXXXXX")
trap 'rm -rf -- "$work"' EXIT
fail() { echo "$cli_name: FAIL: $*" >&2; exit 1; }
# tests/support: helpers the CLI, UML and benchmark scripts share.
support=$(cd "$(dirname "${BASH_SOURCE[0]}")/../support" && pwd)
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
# Renders PAGE in headless Chromium with SCRIPT run after layout (it writes its finding into
# <pre id="roadload-check">) and prints that finding. Exits 77 (skipped) when there is no Chromium,
# unless ROADLOAD_REQUIRE_CHROMIUM=1. SCRIPT goes in on one line through sed's s###: no //
# comments and no ampersands.
render_check() {
  local page=$1 script=$2 chromium
  chromium=$(command -v chromium || true)
  if [[ -z $chromium ]]; then
    [[ ${ROADLOAD_REQUIRE_CHROMIUM:-0} == 1 ]] && fail "chromium is missing (scripts/setup installs it)"
    echo "$cli_name: SKIPPED the rendering (no chromium)"
    exit 77
  fi
  local check="<pre id=\"roadload-check\"></pre><script>$script</script>"
  sed "s#</body>#${check//$'\n'/ }</body>#" "$page" >"$work/check.html"
  timeout 120 "$chromium" --headless=new --no-sandbox --disable-gpu --no-first-run --user-data-dir="$work/profile" \
    --dump-dom "file://$work/check.html" >"$work/dom.html" 2>"$work/chromium.err" || fail "chromium failed: $(tail -5 "$work/chromium.err")"
  sed -n 's#.*<pre id="roadload-check">\([^<]*\)</pre>.*#\1#p' "$work/dom.html"
}
