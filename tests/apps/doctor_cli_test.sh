#!/usr/bin/env bash
# `glarecam doctor` on a simulated lab rig (every check passes or only warns: exit 0), on rigs
# with a part missing (exit 1, the FAIL line names it) and on an invalid config (exit 2).
# Usage: doctor_cli_test.sh GLARECAM
set -uo pipefail
GLARECAM=$1
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
source "$(dirname "$0")/cli_test_lib.sh"

rig() {  # rig INCLINOMETER_URI [EXTRA]
  cat <<TOML
camera = "sim:size=160x128"
[source]
elevation_deg = 0
azimuth_deg = 180
[module]
azimuth_deg = 180
[inclinometer]
uri = "$1"
samples = 4
[output]
root = "data"
reserve_mb = 1
${2:-}
TOML
}
mkdir -p "$WORK/data"
rig "sim:50" >"$WORK/rig.toml"
check "doctor on the simulated lab rig" 0 "$GLARECAM" doctor --config "$WORK/rig.toml"
for name in config camera inclinometer sun clock disk permissions systemd; do
  expect "the table has a $name line" grep -q "^$name " "$WORK/out"
done
expect "the camera streamed a test frame" grep -q "^camera *ok .*160x128 Mono12 frame" "$WORK/out"
expect "the inclinometer is steady at 50°" grep -q "^inclinometer *ok .*tilt 50.0" "$WORK/out"
expect "no line fails" bash -c "! grep -q ' FAIL ' '$WORK/out'"

rig "adxl355:/dev/i2c-9@0x1d" >"$WORK/rig.toml"
check "doctor without the I2C bus" 1 "$GLARECAM" doctor --config "$WORK/rig.toml"
expect "the inclinometer fails, naming the bus" grep -q "^inclinometer *FAIL .*/dev/i2c-9" "$WORK/out"
expect "permissions name the bus" grep -q "^permissions *FAIL .*I2C bus /dev/i2c-9" "$WORK/out"
expect "the exit is explained in one line" one_line_naming "the rig is not ready"

rig "sim:50" "reserve_mb = 1073741824" | sed '/^reserve_mb = 1$/d' >"$WORK/rig.toml"
check "doctor with a disk below the reserve" 1 "$GLARECAM" doctor --config "$WORK/rig.toml" --json
expect "JSON says not ok" grep -q '"ok": false' "$WORK/out"
expect "the disk check fails" grep -q 'below the 1.0 PiB reserve' "$WORK/out"

printf 'camera = "sim:"\n[schedule]\nmode = "sometimes"\n' >"$WORK/bad.toml"
check "doctor on an invalid config" 2 "$GLARECAM" doctor --config "$WORK/bad.toml"
expect "the config line names the file and line" grep -q "^config *FAIL .*bad.toml:3:" "$WORK/out"
check "doctor on a missing config" 2 "$GLARECAM" doctor --config "$WORK/none.toml"
finish
