#!/usr/bin/env bash
# The calibration procedure of docs/calibration.md as an operator runs it, on the simulated
# camera's targets: dark, linearity, noise, flat, intrinsics, luminance, merge, then a glare
# stack processed with the merged file (and refused for another camera's serial); the drift
# check; every bad input exits 2 with a one-line error naming the problem.
# Usage: calibrate_cli_test.sh GLARECAM
set -uo pipefail
GLARECAM=$1
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
source "$(dirname "$0")/cli_test_lib.sh"

T=$WORK/targets
C=$WORK/cal

for target in dark flat linearity noise luminance board; do
  check "simulate-calibration $target" 0 "$GLARECAM" simulate-calibration "$target" --out "$T"
done
expect "board: 12 view stacks" test "$(ls -d "$T"/board-* | wc -l)" -eq 12
# --no-progress, as every command with a long operation takes it.
check "simulate-calibration --no-progress" 0 "$GLARECAM" simulate-calibration dark --out "$WORK/np" \
  --no-progress
expect "simulate-calibration --no-progress: stderr quiet" test ! -s "$WORK/err"

# Dark: black level 64 DN, 12 hot pixels (tolerances: tests/calibration/calibration_procedures_test.cpp).
check "calibrate dark" 0 "$GLARECAM" calibrate dark "$T/dark" --out "$C/dark.json" --no-progress
expect "dark: black level 64" near "$(json_number black_level_dn "$C/dark.json")" 64 0.05
expect "dark: 12 hot pixels" test "$(json_number hot_pixel_count "$C/dark.json")" -eq 12
expect "dark: the dark frame" test -s "$C/dark-dark.exr"
expect "dark: the hot-pixel map" test -s "$C/dark-hot-pixels.png"
expect "dark: provenance" grep -q '"measured_at": "2026-06-21T10:00:00Z"' "$C/dark.json"

check "calibrate linearity" 0 "$GLARECAM" calibrate linearity "$T/linearity" --out "$C/linearity.json" \
  --calibration "$C/dark.json" --no-progress
truth_saturation=$(json_number saturation_dn "$T/linearity/truth.json")
expect "linearity: saturation where the response bends 1 %" \
  near "$(json_number saturation_dn "$C/linearity.json")" "$truth_saturation" 20

check "calibrate noise" 0 "$GLARECAM" calibrate noise "$T/noise" --out "$C/noise.json" \
  --calibration "$C/dark.json" --calibration "$C/linearity.json" --no-progress
# 2 DN read noise raised to 2.02 by quantisation, 0.5 DN/e-: to 3 % (the fit's u is ~1 %).
expect "noise: read noise" near "$(json_number read_noise_dn "$C/noise.json")" 2.02 0.06
expect "noise: gain" near "$(json_number dn_per_electron "$C/noise.json")" 0.5 0.015

check "calibrate flat" 0 "$GLARECAM" calibrate flat "$T/flat" --out "$C/flat.json" \
  --calibration "$C/dark.json" --calibration "$C/linearity.json" --no-progress
expect "flat: the field" test -s "$C/flat-flat.exr"
# cos⁴ of the corner's field angle at 40° across 320x256 is 0.675; the smallest of the noisy
# pixels (0.56 % each) lies up to ~2 % below.
expect "flat: corner vignetting" near "$(json_number min "$C/flat.json")" 0.665 0.02

check "calibrate intrinsics" 0 "$GLARECAM" calibrate intrinsics "$T"/board-* --board 9x6 --square-mm 30 \
  --out "$C/intrinsics.json" --no-progress
expect "intrinsics: fx" near "$(json_number fx "$C/intrinsics.json")" "$(json_number fx "$T/board-00/truth.json")" 3.5
expect "intrinsics: RMS below 0.3 px" near "$(json_number rms_reprojection_px "$C/intrinsics.json")" 0.15 0.15

check "calibrate luminance" 0 "$GLARECAM" calibrate luminance "$T/luminance" --out "$C/luminance.json" \
  --reference 4990 --reference 5010 --roi 84,68,152,120 --calibration "$C/dark.json" \
  --calibration "$C/linearity.json" --calibration "$C/noise.json" --calibration "$C/flat.json" --no-progress
