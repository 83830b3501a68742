#!/bin/sh
# One manual page per subcommand of PROGRAM (roadload-analyze.1, ...), made by help2man from the
# subcommand's own --help and --version. The subcommands come from the program itself (its
# `--complete` words), so a new command gets its page without a list to keep here.
# usage: subcommand-man-pages.sh HELP2MAN PROGRAM OUTDIR
set -eu
help2man=$1 program=$2 out=$3
name=$(basename "$program")
mkdir -p "$out"
rm -f "$out"/"$name"-*.1
"$program" --complete | while read -r word kind; do
  [ "$kind" = command ] || continue
  summary=$("$program" --help | sed -n "s/^  $word  *//p" | head -n 1)
  "$help2man" --no-info --no-discard-stderr --section 1 --name "${summary:-$name $word}" \
    --help-option "$word --help" --version-option "$word --version" \
    --output "$out/$name-$word.1" "$program"
  # help2man names the page after the program; the page and its NAME are the subcommand's, so
  # `man roadload-analyze` and apropos find it.
  sed -i -e "s/^\.TH \"\{0,1\}[A-Z]*\"\{0,1\} /.TH \"$(echo "$name-$word" | tr a-z A-Z)\" /" \
    -e "/^\.SH NAME/{n;s/^$name /$name-$word /}" "$out/$name-$word.1"
done
