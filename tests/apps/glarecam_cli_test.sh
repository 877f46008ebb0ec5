#!/usr/bin/env bash
# End-to-end tests of the glarecam executable: exit statuses (0 ok, 2 bad input or usage,
# 1 other failure), one-line errors naming the file, and the outputs of simulate + process.
# Usage: glarecam_cli_test.sh GLARECAM BAD_STACK_CORPUS_DIR
set -uo pipefail
GLARECAM=$1
CORPUS=$2
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
source "$(dirname "$0")/cli_test_lib.sh"

# Usage errors.
check "help" 0 "$GLARECAM" --help
expect "help lists commands" grep -q "simulate" "$WORK/out"
check "process help" 0 "$GLARECAM" process --help
expect "process help types --alpha" grep -qE -- "--alpha DEG" "$WORK/out"
# Every option's value is named in --help (DEG, CD_M2, WxH, FILE, ...), never CLI11's bare TEXT.
for command in simulate simulate-calibration process sweep fit datasheet model "model fit" brdf \
    simulate-brdf route-check cameras capture \
    fake-camera sun alpha "inclinometer read" "inclinometer flip" gpio doctor "calibrate dark" \
    "calibrate flat" "calibrate linearity" "calibrate noise" "calibrate luminance" \
    "calibrate intrinsics" "calibrate merge"; do
  # shellcheck disable=SC2086 # the command's words
  "$GLARECAM" $command --help > "$WORK/help" 2>&1
  expect "$command --help names every option's value" \
    sh -c "! grep -E '^ +-[^ ]+ TEXT' '$WORK/help'"
