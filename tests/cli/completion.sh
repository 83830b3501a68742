#!/usr/bin/env bash
# Bash completion as a user's shell runs it: bash-completion and the installed scripts sourced,
# each program asked for its own words. A command, an option of a command, an option of the daemon,
# and a file where an option takes one.
# usage: completion.sh ROADLOAD_BIN ROADLOADD_BIN COMPLETION_DIR
set -uo pipefail  # not -e: bash-completion's functions return non-zero in their normal course
roadload=$(realpath "${1:?usage: completion.sh ROADLOAD_BIN ROADLOADD_BIN COMPLETION_DIR}")
roadloadd=$(realpath "${2:?usage: completion.sh ROADLOAD_BIN ROADLOADD_BIN COMPLETION_DIR}")
scripts=${3:?usage: completion.sh ROADLOAD_BIN ROADLOADD_BIN COMPLETION_DIR}
. "$(dirname "$0")/cli-lib.sh" completion
[[ -r /usr/share/bash-completion/bash_completion ]] || { echo "completion: no bash-completion here; skipped"; exit 77; }
. /usr/share/bash-completion/bash_completion
. "$scripts/roadloadd"  # which sources roadload's, as bash-completion would load both

# The words offered for the last of "$@" (the command line up to the cursor), one a line.
complete_words() {
  COMP_WORDS=("$@")
  COMP_CWORD=$(($# - 1))
  COMP_LINE="$*"
  COMP_POINT=${#COMP_LINE}
  COMPREPLY=()
  _roadload
  printf '%s\n' "${COMPREPLY[@]}"
}

# Whether standard input holds the line, read to its end: `grep -q` stops at the first match, and
# under pipefail the writer's SIGPIPE then failed the check now and then.
has_line() { grep -x -- "$1" >/dev/null; }

# What the program itself said, for a failure's message: the completion hides its errors.
listing_of() {
  local out rc
  out=$("$@" 2>&1)
  rc=$?
  echo "'${*##*/} ' exited $rc: $(tail -3 <<<"$out" | tr '\n' ' ')"
}

[[ $(complete_words "$roadload" ana) == analyze ]] || fail "'roadload ana' completes to: $(complete_words "$roadload" ana)"
complete_words "$roadload" analyze --ve | has_line --vehicle ||
  fail "'roadload analyze --ve' lacks --vehicle; $(listing_of "$roadload" --complete analyze)"
complete_words "$roadload" route "" | has_line build || fail "'roadload route' lacks its action build"
complete_words "$roadload" gap bench --ca | has_line --cases || fail "'roadload gap bench --ca' lacks --cases"
complete_words "$roadloadd" --data | has_line --data-dir || fail "'roadloadd --data' lacks --data-dir"
touch "$work/drive.toml"
complete_words "$roadload" analyze "$work/rec" --route "$work/dr" | has_line "$work/drive.toml" ||
  fail "--route's value does not complete to a file: $(complete_words "$roadload" analyze "$work/rec" --route "$work/dr")"
# The hidden listing itself: every command, and no option the help does not describe.
for c in decode analyze calibrate cat gap grade psd replay report route simulate vehicle; do
  "$roadload" --complete | has_line "$c command" || fail "roadload --complete does not list $c"
done
"$roadload" --complete analyze | has_line "--out value" || fail "roadload --complete analyze lacks --out"
"$roadload" --complete analyze | has_line "-q flag" || fail "roadload --complete analyze lacks -q"
echo "completion: PASS"