# K = 1500 to 0.5 % (the chain's flat and noise are measured, not true), u from the ±2 % meter.
expect "luminance: K" near "$(json_number luminance_factor "$C/luminance.json")" 1500 7.5
expect "luminance: u(K) about 1.2 %" near "$(json_number luminance_factor_u "$C/luminance.json")" 17.5 2

mkdir -p "$WORK/rig"
check "calibrate merge" 0 "$GLARECAM" calibrate merge "$C"/dark.json "$C"/linearity.json "$C"/noise.json \
  "$C"/flat.json "$C"/intrinsics.json "$C"/luminance.json --out "$WORK/rig/calibration.json"
expect "merge: the images beside it" test -s "$WORK/rig/flat-flat.exr" -a -s "$WORK/rig/dark-dark.exr"
expect "merge: six parts" test "$(grep -c '"method"' "$WORK/rig/calibration.json")" -eq 6

# The merged calibration processes a glare stack of the same (simulated) camera: the maximum
# luminance within 3 % of the truth (the chain's K, flat and saturation are all measured).
check "simulate a glare stack" 0 "$GLARECAM" simulate --size 320x256 --out "$WORK/glare" --no-progress
check "process with the calibration" 0 "$GLARECAM" process "$WORK/glare" \
  --calibration "$WORK/rig/calibration.json" --out "$WORK/glare-result" --no-progress
truth_max=$(json_number luminance_max_cd_m2 "$WORK/glare/truth.json")
measured_max=$(json_number max_cd_m2 "$WORK/glare-result/result.json")
expect "process: maximum luminance within 3 %" near "$measured_max" "$truth_max" "$(awk -v t="$truth_max" 'BEGIN { print 0.03 * t }')"
sed -i 's/"serial": "SIM-0001"/"serial": "OTHER-7"/' "$WORK/glare/stack.json"
check "process: another camera's calibration" 2 "$GLARECAM" process "$WORK/glare" \
  --calibration "$WORK/rig/calibration.json" --out "$WORK/glare-result" --no-progress
expect "process: serial mismatch named" one_line_naming "made for camera serial SIM-0001, but the stack was taken with serial OTHER-7"
check "process: forced" 0 "$GLARECAM" process "$WORK/glare" --calibration "$WORK/rig/calibration.json" \
  --force-calibration --out "$WORK/glare-result" --no-progress
check "process: old calibration warns" 0 "$GLARECAM" process "$WORK/glare" --calibration "$WORK/rig/calibration.json" \
  --force-calibration --max-calibration-age-days 1 --out "$WORK/glare-result" --no-progress
expect "process: the age warning names the part" grep -q "part dark was measured .* days ago" "$WORK/err"

# Drift check on the reference patch: K agrees with itself; the log gets a header and a line.
check "luminance --check" 0 "$GLARECAM" calibrate luminance "$T/luminance" --check \
  --calibration "$WORK/rig/calibration.json" --reference 5000 --roi 84,68,152,120 --log "$WORK/drift.csv" --no-progress
expect "check: drift printed" grep -q "drift" "$WORK/out"
check "luminance --check with a 6 % drift exits 1" 1 "$GLARECAM" calibrate luminance "$T/luminance" --check \
  --calibration "$WORK/rig/calibration.json" --reference 5300 --roi 84,68,152,120 --log "$WORK/drift.csv" --no-progress
expect "check: two lines and a header" test "$(wc -l <"$WORK/drift.csv")" -eq 3
expect "check: a 6 % drift says recalibrate" one_line_naming "recalibrate K"
expect "check: the report still printed" grep -q "drift +6" "$WORK/out"

# ---- capturing with --camera: the simulated camera in front of a target ----------------------
check "flat --camera" 0 "$GLARECAM" calibrate flat --camera sim:target=flat,size=320x256 \
  --exposures 2000,2000,2000,2000 --out "$C/camera-flat.json" --calibration "$C/dark.json" \
  --calibration "$C/linearity.json" --no-progress
