#!/usr/bin/env bash
# `glarecam sun`, `glarecam alpha`, `glarecam inclinometer read|flip` and `glarecam capture
# --config` as a user runs them, on the simulated inclinometer: values against references, the
# flip calibration stored and used, the geometry block in a captured stack, and every bad input
# (exit 2) and missing device (exit 1) with a one-line error naming it.
# Usage: rig_cli_test.sh GLARECAM
set -uo pipefail
GLARECAM=$1
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
source "$(dirname "$0")/cli_test_lib.sh"

# ---- sun -------------------------------------------------------------------------------------
# NREL SPA's documented test case (Reda & Andreas, NREL/TP-560-34302): zenith 50.11162°,
# azimuth 194.34024°. The paper prints 5 decimals; ΔT from our polynomial (≈ 64.6 s) instead of
# the paper's 67 s moves the sun by 0.00003°: 1e-4° tolerance.
nrel=(--lat 39.742476 --lon -105.1786 --altitude-m 1830.14 --pressure-hpa 820 --temperature-c 11
      --time 2003-10-17T12:30:30-07:00)
check "sun: NREL test case" 0 "$GLARECAM" sun "${nrel[@]}" --json
cp "$WORK/out" "$WORK/sun.json"
expect "sun: zenith 50.11162" near "$(json_number zenith_deg "$WORK/sun.json")" 50.11162 1e-4
expect "sun: azimuth 194.34024 (from north)" near "$(json_number azimuth_deg "$WORK/sun.json")" 194.34024 1e-4
expect "sun: elevation = 90 - zenith" near "$(json_number elevation_deg "$WORK/sun.json")" 39.88838 1e-4
check "sun: text output" 0 "$GLARECAM" sun "${nrel[@]}"
expect "sun: text names elevation and azimuth" grep -q "elevation 39.888.*azimuth 194.340" "$WORK/out"
check "sun: now (no --time)" 0 "$GLARECAM" sun --lat 48 --lon 11 --json
expect "sun: now has an azimuth" test -n "$(json_number azimuth_deg "$WORK/out")"

check "sun: latitude beyond 90" 2 "$GLARECAM" sun --lat 91 --lon 0 --time 2026-01-01T12:00:00Z
expect "sun: latitude error is one line" one_line_naming "latitude"
check "sun: longitude not a number" 2 "$GLARECAM" sun --lat 10 --lon east --time 2026-01-01T12:00:00Z
expect "sun: longitude error is one line" one_line_naming "--lon"
check "sun: time without a zone" 2 "$GLARECAM" sun --lat 10 --lon 0 --time 2026-01-01T12:00:00
expect "sun: zone error is one line" one_line_naming "2026-01-01T12:00:00"
check "sun: February 30" 2 "$GLARECAM" sun --lat 10 --lon 0 --time 2026-02-30T12:00:00Z
check "sun: negative pressure" 2 "$GLARECAM" sun --lat 10 --lon 0 --pressure-hpa -5 --time 2026-01-01T12:00:00Z
expect "sun: pressure error is one line" one_line_naming "pressure"
check "sun: missing --lon" 2 "$GLARECAM" sun --lat 10

# ---- inclinometer ----------------------------------------------------------------------------
check "inclinometer read: sim" 0 "$GLARECAM" inclinometer read --inclinometer sim:30 --no-progress
expect "inclinometer read: prints the module tilt" grep -Eq "module tilt (29\.99|30\.00)" "$WORK/out"
check "inclinometer read: json and --out" 0 "$GLARECAM" inclinometer read --inclinometer "sim:12,roll_deg=2" \
  --json --out "$WORK/reading.json" --no-progress
