#!/usr/bin/env bash
# `make install` into a staging root (DESTDIR): every file in its place, the units pointing at
# the installed binaries and passing `systemd-analyze verify` there, the operator's config never
# overwritten. Usage: install_test.sh BUILD_DIR
set -uo pipefail
BUILD=$1
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
source "$(dirname "$0")/../apps/cli_test_lib.sh"
ROOT=$WORK/root
PREFIX=$(sed -n 's/^CMAKE_INSTALL_PREFIX:PATH=//p' "$BUILD/CMakeCache.txt")

check "cmake --install into DESTDIR" 0 env DESTDIR="$ROOT" cmake --install "$BUILD"
for file in bin/glarecam bin/glarecamd lib/systemd/system/glarecamd.service \
  lib/systemd/system/glarecam-capture.service lib/systemd/system/glarecam-capture.timer \
  lib/sysusers.d/glarecam.conf lib/udev/rules.d/99-glarecam.rules \
  share/glarecam/glarecam.toml.example share/glarecam/genicam/sfnc-linear-mono.conf \
  share/glarecam/raspberry-pi/config.txt share/doc/glarecam/operator.md \
  share/doc/glarecam/README.md; do
  expect "installed $file" test -e "$ROOT$PREFIX/$file"
done
expect "no config over /etc" test ! -e "$ROOT/etc/glarecam/glarecam.toml"
expect "the unit starts the installed glarecamd" \
  grep -q "^ExecStart=$PREFIX/bin/glarecamd " "$ROOT$PREFIX/lib/systemd/system/glarecamd.service"
check "the installed glarecamd runs" 0 "$ROOT$PREFIX/bin/glarecamd" --version
# verify wants the unit's binary at its real path: check a copy pointed into the staging root.
sed "s|$PREFIX/bin/|$ROOT$PREFIX/bin/|" "$ROOT$PREFIX/lib/systemd/system/glarecamd.service" \
  >"$WORK/glarecamd.service"
check "the installed unit verifies" 0 systemd-analyze verify "$WORK/glarecamd.service"
finish
