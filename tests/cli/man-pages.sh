#!/usr/bin/env bash
# The manual pages the build makes from the programs' --help: present, readable by man, and
# saying what --help says (every command of roadload and its own page, roadloadd's options).
set -euo pipefail
roadload_page=${1:?usage: man-pages.sh ROADLOAD_1 ROADLOADD_8}
roadloadd_page=${2:?usage: man-pages.sh ROADLOAD_1 ROADLOADD_8}
fail() { echo "man-pages: FAIL: $*" >&2; exit 1; }
command -v man >/dev/null || { echo "man-pages: no man(1) here; skipped"; exit 77; }
[[ -s $roadload_page && -s $roadloadd_page ]] || fail "a page is missing: $roadload_page $roadloadd_page"
text=$(MANWIDTH=100 man -l "$roadload_page" 2>/dev/null)
for c in decode analyze calibrate cat gap grade psd replay report route simulate vehicle; do
  grep -Eq "^ *$c( |$)" <<<"$text" || fail "roadload(1) does not list the command $c"
done
grep -q "usage: roadload <command>" <<<"$text" || fail "roadload(1) has no usage line"
# A page per command, beside roadload.1 (man/), named and described as the command.
for c in decode analyze calibrate cat gap grade psd replay report route simulate vehicle; do
  page=$(dirname "$roadload_page")/man/roadload-$c.1
  [[ -s $page ]] || fail "no page $page"
  ctext=$(MANWIDTH=100 man -l "$page" 2>/dev/null)
  grep -Eq "^ *roadload-$c +- " <<<"$ctext" || fail "roadload-$c(1) has no NAME line for roadload-$c"
  grep -q "usage: roadload $c" <<<"$ctext" || fail "roadload-$c(1) lacks the command's usage"
done
dtext=$(MANWIDTH=100 man -l "$roadloadd_page" 2>/dev/null)
grep -q -- "--config" <<<"$dtext" || fail "roadloadd(8) does not describe --config"
grep -q "ROADLOADD\|roadloadd" <<<"$dtext" || fail "roadloadd(8) does not name the program"
echo "man-pages: PASS"