expect "inclinometer read: --out written" test -s "$WORK/reading.json"
# Quantisation (3.9 µg) and noise (60 µg, mean of 50): 0.002° is several σ.
expect "inclinometer read: tilt_x 12" near "$(json_number tilt_x_deg "$WORK/reading.json")" 12 0.002
expect "inclinometer read: tilt_y 2" near "$(json_number tilt_y_deg "$WORK/reading.json")" 2 0.002
check "inclinometer read: moving rig" 1 "$GLARECAM" inclinometer read --inclinometer sim:30,noise_g=0.02 --no-progress
expect "inclinometer read: moving error is one line" one_line_naming "the rig is moving"
check "inclinometer read: saturated axis" 1 "$GLARECAM" inclinometer read --inclinometer sim:30,fault=saturated --no-progress
expect "inclinometer read: saturation named" one_line_naming "saturated"
check "inclinometer read: all-zero data" 1 "$GLARECAM" inclinometer read --inclinometer sim:0,fault=zeros --no-progress
check "inclinometer read: sensor absent" 1 "$GLARECAM" inclinometer read --inclinometer sim:0,fault=absent --no-progress
check "inclinometer read: no I2C bus here" 1 "$GLARECAM" inclinometer read --inclinometer adxl355:/dev/i2c-97@0x1d
expect "inclinometer read: the bus is named" one_line_naming "/dev/i2c-97"
check "inclinometer read: no IIO device here" 1 "$GLARECAM" inclinometer read --inclinometer iio:iio:device97
expect "inclinometer read: the IIO device is named" one_line_naming "iio:device97"
check "inclinometer read: unknown scheme" 2 "$GLARECAM" inclinometer read --inclinometer spirit:level
expect "inclinometer read: scheme error is one line" one_line_naming "spirit:level"
check "inclinometer read: bad sim key" 2 "$GLARECAM" inclinometer read --inclinometer sim:30,wobble=1
check "inclinometer read: bad address" 2 "$GLARECAM" inclinometer read --inclinometer adxl355:/dev/i2c-1@0x1zz
check "inclinometer read: no sensor given" 2 "$GLARECAM" inclinometer read
check "inclinometer read: one sample" 2 "$GLARECAM" inclinometer read --inclinometer sim:0 --samples 1
check "inclinometer read: empty --out" 2 "$GLARECAM" inclinometer read --inclinometer sim:0 --out ""
check "inclinometer: no subcommand" 2 "$GLARECAM" inclinometer

# The flip: a surface 5° off level, the sensor mounted 0.3° off; turned 180° the surface reads
# -5° + 0.3°. Rotations about one axis add exactly: the offset is 0.3° within the readings' noise.
"$GLARECAM" inclinometer read --inclinometer "sim:5,offset_x_deg=0.3,seed=1" --out "$WORK/a.json" --no-progress >/dev/null
"$GLARECAM" inclinometer read --inclinometer "sim:-5,offset_x_deg=0.3,seed=2" --out "$WORK/b.json" --no-progress >/dev/null
echo '{"note": "rig 1"}' >"$WORK/calib.json"
check "flip: from two readings" 0 "$GLARECAM" inclinometer flip --from "$WORK/a.json" "$WORK/b.json" \
  --calibration "$WORK/calib.json"
expect "flip: prints the offset" grep -Eq "zero offset x 0\.(29|30)" "$WORK/out"
expect "flip: offset stored" near "$(json_number zero_offset_x_deg "$WORK/calib.json")" 0.3 0.002
expect "flip: the calibration's other keys kept" grep -q '"note": "rig 1"' "$WORK/calib.json"
expect "flip: provenance recorded" grep -q '"method": "flip"' "$WORK/calib.json"
# Interactive: the operator presses Enter between the readings. The simulated sensor cannot be
# turned: its two readings agree, which shows no turn, and is refused (a turned frame on a level
# surface reads the same: the flip needs a tilted one). The turn itself: flip_calibration_test.
check "flip: interactive, not turned" 2 bash -c "echo | '$GLARECAM' inclinometer flip --inclinometer 'sim:0,offset_y_deg=-0.4' \
  --calibration '$WORK/calib2.json' --no-progress"
expect "flip: interactive prompt on stderr" grep -q "Turn the frame" "$WORK/err"
expect "flip: no turn explained" grep -q "the two readings agree" "$WORK/err"
expect "flip: nothing stored without a turn" test ! -e "$WORK/calib2.json"
check "flip: stdin closed" 2 bash -c "'$GLARECAM' inclinometer flip --inclinometer sim:0 --calibration '$WORK/c3.json' --no-progress </dev/null"
expect "flip: stdin error names --from" grep -q -- "--from" "$WORK/err"
expect "flip: nothing written when it failed" test ! -e "$WORK/c3.json"
"$GLARECAM" inclinometer read --inclinometer sim:30,seed=1 --out "$WORK/steep1.json" --no-progress >/dev/null
"$GLARECAM" inclinometer read --inclinometer sim:30,seed=2 --out "$WORK/steep2.json" --no-progress >/dev/null
check "flip: readings of a steep surface" 2 "$GLARECAM" inclinometer flip --from "$WORK/steep1.json" \
  "$WORK/steep2.json" --calibration "$WORK/c4.json"
expect "flip: steep readings explained" grep -q "within a few degrees of level" "$WORK/err"
check "flip: the same reading twice" 2 "$GLARECAM" inclinometer flip --from "$WORK/a.json" "$WORK/a.json" \
  --calibration "$WORK/c4.json"