expect "flat --camera: the captured stack kept beside the part" test -s "$(ls -d "$C"/camera-flat-stacks/*/ | head -1)stack.json"
expect "flat --camera: provenance names it" grep -q "camera-flat-stacks/" "$C/camera-flat.json"
expect "flat --camera: the same vignetting" near "$(json_number min "$C/camera-flat.json")" 0.665 0.02
check "noise --camera" 0 "$GLARECAM" calibrate noise --camera sim:target=noise,size=320x256 \
  --exposures 20,20,150,150,600,600,2000,2000,3000,3000 --out "$C/camera-noise.json" \
  --calibration "$C/dark.json" --calibration "$C/linearity.json" --no-progress
expect "noise --camera: gain" near "$(json_number dn_per_electron "$C/camera-noise.json")" 0.5 0.015
check "--camera without --exposures" 2 "$GLARECAM" calibrate flat --camera sim:target=flat --out "$C/x.json"
expect "--camera: exposures asked for" one_line_naming "--camera needs --exposures"
check "--camera and stacks" 2 "$GLARECAM" calibrate flat "$T/flat" --camera sim:target=flat --exposures 100 --out "$C/x.json"
check "neither stacks nor --camera" 2 "$GLARECAM" calibrate flat --out "$C/x.json"
check "--camera: unknown target" 2 "$GLARECAM" calibrate flat --camera sim:target=sphere --exposures 100 --out "$C/x.json"
expect "--camera: target named" one_line_naming "unknown calibration target \"sphere\""

# ---- bad inputs ------------------------------------------------------------------------------
check "dark: not a stack" 2 "$GLARECAM" calibrate dark "$WORK/nothing" --out "$C/x.json"
expect "dark: names the directory" one_line_naming "$WORK/nothing"
check "dark: lit frames" 2 "$GLARECAM" calibrate dark "$T/flat" --out "$C/x.json" --no-progress
expect "dark: lit frame named" one_line_naming "not a dark frame"
check "dark: no --out" 2 "$GLARECAM" calibrate dark "$T/dark" --no-progress
check "flat: no black level known" 2 "$GLARECAM" calibrate flat "$T/flat" --out "$C/x.json" --no-progress
expect "flat: says to run calibrate dark" one_line_naming "glarecam calibrate dark"
check "flat: saturated frames" 2 "$GLARECAM" calibrate flat "$T/luminance" --out "$C/x.json" \
  --calibration "$C/dark.json" --calibration "$C/linearity.json" --no-progress
check "noise: too few exposures" 2 "$GLARECAM" calibrate noise "$T/flat" --out "$C/x.json" \
  --calibration "$C/dark.json" --no-progress
expect "noise: pairs named" one_line_naming "needs pairs at 3 or more exposures"
check "luminance: no --reference" 2 "$GLARECAM" calibrate luminance "$T/luminance" --out "$C/x.json"
check "luminance: negative reference" 2 "$GLARECAM" calibrate luminance "$T/luminance" --out "$C/x.json" \
  --reference -5 --calibration "$C/dark.json" --no-progress
check "luminance: ROI outside" 2 "$GLARECAM" calibrate luminance "$T/luminance" --out "$C/x.json" \
  --reference 5000 --roi 300,200,100,100 --calibration "$C/dark.json" --no-progress
expect "luminance: ROI named" one_line_naming "--roi 300,200,100,100 is not inside the 320x256 frames"
check "luminance: ROI past int" 2 "$GLARECAM" calibrate luminance "$T/luminance" --out "$C/x.json" \
  --reference 5000 --roi 2147483000,0,1000,10 --calibration "$C/dark.json" --no-progress
check "luminance --check without --roi" 2 "$GLARECAM" calibrate luminance "$T/luminance" --check \
  --calibration "$C/dark.json" --reference 5000 --no-progress
check "luminance: bad ROI text" 2 "$GLARECAM" calibrate luminance "$T/luminance" --out "$C/x.json" \
  --reference 5000 --roi 1,2,3 --calibration "$C/dark.json" --no-progress
