#!/usr/bin/env bash
# The part of install-in-clean-root.sh that runs in its own mount namespace: $work/root is the
# overlay, $deb the package. Every check names what it expected.
set -euo pipefail
root=$work/root
fail() { echo "package: FAIL: $*" >&2; exit 1; }
in_root() { chroot "$root" env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin LANG=C.UTF-8 "$@"; }

mount -t overlay overlay -o "lowerdir=/,upperdir=$work/upper,workdir=$work/ovl" "$root"
for d in /usr/local /opt /home /root /tmp /work "$source_dir" "$build"; do
  [[ -d $root$d ]] && mount -t tmpfs tmpfs "$root$d"
done
mount -t proc proc "$root/proc"
mount --bind /dev "$root/dev"

[[ ! -e $root/usr/bin/roadload && ! -e $root/usr/sbin/roadloadd ]] || fail "the root already has roadload"
dpkg --root="$root" -i "$deb" >"$work/dpkg.log" 2>&1 || { cat "$work/dpkg.log" >&2; fail "dpkg -i"; }
status=$(in_root dpkg-query -W -f='${Status} ${Version}' roadload)
[[ $status == "install ok installed "* ]] || fail "dpkg says: $status"
echo "package: installed: $status"

version=$(in_root roadload --version)
[[ $version =~ ^roadload\ [0-9]+\.[0-9]+\.[0-9]+ ]] || fail "roadload --version printed '$version'"
[[ $(in_root roadloadd --version) == "roadloadd ${version#roadload }" ]] || fail "roadloadd --version differs"
echo "package: $version"

trace=/usr/share/doc/roadload/examples/css-fcbf0606-tp-sample.log
# The installed definitions name EEC1, and every one of the trace's 577 EEC1 frames is counted.
in_root roadload decode --pgn-stats "$trace" >"$work/stats" 2>/dev/null || fail "roadload decode --pgn-stats $trace"
grep -qx "61444,EEC1,577,00,.*" "$work/stats" || fail "decode --pgn-stats: no '61444,EEC1,577' row: $(head -n 5 "$work/stats")"
in_root roadload decode "$trace" >"$work/decoded" 2>/dev/null || fail "roadload decode $trace"
lines=$(wc -l <"$work/decoded")
((lines > 100)) || fail "decode printed $lines lines"
echo "package: roadload decode: $lines lines from the shipped trace"

# The Python module imports from the installed package, not a build tree (covered by tmpfs), and
# decodes the same trace to the same 577 EEC1 messages; root's import leaves byte code behind,
# which purge must remove too.
in_root python3 -c 'import os, sys, roadload
assert roadload.__file__.startswith("/usr/lib/python3/dist-packages/roadload/"), roadload.__file__
eec1 = roadload.decode(sys.argv[1], pgn=61444)
messages = len(eec1[["t_ns", "sa"]].drop_duplicates())
assert messages == 577, messages
print("package: python3: roadload %s, %d EEC1 messages" % (roadload.__version__, messages))
import roadload.batch' "$trace" >"$work/python" 2>&1 || { cat "$work/python" >&2; fail "import roadload in python3"; }
cat "$work/python"
in_root roadload batch --help >/dev/null || fail "roadload batch --help"

in_root roadloadd --config /etc/roadload/roadloadd.toml --print-config >"$work/config" || fail "roadloadd --print-config"
grep -q '^data_dir = "/var/lib/roadload"' "$work/config" || fail "print-config: no data_dir /var/lib/roadload"

unit=/lib/systemd/system/roadloadd.service
grep -q "^ExecStart=/usr/sbin/roadloadd --config /etc/roadload/roadloadd.toml" "$root$unit" || fail "$unit: ExecStart"
in_root systemd-analyze verify "$unit" >"$work/verify" 2>&1 || { cat "$work/verify" >&2; fail "systemd-analyze verify"; }
[[ ! -s $work/verify ]] || { cat "$work/verify" >&2; fail "systemd-analyze verify printed warnings"; }
echo "package: systemd-analyze verify $unit: clean"

# What the unit needs on a stock Debian: its user and groups (sysusers), its folders (tmpfiles).
for g in spi gpio roadload; do in_root getent group "$g" >/dev/null || fail "no group $g after install"; done
in_root getent passwd roadload >/dev/null || fail "no user roadload after install"
[[ $(in_root stat -c %U /var/lib/roadload) == roadload ]] || fail "/var/lib/roadload is not roadload's"
grep -qx /etc/roadload/roadloadd.toml "$root/var/lib/dpkg/info/roadload.conffiles" || fail "roadloadd.toml is no conffile"
in_root logrotate --debug /etc/logrotate.d/roadload >"$work/logrotate" 2>&1 ||
  { cat "$work/logrotate" >&2; fail "logrotate rejects /etc/logrotate.d/roadload"; }
for page in roadloadd roadload roadload-analyze roadload-gap; do
  in_root man -w "$page" >/dev/null 2>&1 || fail "man $page finds no page"
done
# Bash completion where bash-completion looks, and it completes from the installed program.
[[ -f $root/usr/share/bash-completion/completions/roadload ]] || fail "no bash completion for roadload"
words=$(in_root bash -c '. /usr/share/bash-completion/bash_completion; . /usr/share/bash-completion/completions/roadload
  COMP_WORDS=(roadload ana); COMP_CWORD=1; COMP_LINE="roadload ana"; COMP_POINT=${#COMP_LINE}; _roadload; printf "%s\n" "${COMPREPLY[@]}"')
[[ $words == *analyze* ]] || fail "bash completion of 'roadload ana' gave '$words'"

dpkg --root="$root" --purge roadload >>"$work/dpkg.log" 2>&1 || { cat "$work/dpkg.log" >&2; fail "dpkg --purge"; }
for f in /usr/bin/roadload /usr/sbin/roadloadd /usr/share/roadload /etc/roadload "$unit" /usr/lib/python3/dist-packages/roadload; do
  [[ ! -e $root$f ]] || fail "$f is left after purge"
done
echo "package: purge leaves no file of the package"