expect "flip: same reading named" one_line_naming "the same reading twice"
check "flip: interactive on a steep surface stops before the turn" 2 bash -c "echo | '$GLARECAM' inclinometer flip \
  --inclinometer sim:25 --calibration '$WORK/c6.json' --no-progress"
expect "flip: steep surface explained" grep -q "within a few degrees of level" "$WORK/err"
expect "flip: no turn asked for on a steep surface" bash -c "! grep -q 'Turn the frame' '$WORK/err'"
echo 'not json' >"$WORK/notjson.json"
check "flip: a calibration file that is not JSON is refused before the readings" 2 bash -c "echo | '$GLARECAM' \
  inclinometer flip --inclinometer sim:0 --calibration '$WORK/notjson.json' --no-progress"
expect "flip: refused before asking to turn" bash -c "! grep -q 'Turn the frame' '$WORK/err'"
echo '{not json' >"$WORK/broken.json"
check "flip: a calibration that is not JSON is not overwritten" 2 "$GLARECAM" inclinometer flip \
  --from "$WORK/a.json" "$WORK/b.json" --calibration "$WORK/broken.json"
expect "flip: broken file untouched" grep -q '^{not json$' "$WORK/broken.json"
check "flip: no calibration file named" 2 "$GLARECAM" inclinometer flip --from "$WORK/a.json" "$WORK/b.json"
check "flip: reading file missing" 2 "$GLARECAM" inclinometer flip --from "$WORK/nope.json" "$WORK/b.json" \
  --calibration "$WORK/c5.json"
expect "flip: missing reading named" one_line_naming "nope.json"

# ---- alpha -----------------------------------------------------------------------------------
# Lab mode: a lamp on the horizon due south, a south-facing module tilted 60° (sensor mounted
# 0.3° off, corrected by the stored flip offset): α = 30°.
cat >"$WORK/lab.toml" <<TOML
calibration = "calib.json"
[source]
elevation_deg = 0
azimuth_deg = 180
[module]
azimuth_deg = 180
[inclinometer]
uri = "sim:60,offset_x_deg=0.3"
TOML
check "alpha: lab mode" 0 "$GLARECAM" alpha --config "$WORK/lab.toml" --json --no-progress
cp "$WORK/out" "$WORK/alpha.json"
# The stored offset came from noisy readings (±0.0005°) plus the sensor's noise: 0.005°.
expect "alpha: 30° from the tilt" near "$(json_number alpha_deg "$WORK/alpha.json")" 30 0.005
expect "alpha: geometry names its source" grep -q '"source": "fixed"' "$WORK/alpha.json"
expect "alpha: raw inclinometer vector recorded" grep -q '"z_g"' "$WORK/alpha.json"
check "alpha: text" 0 "$GLARECAM" alpha --config "$WORK/lab.toml" --no-progress
expect "alpha: text has α and its uncertainty" grep -q "^alpha 30.00[0-9]° ± " "$WORK/out"

# Sun mode at NREL's test case: a module facing the sun exactly (tilt = zenith, azimuth = the
# sun's) sees it at α ≈ 0.
cat >"$WORK/sun.toml" <<TOML
[site]
latitude_deg = 39.742476
longitude_deg = -105.1786
altitude_m = 1830.14
pressure_hpa = 820
temperature_c = 11
[module]
azimuth_deg = 194.34024
tilt_deg = 50.11162
TOML
check "alpha: sun mode at a given time" 0 "$GLARECAM" alpha --config "$WORK/sun.toml" --time 2003-10-17T19:30:30Z --json
expect "alpha: module facing the sun, α ≈ 0" near "$(json_number alpha_deg "$WORK/out")" 0 0.001
expect "alpha: sun azimuth recorded" near "$(json_number sun_azimuth_deg "$WORK/out")" 194.34024 1e-4

expect "alpha: a given --time involves no clock" bash -c "! grep -q 'not synchronised' '$WORK/err'"
expect "alpha: a given --time records no clock state" bash -c "! grep -q clock_synchronised '$WORK/out'"
sed 's/calibration = "calib.json"/calibration = "not-yet.json"/' "$WORK/lab.toml" >"$WORK/fresh.toml"
check "alpha: a rig whose calibration file does not exist yet" 0 "$GLARECAM" alpha --config "$WORK/fresh.toml" \
  --json --no-progress