check "intrinsics: wrong board" 2 "$GLARECAM" calibrate intrinsics "$T"/board-* --board 8x5 --out "$C/x.json" --no-progress
expect "intrinsics: board not found" one_line_naming "found in 0 of 12"
check "intrinsics: square board" 2 "$GLARECAM" calibrate intrinsics "$T"/board-* --board 6x6 --out "$C/x.json" --no-progress
check "merge: one file" 2 "$GLARECAM" calibrate merge "$C/dark.json" --out "$C/x.json"
printf '{"schema": "glarecam.calibration/1", "camera": {"serial": "OTHER"}, "parts": {}}\n' >"$WORK/other.json"
check "merge: another camera" 2 "$GLARECAM" calibrate merge "$C/dark.json" "$WORK/other.json" --out "$C/x.json"
expect "merge: serials named" one_line_naming "camera serial \"OTHER\" differs"
printf '{"schema": "glarecam.calibration/1", "black_level_dn": 64,\n' >"$WORK/broken.json"
check "merge: broken JSON" 2 "$GLARECAM" calibrate merge "$C/dark.json" "$WORK/broken.json" --out "$C/x.json"
expect "merge: file named" one_line_naming "broken.json"
# A calibration made at another image size would give wrong angles (640x480 intrinsics halve a
# 320x256 stack's ellipse): merge refuses parts that disagree, naming both, and process refuses
# intrinsics of another size than the frames, even forced.
check "simulate-calibration board at 640x480" 0 "$GLARECAM" simulate-calibration board --size 640x480 \
  --out "$WORK/big"
check "calibrate intrinsics at 640x480" 0 "$GLARECAM" calibrate intrinsics "$WORK/big"/board-* --board 9x6 \
  --square-mm 30 --out "$C/intrinsics-640.json" --no-progress
expect "intrinsics: the part records its size" grep -q '"width": 640' "$C/intrinsics-640.json"
check "merge: parts of different sizes" 2 "$GLARECAM" calibrate merge "$C/flat.json" "$C/intrinsics-640.json" \
  --out "$C/x.json"
expect "merge: both sizes and files named" one_line_naming \
  "intrinsics-640.json: part intrinsics was measured at 640x480, but part flat of $C/flat.json at 320x256"
# The glare stack's own calibration (which records no size) merged with the 640x480 intrinsics.
python3 - "$WORK/glare/stack.json" "$WORK/own/own.json" <<'PY'
import json, os, sys
block = json.load(open(sys.argv[1]))["calibration"]
block.pop("flat_field", None)
block["schema"] = "glarecam.calibration/1"
os.makedirs(os.path.dirname(sys.argv[2]), exist_ok=True)
json.dump(block, open(sys.argv[2], "w"))
PY
check "merge: a sizeless calibration and 640x480 intrinsics" 0 "$GLARECAM" calibrate merge "$WORK/own/own.json" \
  "$C/intrinsics-640.json" --out "$WORK/own/mixed.json"
check "process: intrinsics of another size" 2 "$GLARECAM" process "$WORK/glare" \
  --calibration "$WORK/own/mixed.json" --out "$WORK/mixed-result" --no-progress
expect "process: sizes named" one_line_naming \
  "mixed.json: intrinsics were calibrated at 640x480, frames are 320x256"
check "process: another size is not forced" 2 "$GLARECAM" process "$WORK/glare" \
  --calibration "$WORK/own/mixed.json" --force-calibration --out "$WORK/mixed-result" --no-progress
expect "process: nothing written for another size" test ! -e "$WORK/mixed-result"
check "process: a part is not a calibration" 2 "$GLARECAM" process "$WORK/glare" --calibration "$C/dark.json" \
  --out "$WORK/glare-result" --no-progress
expect "process: missing key named" one_line_naming "saturation_dn is missing (a calibration part: combine the parts with"
check "simulate-calibration: unknown target" 2 "$GLARECAM" simulate-calibration sphere --out "$T"
expect "simulate-calibration: targets listed" one_line_naming "known: dark, flat"
expect "nothing half-written" test -z "$(find "$WORK" -name '.tmp-*')"

finish