done
# glarecam --help's "Docs:" list names every user guide in docs/ (not the developers' pages, nor
# the copied spec); the commands' own lines name theirs too, so only that list is read.
check "help lists the docs" 0 "$GLARECAM" --help
sed -n '/^Docs:/,/^Usage:/p' "$WORK/out" >"$WORK/docs-list"
for doc in "$(dirname "$0")"/../../docs/*.md; do
  name=docs/$(basename "$doc")
  case $name in docs/architecture.md | docs/fuzzing.md | docs/hazard-method.md) continue ;; esac
  expect "--help's Docs: list names $name" grep -qF "$name" "$WORK/docs-list"
done
# docs/process.md quotes the usage error as it is printed.
check "usage error" 2 "$GLARECAM" process --bogus
quoted=$(grep -o 'glarecam: [^`]*--bogus[^`]*' "$(dirname "$0")/../../docs/process.md")
expect "docs/process.md quotes a usage error" test -n "$quoted"
expect "usage error as docs/process.md quotes it" grep -qxF "$quoted" "$WORK/err"
check "no command" 2 "$GLARECAM"
check "unknown command" 2 "$GLARECAM" frobnicate
check "unknown option" 2 "$GLARECAM" process --frobnicate x
check "simulate without --out" 2 "$GLARECAM" simulate
check "alpha out of range" 2 "$GLARECAM" simulate --out "$WORK/x" --alpha 95
expect "alpha error is one line" one_line_naming "--alpha"
check "bad size" 2 "$GLARECAM" simulate --out "$WORK/x" --size 100by20
check "unknown module" 2 "$GLARECAM" simulate --out "$WORK/x" --module bifacial
expect "unknown module lists the known ones" one_line_naming "known: standard"
check "unknown surface" 2 "$GLARECAM" simulate --out "$WORK/x" --surface velvet
check "a missing surface file" 2 "$GLARECAM" simulate --out "$WORK/x" --surface "$WORK/none.toml"
check "module and surface" 2 "$GLARECAM" simulate --out "$WORK/x" --module standard --surface standard
check "a surface's stack" 0 "$GLARECAM" simulate -q --out "$WORK/surface-stack" --size 96x80 --surface glare-reduced --alpha 50
expect "the stack names its surface" grep -q '"surface": "glare-reduced"' "$WORK/surface-stack/stack.json"
check "unknown command named" 2 "$GLARECAM" frobnicate
expect "unknown command is named" one_line_naming 'unknown command "frobnicate"'
check "misspelt command" 2 "$GLARECAM" procss
expect "misspelt command gets a suggestion" one_line_naming 'unknown command "procss" (did you mean process?)'
check "misspelt subcommand" 2 "$GLARECAM" calibrate drak
expect "misspelt subcommand gets a suggestion" one_line_naming 'calibrate: unknown command "drak" (did you mean dark?)'
check "misspelt option" 2 "$GLARECAM" process --threshhold 3e4 "$WORK/x"
expect "misspelt option gets a suggestion" one_line_naming 'process: unknown option --threshhold (did you mean --threshold?)'
check "misspelt option with =" 2 "$GLARECAM" simulate --aplha=40 --out "$WORK/x"
expect "misspelt option with = gets a suggestion" one_line_naming 'simulate: unknown option --aplha (did you mean --alpha?)'
check "unknown option, nothing close" 2 "$GLARECAM" process --frobnicate x
expect "unknown option without a guess" one_line_naming 'process: unknown option --frobnicate'
expect "no guess when nothing is close" sh -c "! grep -q 'did you mean' '$WORK/err'"
check "a flag given a value" 2 "$GLARECAM" process --json=yes "$WORK/x"
expect "a flag given a value is refused" one_line_naming 'process: --json is a flag and takes no value (got "yes")'
check "a global flag given a value" 2 "$GLARECAM" --quiet=false simulate --out "$WORK/x"
expect "a global flag given a value is refused" one_line_naming "--quiet is a flag and takes no value"
check "negative seed" 2 "$GLARECAM" simulate --out "$WORK/x" --seed -1
check "hot pixels beyond 1 %" 2 "$GLARECAM" simulate --out "$WORK/x" --size 64x48 --hot-pixels 31
expect "hot pixels error is one line" one_line_naming "--hot-pixels must be between 0 and 1 %"
check "negative hot pixels" 2 "$GLARECAM" simulate --out "$WORK/x" --size 64x48 --hot-pixels=-1
check "fixed pattern beyond 100 DN" 2 "$GLARECAM" simulate --out "$WORK/x" --size 64x48 --fixed-pattern 101
expect "fixed pattern error is one line" one_line_naming "--fixed-pattern must be between 0 and 100 DN"
check "bad sensor seed" 2 "$GLARECAM" simulate --out "$WORK/x" --size 64x48 --sensor-seed x
expect "bad sensor seed is one line" one_line_naming "--sensor-seed"
check "simulate-calibration: bad sensor seed" 2 "$GLARECAM" simulate-calibration dark --out "$WORK/x" --sensor-seed -3
expect "simulate-calibration: bad sensor seed is one line" one_line_naming "--sensor-seed"
check "trailing comma" 2 "$GLARECAM" simulate --out "$WORK/x" --distortion=0.1,
check "folding distortion" 2 "$GLARECAM" simulate --out "$WORK/x" --size 64x48 --distortion=-5
check "lobe outside the frame" 2 "$GLARECAM" simulate --out "$WORK/x" --size 64x48 --offset-deg 30,0
check "background above the limit" 2 "$GLARECAM" simulate --out "$WORK/x" --size 64x48 --background 30000
check "empty --out" 2 "$GLARECAM" simulate --out "" --size 64x48
check "global option after the command" 0 "$GLARECAM" simulate --out "$WORK/y" --size 64x48 -q
expect "nothing written on bad input" test ! -e "$WORK/x"

# The happy path.
check "simulate" 0 "$GLARECAM" simulate --out "$WORK/s" --alpha 70 --size 200x160 --fov 16 --seed 3
expect "simulate prints the stack path" grep -qF "$WORK/s" "$WORK/out"
expect "stack has manifest and truth" test -f "$WORK/s/stack.json" -a -f "$WORK/s/truth.json"
check "process" 0 "$GLARECAM" process --no-progress "$WORK/s"
for f in luminance.exr quality.exr luminance.png result.json; do
  expect "process writes $f" test -s "$WORK/s/result/$f"
done
check "process --json" 0 "$GLARECAM" process --no-progress --json --out "$WORK/r2" "$WORK/s"
expect "--json prints the result" grep -q '"schema": "glarecam.result/1"' "$WORK/out"
expect "--json result has glare" grep -q '"glare": true' "$WORK/out"
expect "--out is honoured" test -s "$WORK/r2/result.json"
expect "--json has the limit ellipse" grep -q '"vertical_deg"' "$WORK/out"
expect "--json has the contour ladder with its limit and half-maximum rungs" \
  bash -c "grep -q '\"kind\": \"ladder\"' '$WORK/out' && grep -q '\"kind\": \"limit\"' '$WORK/out' && grep -q '\"kind\": \"half_maximum\"' '$WORK/out'"
check "process --no-ladder" 0 "$GLARECAM" process --no-progress --json --no-ladder --out "$WORK/r2" "$WORK/s"
expect "--no-ladder: no contours" grep -q '"contours": null' "$WORK/out"
expect "--json has both ellipses with uncertainties" \
  test "$(grep -c '"uncertainty": {' "$WORK/out")" -eq 2

# Glare-limit options.
check "--threshold" 0 "$GLARECAM" process --no-progress --json --out "$WORK/r3" --threshold 30000 "$WORK/s"
expect "--threshold is the constant mode" grep -q '"mode": "constant"' "$WORK/out"
check "--thresholds" 0 "$GLARECAM" process --no-progress --json --no-ladder --out "$WORK/r3" --thresholds 5e4,2e5 "$WORK/s"
expect "--thresholds gives one ellipse each" \
  test "$(grep -c '"threshold_cd_m2"' "$WORK/out")" -eq 2 -a "$(grep -c '"uncertainty": {' "$WORK/out")" -eq 4
for bad in abc -5 0 nan 1e400 "30000,40000"; do
  check "bad --threshold $bad" 2 "$GLARECAM" process --no-progress --out "$WORK/r4" --threshold="$bad" "$WORK/s"
  expect "bad --threshold $bad is one line naming the option" one_line_naming "--threshold"
done
for bad in "1e5," "1e5,,2e5" "1e5,x" "-1"; do
  check "bad --thresholds $bad" 2 "$GLARECAM" process --no-progress --out "$WORK/r4" --thresholds="$bad" "$WORK/s"
  expect "bad --thresholds $bad is one line" one_line_naming "--thresholds"
done
for option in --threshold --thresholds --out --calibration; do  # e.g. an unset shell variable
  check "empty $option" 2 "$GLARECAM" process --no-progress "$WORK/s" "$option" ""
  expect "empty $option is named" one_line_naming "$option"
done
check "thousands separator" 2 "$GLARECAM" process --no-progress --out "$WORK/r4" --threshold 30,000 "$WORK/s"
expect "thousands separator error says one number" one_line_naming "expected one number"
expect "nothing written on bad thresholds" test ! -e "$WORK/r4"
# The source illuminance (docs/process.md, "Referred and unreferred"): a bad value is refused
# with exit 2 naming where it came from, before anything is written.
for bad in -5 0 nan inf 1e400 150001 abc "90000±90000" "90000±-5"; do
  check "bad --source-illuminance $bad" 2 "$GLARECAM" process --no-progress --out "$WORK/r6" \
    --source-illuminance="$bad" "$WORK/s"
  expect "bad --source-illuminance $bad is one line naming the option" one_line_naming "--source-illuminance"
  check "simulate: bad --source-illuminance $bad" 2 "$GLARECAM" simulate --out "$WORK/r6s" \
    --size 64x48 --source-illuminance="$bad"
  expect "simulate: bad --source-illuminance $bad names the option" one_line_naming "--source-illuminance"
  check "capture: bad --source-illuminance $bad" 2 "$GLARECAM" capture --camera sim:size=64x48 \
    --alpha 40 --out "$WORK/r6c" --source-illuminance="$bad"
  expect "capture: bad --source-illuminance $bad names the option" one_line_naming "--source-illuminance"
done
for bad in 0 -1 nan 2e5; do
  check "bad --reference-illuminance $bad" 2 "$GLARECAM" process --no-progress --out "$WORK/r6" \
    --reference-illuminance="$bad" "$WORK/s"
  expect "bad --reference-illuminance $bad names the option" one_line_naming "--reference-illuminance"
done
expect "nothing written on a bad illuminance" test ! -e "$WORK/r6" -a ! -e "$WORK/r6s" -a ! -e "$WORK/r6c"
# A stack recorded without a source (an older rig's): unreferred, unless a value or the clear-sky
# estimate is given; the estimate needs the sun the rig measured, which a simulated stack has not.
check "simulate --unreferred" 0 "$GLARECAM" simulate --out "$WORK/su" --alpha 70 --size 200x160 --fov 16 -q --unreferred
check "process an unreferred stack" 0 "$GLARECAM" process --no-progress --json --out "$WORK/ru" "$WORK/su"
expect "an unreferred result says so" grep -q '"status": "unreferred"' "$WORK/out"
check "process a referred stack" 0 "$GLARECAM" process --no-progress --json --out "$WORK/ru" "$WORK/s"
expect "a simulated stack is referred to 100 klx" grep -q '"reference_lx": 100000' "$WORK/out"
check "process with a given source" 0 "$GLARECAM" process --no-progress --json --out "$WORK/ru" \
  --source-illuminance 80000+-2400 "$WORK/su"
expect "a given source is recorded as given" grep -q '"origin": "given"' "$WORK/out"
check "clear-sky without a sun" 2 "$GLARECAM" process --no-progress --out "$WORK/ru2" \
  --source-illuminance clear-sky "$WORK/su"
expect "clear-sky without a sun says why" one_line_naming "records no sun"
check "clear-sky on a stack with a source" 0 "$GLARECAM" process --no-progress --json --out "$WORK/ru" \
  --source-illuminance clear-sky "$WORK/s"
expect "the recorded source is kept" grep -q '"origin": "given"' "$WORK/out"
expect "keeping it is warned about" grep -q "kept: the clear-sky estimate is only for a stack that records none" "$WORK/err"
python3 - "$WORK/su/stack.json" <<'PY'
import json, sys
path = sys.argv[1]
manifest = json.load(open(path))
manifest["geometry"] = {
    "source": "sun", "time": "2026-06-21T11:30:00Z", "sun_elevation_deg": 40.0,
    "alpha_deg": 70.0, "alpha_uncertainty_deg": 0.1, "module_tilt_deg": 30.0,
    "module_azimuth_deg": 180.0}
json.dump(manifest, open(path, "w"))
PY
check "clear-sky with the rig's sun" 0 "$GLARECAM" process --no-progress --json --out "$WORK/ru" \
  --source-illuminance clear-sky "$WORK/su"
expect "the clear-sky estimate is marked clear_sky" grep -q '"origin": "clear_sky"' "$WORK/out"

# A lens with distortion and levels whose region is the whole view or none: statuses, exit 0.
check "simulate with distortion" 0 "$GLARECAM" simulate --out "$WORK/sd" --size 160x128 --fov 16 --distortion=-0.05 -q
check "thresholds below the background and above the maximum" 0 "$GLARECAM" process --no-progress --json --thresholds 1000,1e12 "$WORK/sd"
expect "a level below the background fills the image" grep -q '"status": "fills_image"' "$WORK/out"
expect "a level above the maximum is below_level" grep -q '"status": "below_level"' "$WORK/out"

# A principal point far from the image centre (intrinsics of another crop or orientation) warns.
python3 - "$WORK/sd/stack.json" "$WORK/off-centre.json" <<'PY'
import json, sys
block = json.load(open(sys.argv[1]))["calibration"]
block.pop("flat_field", None)
block["intrinsics"]["cx"] += 40  # 25 % of the 160 px width
json.dump(block, open(sys.argv[2], "w"))
PY
check "process with an off-centre principal point" 0 "$GLARECAM" process --no-progress --out "$WORK/r5" \
  --calibration "$WORK/off-centre.json" "$WORK/sd"
expect "the off-centre principal point warns" grep -q "off-centre.json: the principal point (119.5, 63.5) lies 40 px" "$WORK/err"
check "process with a centred principal point" 0 "$GLARECAM" process --no-progress --out "$WORK/r5" "$WORK/sd"
expect "a centred principal point does not warn" test -z "$(grep "principal point" "$WORK/err")"

# Calibration override from the command line.
check "process with missing --calibration" 2 "$GLARECAM" process "$WORK/s" --calibration "$WORK/none.json"
expect "missing calibration named" one_line_naming "none.json"

# Failures that are not the user's input exit 1.
check "unwritable output" 1 "$GLARECAM" process --no-progress --out /proc/glarecam-cannot-write "$WORK/s"
expect "unwritable output is one line" one_line_naming "/proc/glarecam-cannot-write"

# Never replace what is not a stack; never read what is not a directory.
mkdir -p "$WORK/precious" && echo keep >"$WORK/precious/thesis.txt"
check "simulate over a non-stack directory" 2 "$GLARECAM" simulate --out "$WORK/precious" --size 32x32
expect "non-stack directory untouched" grep -q keep "$WORK/precious/thesis.txt"
expect "refusal is one line" one_line_naming "refusing to replace"
check "simulate over a file" 2 "$GLARECAM" simulate --out "$WORK/precious/thesis.txt" --size 32x32
check "simulate over ." 2 "$GLARECAM" simulate --out . --size 32x32
check "process a regular file" 2 "$GLARECAM" process "$WORK/precious/thesis.txt"
expect "regular file: not a stack directory" one_line_naming "not a stack directory"

# Sweep, fit, datasheet, model.
TABLE3="$CORPUS/../standard-module-table3.csv"
for alpha in 20 40 60 80; do
  check "simulate sweep stack $alpha" 0 "$GLARECAM" simulate --out "$WORK/sweep-in/a$alpha" \
    --alpha "$alpha" --size 160x128 --fov 16 --seed "$alpha" --no-progress
done
mkdir -p "$WORK/sweep-in/broken" && echo "{" >"$WORK/sweep-in/broken/stack.json"
check "sweep" 0 "$GLARECAM" sweep "$WORK/sweep-in" --out "$WORK/sw" --jobs 2 --no-progress
expect "sweep prints the table's path" grep -qx "$WORK/sw/sweep.csv" "$WORK/out"
expect "sweep reports the broken stack" grep -q "skipped $WORK/sweep-in/broken" "$WORK/err"
expect "sweep table notes the broken stack" grep -q "^# skipped $WORK/sweep-in/broken" "$WORK/sw/sweep.csv"
expect "sweep table has 4 rows sorted by alpha" \
  test "$(grep -v '^#' "$WORK/sw/sweep.csv" | tail -n +2 | cut -d, -f1 | tr '\n' ' ')" = "20 40 60 80 "
expect "sweep wrote each result" test -s "$WORK/sw/results/a60/result.json"
expect "sweep wrote contours.csv beside sweep.csv" \
  grep -q '^stack_id,alpha_deg,level_cd_m2,kind,status,vertical_deg' "$WORK/sw/contours.csv"
expect "contours.csv has each stack's ladder, the limit and half maximum among it" \
  bash -c "grep -q ',20,10000,ladder,' '$WORK/sw/contours.csv' && grep -q ',80,400000,limit,' '$WORK/sw/contours.csv' && test \$(grep -c ',half_maximum,' '$WORK/sw/contours.csv') -eq 4"
check "sweep --strict with a broken stack" 2 "$GLARECAM" sweep "$WORK/sweep-in" --out "$WORK/sw2" --strict --no-progress
expect "--strict still writes the table" test -s "$WORK/sw2/sweep.csv"
# A stack whose frames disagree (two frames swapped) is flagged all the way down: sweep.csv marks
# the row suspect with the reason, --strict fails on it, fit leaves it out and says so, the
# picture carries a banner.
mkdir -p "$WORK/swapped-in"
for alpha in 20 40 60 80; do cp -r "$WORK/sweep-in/a$alpha" "$WORK/swapped-in/"; done
# A fifth stack: the fits need four rows besides the suspect one.
check "simulate a fifth sweep stack" 0 "$GLARECAM" simulate --out "$WORK/swapped-in/a70" --alpha 70 \
  --size 160x128 --fov 16 --seed 70 --no-progress
python3 - "$WORK/swapped-in/a40/stack.json" <<'PY'
import json, sys
manifest = json.load(open(sys.argv[1]))
frames = manifest["frames"]
frames[2]["file"], frames[3]["file"] = frames[3]["file"], frames[2]["file"]
json.dump(manifest, open(sys.argv[1], "w"))
PY
check "sweep with a swapped-frame stack" 0 "$GLARECAM" sweep "$WORK/swapped-in" --out "$WORK/sws" --no-progress
expect "sweep.csv has frames_consistent and suspect" grep -q "frames_consistent,suspect" "$WORK/sws/sweep.csv"
expect "the swapped stack's row is suspect, with the frames named" \
  grep -q '^40,.*,false,"\?frames disagree with the merge: frame-0[23].png reads' "$WORK/sws/sweep.csv"
expect "the other rows are not suspect" test "$(grep -c ',measured,true,,' "$WORK/sws/sweep.csv")" -eq 4
expect "the picture is bannered" test -s "$WORK/sws/results/a40/luminance.png"
check "sweep --strict with a suspect row" 2 "$GLARECAM" sweep "$WORK/swapped-in" --out "$WORK/sws2" --strict --no-progress
expect "--strict names the suspect row" grep -q "1 suspect row(s), the first $WORK/swapped-in/a40: frames disagree" "$WORK/err"
check "fit leaves the suspect row out" 0 "$GLARECAM" fit "$WORK/sws/sweep.csv" --json
expect "fit says so" grep -q "1 suspect row(s)" "$WORK/err"
expect "fit lists the row" grep -q "suspect: α 40° .*frames disagree" "$WORK/err"
check "fit --include-suspect" 0 "$GLARECAM" fit "$WORK/sws/sweep.csv" --include-suspect
expect "fit --include-suspect says it fitted the row" grep -q "suspect (fitted as asked): α 40°" "$WORK/err"
check "datasheet of the sweep with a suspect row" 0 "$GLARECAM" datasheet "$WORK/sws/sweep.csv" --date 2026-06-21
expect "its profile is /2 with the sweep's ladder from 20 to 80°" python3 -c '
import json, sys
p = json.load(open(sys.argv[1]))
assert p["schema"] == "glarecam.glare-profile/2", p["schema"]
assert [r["alpha_deg"] for r in p["ladder"]] == list(range(20, 81)), [r["alpha_deg"] for r in p["ladder"]]
assert p["ladder"][0]["contours"][0]["level_cd_m2"] == 10000
' "$WORK/sws/glare-profile.json"
expect "datasheet warns about the suspect row" grep -q "suspect: α 40°" "$WORK/err"

check "sweep of nothing usable" 2 "$GLARECAM" sweep "$WORK/sweep-in/broken" "$WORK/nowhere" --out "$WORK/sw3"
expect "nothing usable: no table" test ! -e "$WORK/sw3/sweep.csv"
check "sweep --jobs 0" 2 "$GLARECAM" sweep "$WORK/sweep-in" --jobs 0
check "sweep --memory 0" 2 "$GLARECAM" sweep "$WORK/sweep-in" --memory 0
check "sweep --memory 1 runs one job" 0 "$GLARECAM" -v sweep "$WORK/sweep-in" --out "$WORK/sw4" \
  --memory 1 --threads 2 --no-progress
expect "the log says one at a time" grep -q "sweep: 5 stacks, 1 at once with 2 threads each" "$WORK/err"
check "sweep --threshold bad" 2 "$GLARECAM" sweep "$WORK/sweep-in" --threshold -5

check "fit the sweep" 0 "$GLARECAM" fit "$WORK/sw/sweep.csv"
expect "fit reports R²" grep -q "R²" "$WORK/out"
check "fit table III --json" 0 "$GLARECAM" fit "$TABLE3" --json
for key in '"cos"' '"biquadratic"' '"logistic"' '"r2"' '"standard_errors"'; do
  expect "fit json has $key" grep -q "$key" "$WORK/out"
done
printf 'alpha_deg,lmax_cd_m2\n5,1\n' >"$WORK/missing-col.csv"
check "fit: missing columns" 2 "$GLARECAM" fit "$WORK/missing-col.csv"
expect "missing columns named" one_line_naming "missing-col.csv:1: missing column(s) limit_cd_m2"
head -3 "$TABLE3" >"$WORK/short.csv"
check "fit: fewer rows than parameters" 2 "$GLARECAM" fit "$WORK/short.csv"
expect "too few rows named" one_line_naming "short.csv: 2 rows"
sed 's/^40,/95,/' "$TABLE3" >"$WORK/alpha95.csv"
check "fit: alpha outside 0-90" 2 "$GLARECAM" fit "$WORK/alpha95.csv"
expect "alpha outside named with its line" one_line_naming "alpha95.csv:6: alpha_deg 95"
sed 's/^50,30000,839000/50,30000,lots/' "$TABLE3" >"$WORK/nonnum.csv"
check "fit: non-numeric" 2 "$GLARECAM" fit "$WORK/nonnum.csv"
expect "non-numeric named" one_line_naming 'nonnum.csv:7: lmax_cd_m2: "lots"'
check "fit: missing file" 2 "$GLARECAM" fit "$WORK/none.csv"

check "datasheet" 0 "$GLARECAM" datasheet "$TABLE3" --out "$WORK/ds" --module "Table III" --date 2026-11-26 --model-beta 1.25
for f in datasheet.pdf datasheet.svg datasheet.png glare-profile.json; do
  expect "datasheet wrote $f" test -s "$WORK/ds/$f"
done
expect "profile carries the date" grep -q '"date": "2026-11-26"' "$WORK/ds/glare-profile.json"
SOURCE_DATE_EPOCH=0 check "datasheet at SOURCE_DATE_EPOCH" 0 "$GLARECAM" datasheet "$TABLE3" --out "$WORK/ds0"
expect "SOURCE_DATE_EPOCH date" grep -q '"date": "1970-01-01"' "$WORK/ds0/glare-profile.json"
check "datasheet: bad date" 2 "$GLARECAM" datasheet "$TABLE3" --out "$WORK/ds1" --date 2026-02-30
check "datasheet: module name not UTF-8" 2 "$GLARECAM" datasheet "$TABLE3" --out "$WORK/ds1" --module $'bad\xff'
expect "module name error is one line" one_line_naming "--module: not valid UTF-8"
check "datasheet: module name in UTF-8" 0 "$GLARECAM" datasheet "$TABLE3" --out "$WORK/ds2" --module "Modul Ä – β"
check "datasheet: bad model beta" 2 "$GLARECAM" datasheet "$TABLE3" --out "$WORK/ds1" --model-beta 60
check "datasheet: bad table" 2 "$GLARECAM" datasheet "$WORK/nonnum.csv" --out "$WORK/ds1"
expect "nothing written for a bad table" test ! -e "$WORK/ds1/datasheet.pdf"
# A sheet never shows a limit its axes were not measured at (Table III: the α curve).
check "datasheet: --threshold other than the sweep's limit" 2 "$GLARECAM" datasheet "$TABLE3" --out "$WORK/ds3" \
  --threshold 50000
expect "--threshold refusal names both limits" \
  grep -qF -- "--threshold 50000 cd/m² differs from the limit the sweep measured its ellipses at (the α curve)" "$WORK/err"
expect "nothing written for another limit" test ! -e "$WORK/ds3/datasheet.pdf"
check "datasheet beside the sweep table" 0 "$GLARECAM" datasheet "$WORK/sw/sweep.csv"
expect "default --out is the table's directory" test -s "$WORK/sw/datasheet.pdf"
check "sweep into a used directory" 0 "$GLARECAM" sweep "$WORK/sweep-in/a20" "$WORK/sweep-in/a40" --out "$WORK/sw" --no-progress
expect "earlier data sheet warned about" grep -q "datasheet.pdf is from an earlier run" "$WORK/err"
expect "earlier results warned about" grep -q "2 result(s) of stacks not in this sweep" "$WORK/err"

check "model" 0 "$GLARECAM" model --beta 2.5 --alpha 0 60
expect "model at normal incidence: 2 beta" grep -qE "^ +0 +5\.0000 +5\.0000 +yes" "$WORK/out"
check "model --json" 0 "$GLARECAM" model --beta 2.5 --json
expect "model json keys" grep -q '"gamma_ew_deg"' "$WORK/out"
check "model: missing --beta" 2 "$GLARECAM" model
check "model: beta 0" 2 "$GLARECAM" model --beta 0
check "model: alpha 100" 2 "$GLARECAM" model --beta 2 --alpha 100
expect "model alpha error is one line" one_line_naming "--alpha: 100"

# The BRDF route (docs/brdf.md): a simulated lab, the route, the model fit, and bad inputs.
check "simulate-brdf" 0 "$GLARECAM" simulate-brdf --surface standard --alpha 10,40 --format both \
  --out "$WORK/lab"
expect "simulate-brdf writes both formats and the truth" \
  test -s "$WORK/lab/a10.dat" -a -s "$WORK/lab/surface.bsdf" -a -s "$WORK/lab/truth.json"
check "brdf" 0 "$GLARECAM" brdf --no-progress "$WORK/lab/a10.dat" "$WORK/lab/a40.dat" \
  --out "$WORK/brdf" --pixels 301
expect "brdf rows are marked brdf" grep -q ',brdf,' "$WORK/brdf/sweep.csv"
check "brdf of the Zemax file" 0 "$GLARECAM" brdf --no-progress --json "$WORK/lab/surface.bsdf" \
  --out "$WORK/brdf-z" --pixels 301
expect "brdf --json names the sweep" grep -q '"sweep_csv"' "$WORK/out"
check "model fit" 0 "$GLARECAM" model fit "$TABLE3" --out "$WORK/fitted.toml"
expect "model fit reports R² beside the empirical fits" grep -q '^  empirical' "$WORK/out"
check "simulate-brdf from the fitted file" 0 "$GLARECAM" simulate-brdf --surface "$WORK/fitted.toml" \
  --alpha 30 --format pabopto --out "$WORK/lab2"
printf '#format: theta phi BSDF\n#intheta 10\n#inphi 0\n1 0 -1\n' > "$WORK/negative.dat"
check "brdf: negative value" 2 "$GLARECAM" brdf --no-progress "$WORK/negative.dat" --out "$WORK/b2"
expect "brdf: the error names the file and line" one_line_naming "negative.dat:4: negative value"
check "brdf: missing file" 2 "$GLARECAM" brdf --no-progress "$WORK/none.dat" --out "$WORK/b3"
check "brdf: unknown format" 2 "$GLARECAM" brdf --no-progress "$TABLE3" --out "$WORK/b4"
expect "brdf: unknown format is said" one_line_naming "unknown BRDF format"
check "brdf: even pixels" 2 "$GLARECAM" brdf --no-progress "$WORK/lab/a10.dat" --pixels 300
check "simulate-brdf: unknown surface" 2 "$GLARECAM" simulate-brdf --surface velvet --out "$WORK/x"
expect "unknown surface lists the names" one_line_naming "standard, glare-reduced, gaussian"
check "model fit: not a table" 2 "$GLARECAM" model fit "$WORK/lab/a10.dat"
check "simulate-brdf: α must ascend" 2 "$GLARECAM" simulate-brdf --alpha 30,10 --out "$WORK/x"
expect "descending α is said" one_line_naming "must ascend"
check "model fit from a start file" 0 "$GLARECAM" model fit "$TABLE3" --start "$WORK/fitted.toml"

# The route check: one α of each route, small; its refusals.
check "route-check" 0 "$GLARECAM" route-check --no-progress --alpha 30,75 --size 320x256 --fov 24 \
  --out "$WORK/rc"
expect "route-check prints its verdict and table" grep -q "the routes agree within" "$WORK/out"
expect "route-check names the α it cannot compare" grep -q "beyond the goniophotometer" "$WORK/out"
expect "route-check writes its CSV" test -s "$WORK/rc/route-check.csv"
check "route-check --json" 0 "$GLARECAM" route-check --no-progress --alpha 30 --size 320x256 --fov 24 \
  --out "$WORK/rc" --json
expect "route-check --json says agree" grep -q '"agree": true' "$WORK/out"
check "route-check: α 0" 2 "$GLARECAM" route-check --alpha 0,30 --out "$WORK/rc"
check "route-check: α descending" 2 "$GLARECAM" route-check --alpha 30,10 --out "$WORK/rc"
expect "descending α is said" one_line_naming "ascend"
check "route-check: unknown surface" 2 "$GLARECAM" route-check --surface velvet --alpha 30 --out "$WORK/rc"
check "route-check: bad size" 2 "$GLARECAM" route-check --size 10x10 --alpha 30 --out "$WORK/rc"
check "route-check: empty --out" 2 "$GLARECAM" route-check --alpha 30 --out ""
check "route-check: --json and --markdown" 2 "$GLARECAM" route-check --json --markdown --alpha 30
check "route-check: negative seed" 2 "$GLARECAM" route-check --seed -1 --alpha 30 --out "$WORK/rc"
mkdir -p "$WORK/busy" && echo mine >"$WORK/busy/notes.txt"
check "route-check: a directory of other files" 2 "$GLARECAM" route-check --alpha 30 --out "$WORK/busy"
expect "the busy directory is named with what it holds" one_line_naming "notes.txt"
check "route-check: --out a file" 2 "$GLARECAM" route-check --alpha 30 --out "$WORK/busy/notes.txt"
check "route-check: nothing to compare" 1 "$GLARECAM" route-check --no-progress --alpha 30 \
  --size 320x256 --fov 24 --fine-step 1 --out "$WORK/rc"
expect "nothing compared is said" one_line_naming "nothing compared"
# Agreement asked far tighter than the routes can: they "disagree", exit 1 with the verdict.
check "route-check: an impossible agreement" 1 "$GLARECAM" route-check --no-progress --alpha 30 \
  --size 320x256 --fov 24 --out "$WORK/rc" --agreement 0.001
expect "the disagreement is said" one_line_naming "BEYOND"

# Cameras: the simulator through the camera interface, and the no-device error paths.
check "cameras" 0 "$GLARECAM" cameras
expect "cameras lists the simulator" grep -q "^sim:" "$WORK/out"
check "cameras --json" 0 "$GLARECAM" cameras --json
expect "cameras --json has a cameras array" grep -q '"cameras": \[' "$WORK/out"
check "capture sim" 0 "$GLARECAM" capture --camera sim:size=200x160,fov=16 --alpha 70 --out "$WORK/cap" \
  --module "ACME 400 #17" --no-progress
expect "capture prints the stack path" grep -q "^$WORK/cap/.*-a70.00$" "$WORK/out"
captured=$(cat "$WORK/out")
check "process a captured stack" 0 "$GLARECAM" process --no-progress --json "$captured"
expect "captured stack glares at α 70" grep -q '"glare": true' "$WORK/out"
expect "the module travels from capture to result.json" grep -q '"module": "ACME 400 #17"' "$WORK/out"
check "capture: empty --module" 2 "$GLARECAM" capture --camera sim:size=64x48 --module "" --out "$WORK/x" --no-progress
expect "empty --module is one line" one_line_naming "--module must not be empty"
check "capture series" 0 "$GLARECAM" capture --camera sim:size=64x48 --out "$WORK/series" --exposures 100,1000 --count 2 --no-progress
expect "series wrote two stacks" test "$(wc -l <"$WORK/out")" -eq 2 -a "$(ls "$WORK/series" | wc -l)" -eq 2
# Ctrl-C stops a series after the stack being captured: complete stacks only, exit 1, one line.
"$GLARECAM" capture --camera sim:size=64x48 --out "$WORK/interrupted" --exposures 100 --count 1000 \
  --interval 0.2 --no-progress >"$WORK/out" 2>"$WORK/err" &
series_pid=$!
# Interrupted once its first stack is there (so not before it handles SIGINT), at most 30 s on.
for _ in $(seq 300); do
  [ -n "$(ls "$WORK/interrupted" 2>/dev/null)" ] && break
  sleep 0.1
done
kill -INT $series_pid
wait $series_pid
status=$?
expect "an interrupted series exits 1 (got $status)" test $status -eq 1
expect "an interrupted series says how far it got" one_line_naming "interrupted after"
expect "every stack of an interrupted series is complete" \
  test "$(ls "$WORK/interrupted" | wc -l)" -eq "$(wc -l <"$WORK/out")" -a -z "$(ls -A "$WORK/interrupted" | grep '^\.')"
mkdir "$WORK/series/.tmp-killed-stack-x1y2z3" && touch -d '1 hour ago' "$WORK/series/.tmp-killed-stack-x1y2z3"
check "capture after a killed one" 0 "$GLARECAM" capture --camera sim:size=64x48 --out "$WORK/series" --exposures 100 --no-progress
expect "the killed capture's staging directory is gone" test ! -e "$WORK/series/.tmp-killed-stack-x1y2z3"
check "capture: unknown backend" 2 "$GLARECAM" capture --camera gige:cam1 --out "$WORK/nocap"
expect "unknown backend is one line" one_line_naming "unknown backend"
check "capture: bad exposures" 2 "$GLARECAM" capture --camera sim: --out "$WORK/nocap" --exposures 10,abc
check "capture: exposure out of range" 2 "$GLARECAM" capture --camera sim:size=64x48 --out "$WORK/nocap" --exposures 1
expect "out-of-range exposure names the camera" one_line_naming "outside sim:size=64x48's range"
check "capture: bad sim parameter" 2 "$GLARECAM" capture --camera sim:colour=red --out "$WORK/nocap"
check "capture: sim α contradicting --alpha" 2 "$GLARECAM" capture --camera sim:alpha=20 --alpha 30 --out "$WORK/nocap"
check "capture: lens options for the sim camera" 2 "$GLARECAM" capture --camera sim: --f-number 4 --out "$WORK/nocap"
check "capture: a pixel format the sim camera lacks" 2 "$GLARECAM" capture --camera sim: --pixel-format Mono8 --out "$WORK/nocap"
check "capture: alpha 95" 2 "$GLARECAM" capture --camera sim: --out "$WORK/nocap" --alpha 95
check "capture: count 0" 2 "$GLARECAM" capture --camera sim: --out "$WORK/nocap" --count 0
check "capture: --max-retries above 1000" 2 "$GLARECAM" capture --camera sim: --out "$WORK/nocap" --max-retries 1001
check "capture: negative --interval" 2 "$GLARECAM" capture --camera sim: --out "$WORK/nocap" --interval -1
check "capture: --interval over a week" 2 "$GLARECAM" capture --camera sim: --out "$WORK/nocap" --interval 1e9
check "capture: --f-number 0" 2 "$GLARECAM" capture --camera v4l2:/dev/null --out "$WORK/nocap" --f-number 0
check "capture: --nd-transmission above 1" 2 "$GLARECAM" capture --camera sim: --out "$WORK/nocap" --nd-transmission 2
check "capture: --gain beyond the camera" 2 "$GLARECAM" capture --camera sim:size=64x48 --out "$WORK/nocap" --gain 40
expect "gain error names the range" one_line_naming "outside sim:size=64x48's range"
check "capture: --gain not a number" 2 "$GLARECAM" capture --camera sim: --out "$WORK/nocap" --gain loud
check "capture: missing calibration file" 2 "$GLARECAM" capture --camera sim: --out "$WORK/nocap" --calibration "$WORK/none.json"
touch "$WORK/a-file"
check "capture: --out is a file" 2 "$GLARECAM" capture --camera sim: --out "$WORK/a-file"
check "capture: empty --out" 2 "$GLARECAM" capture --camera sim: --out ""
expect "nothing captured on bad input" test ! -e "$WORK/nocap"
check "capture: no V4L2 device" 1 "$GLARECAM" capture --camera v4l2:/dev/video-glarecam-missing --out "$WORK/nocap"
expect "missing V4L2 device is one line naming the URI" one_line_naming "v4l2:/dev/video-glarecam-missing"
check "capture: no libcamera camera" 1 "$GLARECAM" capture --camera libcamera: --out "$WORK/nocap"
expect "missing libcamera camera names the URI" grep -q "libcamera:" "$WORK/err"
check "capture: no Aravis camera" 1 "$GLARECAM" capture --camera aravis:glarecam-none --out "$WORK/nocap"
expect "missing Aravis camera names the URI" grep -q "aravis:glarecam-none" "$WORK/err"

# Every bad stack of the corpus: exit 2, one line naming the stack's file and the problem.
check "missing stack" 2 "$GLARECAM" process "$WORK/no-such-stack"
for stack in "$CORPUS"/*/; do
  name=$(basename "$stack")
  check "bad stack $name" 2 "$GLARECAM" process --no-progress --out "$WORK/bad-out" "$stack"
  expect "bad stack $name: one line with the expected text" one_line_naming "$(head -1 "$stack/expect.txt")"
  expect "bad stack $name: names the stack" grep -qF "$name" "$WORK/err"
done
expect "no output for bad stacks" test ! -e "$WORK/bad-out/result.json"

finish