expect "alpha: the missing zero offset is warned about" grep -q "not-yet.json" "$WORK/err"
expect "alpha: and recorded" grep -q '"warnings"' "$WORK/out"
check "alpha: missing config" 2 "$GLARECAM" alpha --config "$WORK/none.toml"
expect "alpha: missing config named" one_line_naming "none.toml"
printf '[site]\nlatitude_deg = 95\nlongitude_deg = 0\n[module]\nazimuth_deg = 0\ntilt_deg = 0\n' >"$WORK/bad.toml"
check "alpha: latitude out of range" 2 "$GLARECAM" alpha --config "$WORK/bad.toml"
expect "alpha: error has file and line" one_line_naming "bad.toml:2:"
printf '[site]\nlatitude_deg = 45\nlongitude_deg = 0\n[module]\nazimuth_deg = 0\n' >"$WORK/notilt.toml"
check "alpha: no tilt source" 2 "$GLARECAM" alpha --config "$WORK/notilt.toml"
expect "alpha: no tilt explained" one_line_naming "no module tilt"
printf 'this is = not toml [\n' >"$WORK/syntax.toml"
check "alpha: TOML syntax error" 2 "$GLARECAM" alpha --config "$WORK/syntax.toml"
expect "alpha: syntax error has file and line" one_line_naming "syntax.toml:1:"
sed 's/sim:60/sim:60,noise_g=0.02/' "$WORK/lab.toml" >"$WORK/moving.toml"
check "alpha: moving rig" 1 "$GLARECAM" alpha --config "$WORK/moving.toml" --no-progress
check "alpha: bad --time" 2 "$GLARECAM" alpha --config "$WORK/sun.toml" --time yesterday

# ---- capture --config ------------------------------------------------------------------------
check "capture: with the lab config" 0 "$GLARECAM" capture --camera "sim:size=160x128" --config "$WORK/lab.toml" \
  --out "$WORK/stacks" --no-progress
stack=$(cat "$WORK/out")
expect "capture: stack written" test -s "$stack/stack.json"
expect "capture: geometry block in the manifest" grep -q '"geometry"' "$stack/stack.json"
expect "capture: module tilt in the geometry" near "$(json_number module_tilt_deg "$stack/stack.json")" 60 0.005
expect "capture: α measured, not given" near "$(json_number alpha_deg "$stack/stack.json")" 30 0.005
expect "capture: raw inclinometer reading" grep -q '"x_g"' "$stack/stack.json"
expect "capture: the scene shows the measured α" near "$(json_number alpha_deg "$stack/truth.json")" 30 0.005
check "capture: processing the geometry-tagged stack" 0 "$GLARECAM" process "$stack" --out "$WORK/result" -q
check "capture: --alpha contradicts the config" 2 "$GLARECAM" capture --camera sim: --config "$WORK/lab.toml" \
  --alpha 20 --out "$WORK/stacks2"
expect "capture: contradiction is one line" one_line_naming "--alpha"
check "capture: no camera anywhere" 2 "$GLARECAM" capture --config "$WORK/lab.toml" --out "$WORK/stacks3"
check "capture: bad config" 2 "$GLARECAM" capture --camera sim: --config "$WORK/bad.toml" --out "$WORK/stacks4"
expect "capture: nothing written on a bad config" test ! -e "$WORK/stacks4"
# A config without [site]: α is the one given, and the simulated scene shows it.
printf 'camera = "sim:size=64x48"\n' >"$WORK/camera-only.toml"
check "capture: --alpha with a config that gives no α" 0 "$GLARECAM" capture --config "$WORK/camera-only.toml" \
  --alpha 20 --out "$WORK/given" --no-progress
stack=$(cat "$WORK/out")
expect "capture: the given α recorded" near "$(json_number alpha_deg "$stack/stack.json")" 20 1e-9
expect "capture: the scene shows the given α" near "$(json_number alpha_deg "$stack/truth.json")" 20 1e-9
# A sim: URI's alpha= fixes the scene: a measured α that contradicts it is refused, not recorded.
check "capture: URI alpha= contradicts the measured α" 2 "$GLARECAM" capture \
  --camera "sim:size=64x48,alpha=50" --config "$WORK/lab.toml" --out "$WORK/fixed" --no-progress
expect "capture: the contradiction is one line" one_line_naming "alpha=50 contradicts the capture's α"
expect "capture: nothing written for a contradiction" test ! -e "$WORK/fixed"
# The same rule as glarecamd: a tilt outside [faults] min/max_tilt_deg is a fault, not an α.
{ cat "$WORK/lab.toml"; printf '[faults]\nmax_tilt_deg = 45\n'; } >"$WORK/implausible.toml"
check "capture: an implausible tilt is refused" 1 "$GLARECAM" capture --camera "sim:size=160x128" \
  --config "$WORK/implausible.toml" --out "$WORK/stacks5" --no-progress
