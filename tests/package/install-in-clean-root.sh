#!/usr/bin/env bash
# Builds the Debian package from this build folder (CPack), installs it with `dpkg --root` into a
# root where nothing of roadload exists, and runs what a user runs first: `roadload --version`,
# `roadload decode` on the shipped trace, the Python module's import and decode of the same trace,
# `roadloadd --print-config` and systemd's check of the installed unit. Then remove and purge leave nothing behind.
#
# The root is this machine's own Debian under an overlay (the package's dependencies are real
# Debian packages there, and dpkg checks Depends against its database) with every place a copy
# of roadload could hide covered by an empty tmpfs: /usr/local, /opt, /home, /root, /tmp, /work,
# the source and the build folder. Writes go to the overlay's upper layer; the host is untouched.
set -euo pipefail
build=${1:?usage: install-in-clean-root.sh BUILD_DIR SOURCE_DIR}
source_dir=${2:?usage: install-in-clean-root.sh BUILD_DIR SOURCE_DIR}
fail() { echo "package: FAIL: $*" >&2; exit 1; }
[[ $(id -u) -eq 0 ]] || { echo "package: needs root for dpkg --root and mounts; skipped"; exit 77; }
for tool in cpack dpkg unshare systemd-analyze; do
  command -v "$tool" >/dev/null || { echo "package: no $tool here; skipped"; exit 77; }
done
prefix=$(sed -n 's/^CMAKE_INSTALL_PREFIX:PATH=//p' "$build/CMakeCache.txt")
[[ $prefix == /usr ]] || fail "$build is configured for the prefix $prefix; a package needs /usr (scripts/build)"

work=$(mktemp -d /var/tmp/roadload-package.XXXXXX)
trap 'rm -rf "$work"' EXIT
(cd "$build" && cpack -G DEB -B "$work/deb" >"$work/cpack.log" 2>&1) || { cat "$work/cpack.log" >&2; fail "cpack"; }
deb=$(ls "$work"/deb/roadload_*.deb)
echo "package: built $(basename "$deb") ($(stat -c %s "$deb") bytes)"
mkdir -p "$work/upper" "$work/ovl" "$work/root"
export deb work source_dir build
unshare -m --propagation private bash -euo pipefail "$(dirname "$0")/in-root.sh" || fail "in the clean root (above)"
echo "package: PASS"
