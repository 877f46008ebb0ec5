#!/usr/bin/env bash
# The systemd units as systemd reads them: `systemd-analyze verify` on each (ExecStart= pointed at
# the built binaries, which verify requires to exist), and `systemd-analyze security` of the
# services at most 3.0 (issue 9), reported.
# Usage: units_test.sh SYSTEMD_DIR BIN_DIR
set -uo pipefail
UNITS=$1
BIN=$(cd "$2" && pwd)
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
source "$(dirname "$0")/../apps/cli_test_lib.sh"
MAX_EXPOSURE=3.0

for unit in glarecamd.service glarecam-capture.service glarecam-capture.timer; do
  sed -e "s|/usr/bin/glarecamd|$BIN/glarecamd|" -e "s|/usr/bin/glarecam |$BIN/glarecam |" \
    "$UNITS/$unit" >"$WORK/$unit"
done
check "systemd-analyze verify the units" 0 systemd-analyze verify "$WORK/glarecamd.service" \
  "$WORK/glarecam-capture.service" "$WORK/glarecam-capture.timer"
expect "verify says nothing about them" test ! -s "$WORK/err"

for service in glarecamd.service glarecam-capture.service; do
  check "systemd-analyze security $service" 0 systemd-analyze security --offline=true \
    --threshold=100 "$WORK/$service"
  score=$(grep -o 'Overall exposure level for [^:]*: [0-9.]*' "$WORK/out" | awk '{print $NF}')
  echo "security exposure of $service: $score"
  expect "$service exposure $score is at most $MAX_EXPOSURE" \
    awk -v s="$score" -v m="$MAX_EXPOSURE" 'BEGIN { exit !(s != "" && s <= m) }'
done

# The daemon's unit keeps the promises issue 9 makes of it.
for setting in Type=notify WatchdogSec= Restart=on-failure RestartPreventExitStatus=78 \
  User=glarecam ProtectSystem=strict ReadWritePaths=/var/lib/glarecam DeviceAllow= \
  NoNewPrivileges=yes CapabilityBoundingSet= StartLimitBurst=; do
  expect "glarecamd.service sets $setting" grep -q "^$setting" "$UNITS/glarecamd.service"
done
finish