expect "capture: the refusal names the tilt and the range" one_line_naming "implausible tilt 60.00"
expect "capture: nothing written for an implausible tilt" test ! -e "$WORK/stacks5"

# ---- gpio (the simulated chip) and capture --on-button ---------------------------------------
cat >"$WORK/gpio.toml" <<TOML
[gpio]
chip = "sim:button_period_s=0.5"
led = 17
trigger = "GPIO22"
button = 27
button_active_low = true
debounce_ms = 20
TOML
check "gpio: LED pattern, trigger, button" 0 "$GLARECAM" gpio --config "$WORK/gpio.toml" --led fault-disk --seconds 0.2 \
  --trigger 2 --wait-button --timeout 5
expect "gpio: trigger pulses reported" grep -q "trigger: 2 pulse" "$WORK/out"
expect "gpio: the press seen" grep -q "button: pressed" "$WORK/out"
check "gpio: status readout" 0 "$GLARECAM" gpio --config "$WORK/gpio.toml"
expect "gpio: describes the lines" grep -q "trigger line 'GPIO22', LED line 17, button line 27, active-low" "$WORK/out"
printf '[gpio]\nchip = "sim"\nbutton = 3\nbutton_active_low = true\n' >"$WORK/nopress.toml"
check "gpio: no press before the timeout" 1 "$GLARECAM" gpio --config "$WORK/nopress.toml" --wait-button --timeout 0.2
expect "gpio: timeout named" grep -q "no button press within 0.2 s" "$WORK/err"
check "gpio: unknown LED status" 2 "$GLARECAM" gpio --config "$WORK/gpio.toml" --led disco
expect "gpio: LED error lists the statuses" one_line_naming "fault-inclinometer"
check "gpio: LED without a led line" 2 "$GLARECAM" gpio --config "$WORK/nopress.toml" --led ready --seconds 0.1
check "gpio: zero trigger pulses" 2 "$GLARECAM" gpio --config "$WORK/gpio.toml" --trigger 0
check "gpio: no [gpio] section" 2 "$GLARECAM" gpio --config "$WORK/lab.toml"
printf '[gpio]\nled = 17\n' >"$WORK/realchip.toml"
check "gpio: no GPIO chip on this machine" 1 "$GLARECAM" gpio --config "$WORK/realchip.toml"
expect "gpio: the chip is named" one_line_naming "GPIO chip gpiochip0 not found"
printf '[gpio]\nchip = "sim"\nled = 17\nbutton = 17\n' >"$WORK/twice.toml"
check "gpio: one line in two roles" 2 "$GLARECAM" gpio --config "$WORK/twice.toml"
expect "gpio: config error has file and line" one_line_naming "twice.toml:1:"
printf '[gpio]\nchip = "sim"\nled = 17\ntrigger = "GPIO17"\n' >"$WORK/byname.toml"
check "gpio: one line by offset and by name" 2 "$GLARECAM" gpio --config "$WORK/byname.toml"
expect "gpio: the shared line is named" one_line_naming "same line 17"
printf '[gpio]\nchip = "sim"\nled = 60\n' >"$WORK/beyond.toml"
check "gpio: a line beyond the chip" 1 "$GLARECAM" gpio --config "$WORK/beyond.toml"
expect "gpio: the chip's size is named" one_line_naming "58 lines"
printf '[gpio]\nchip = "sim"\nled = -1\n' >"$WORK/negative.toml"
check "gpio: negative offset" 2 "$GLARECAM" gpio --config "$WORK/negative.toml"
expect "gpio: offset error has file and line" one_line_naming "negative.toml:3:"

cat "$WORK/lab.toml" "$WORK/gpio.toml" >"$WORK/lab-gpio.toml"
check "capture: one stack per button press" 0 "$GLARECAM" capture --camera "sim:size=160x128" \
  --config "$WORK/lab-gpio.toml" --on-button --count 2 --out "$WORK/pressed" --no-progress
expect "capture: two stacks from two presses" test "$(wc -l <"$WORK/out")" -eq 2
check "capture: --on-button without a button" 2 "$GLARECAM" capture --camera sim: --config "$WORK/lab.toml" \
  --on-button --out "$WORK/nobutton"
check "capture: --on-button without a config" 2 "$GLARECAM" capture --camera sim: --on-button --out "$WORK/nobutton"

finish
