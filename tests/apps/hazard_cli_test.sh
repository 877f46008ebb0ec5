#!/usr/bin/env bash
# glarecam hazard end to end: a profile from the paper's Table III, the docs' example scene, the
# outputs, --json, an array's own profile, the PDF report as a reader reads it (pdftotext,
# pdftoppm), and every bad input: exit 2, one line naming the file and the field, nothing written.
set -u
GLARECAM=$1
SOURCE_DIR=$2
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
source "$(dirname "$0")/cli_test_lib.sh"

SCENE="$SOURCE_DIR/docs/examples/hazard-scene.json"
check "profile from Table III" 0 "$GLARECAM" datasheet "$SOURCE_DIR/tests/data/standard-module-table3.csv" \
  --out "$WORK/ds" --module "Standard module" --date 2026-11-26
TABLE_PROFILE="$WORK/ds/glare-profile.json"
# Table III has no contours: the profile made from it has no ladder, which the default sun
# (clear-sky) needs. A ladder of the rows' own lobe, referred to 100 klx, stands in for one.
python3 "$(dirname "$0")/ladder_profile.py" "$TABLE_PROFILE" "$WORK/ladder-profile.json"
PROFILE="$WORK/ladder-profile.json"

check "help" 0 "$GLARECAM" hazard --help
expect "help types --models" grep -qE -- "--models MODEL,\.\.\." "$WORK/out"
expect "help types --profile" grep -qE -- "--profile FILE" "$WORK/out"
expect "help explains --sun" grep -q -- "--sun" "$WORK/out"
expect "help says circle is this module's" grep -q "not SGHAT's default" "$WORK/out"
expect "help types --report" grep -qE -- "--report FILE.pdf" "$WORK/out"

expect "help names geographic scenes" grep -q "GeoJSON (.geojson" "$WORK/out"

# A geographic scene: the v2 example drawn on a map gives the v2 example's table; a swapped
# lon/lat exits 2 with one line naming the feature.
check "v2 example" 0 "$GLARECAM" hazard "$SOURCE_DIR/docs/examples/hazard-scene-v2.json" \
  --profile "$PROFILE" --year 2027 --step-s 600 --out "$WORK/enu" --no-progress --sun reference
grep -E "ellipse|circle" "$WORK/out" >"$WORK/enu-table.txt"
check "geojson example" 0 "$GLARECAM" hazard "$SOURCE_DIR/docs/examples/hazard-scene.geojson" \
  --profile "$PROFILE" --year 2027 --step-s 600 --out "$WORK/geo" --no-progress --sun reference
grep -E "ellipse|circle" "$WORK/out" >"$WORK/geo-table.txt"
expect "geojson: the v2 example's table" cmp -s "$WORK/enu-table.txt" "$WORK/geo-table.txt"
python3 -c 'import json,sys
d=json.load(open(sys.argv[1])); c=d["features"][1]["geometry"]["coordinates"]; c[0],c[1]=c[1],c[0]
json.dump(d,open(sys.argv[2],"w"))' "$SOURCE_DIR/docs/examples/hazard-scene.geojson" "$WORK/swapped.geojson"
check "geojson: lon/lat swapped" 2 "$GLARECAM" hazard "$WORK/swapped.geojson" --profile "$PROFILE" \
  --year 2027 --out "$WORK/swapped" --no-progress
expect "swapped: one line naming the feature" one_line_naming 'swapped.geojson: features[1] ("window-3"): geometry vertex 0'
expect "swapped: says lon/lat swapped" grep -qF "lon/lat swapped?" "$WORK/err"

# 10-minute steps keep the year short; the physics is the unit tests'.
check "a year" 0 "$GLARECAM" hazard "$SCENE" --profile "$PROFILE" --year 2027 --step-s 600 \
  --out "$WORK/h" --no-progress
for f in hazard.json hazard.geojson events.csv glare-window-3.png glare-window-3.svg glare-window-west.png; do
  expect "wrote $f" test -s "$WORK/h/$f"
done
expect "table lists window-3 by ellipse" grep -qE "^window-3 +ellipse" "$WORK/out"
expect "table lists the circle" grep -qE "^window-west +circle" "$WORK/out"
expect "table gives verdicts" grep -q "significant" "$WORK/out"
expect "events.csv header" grep -q "^observer,array,model,start_local,end_local,duration_min" "$WORK/h/events.csv"
expect "hazard.json schema" grep -q '"schema": "glarecam.hazard/1"' "$WORK/h/hazard.json"
expect "hazard.geojson: a point per observer, a polygon per array, hazard.json's minutes" python3 -c 'import json,sys
g=json.load(open(sys.argv[1])); h=json.load(open(sys.argv[2]))
assert g["type"]=="FeatureCollection" and g["glarecam"]["schema"]=="glarecam.hazard-geojson/1"
p=[f for f in g["features"] if f["geometry"]["type"]=="Point"]
a=[f for f in g["features"] if f["geometry"]["type"]=="Polygon"]
assert len(p)==len(h["observers"]) and len(a)==len(h["inputs"]["arrays"])
for f,o in zip(p,h["observers"]):
  assert f["properties"]["ellipse_minutes_per_year"]==o["models"]["ellipse"]["minutes_per_year"]
assert h["inputs"]["max_distance_m"]==100 and h["inputs"]["frame"]==g["glarecam"]["frame"]' "$WORK/h/hazard.geojson" "$WORK/h/hazard.json"
expect "hazard.json names the profile's module" grep -q '"module": "Standard module"' "$WORK/h/hazard.json"
expect "summary gives the array's facing" grep -qxF "array roof-north: faces 0° (N), tilt 30.0°, 72.0 m²" "$WORK/out"
expect "a measured profile: no SIMULATED" bash -c "! grep -q SIMULATED '$WORK/out' '$WORK/err' '$WORK/h/events.csv'"
expect "a measured profile: events not simulated" awk -F, 'NR > 1 { n++; if ($10 != "false") bad = 1 } END { exit bad || !n }' "$WORK/h/events.csv"

# The PDF report, read as a user reads it: each receptor's row of the results table (its name,
# then the table's numbers and verdicts as stdout printed them), the sun used, civil clock times;
# every page renders. A v2 scene, so that a route's worst point and a house are in it too.
python3 -c 'import json,sys
d=json.load(open(sys.argv[1])); d["schema"]="glarecam.hazard-scene/2"
d["observers"][0]["facing_azimuth_deg"]=180
d["routes"]=[{"name":"road","points_m":[[-40,40,1.1],[40,40,1.1]],"spacing_m":20,"direction":"both"}]
d["obstructions"]=[{"name":"house","footprint_m":[[20,20],[30,20],[30,30],[20,30]],"height_m":8}]
json.dump(d,open(sys.argv[2],"w"))' "$SCENE" "$WORK/report-scene.json"
check "report" 0 "$GLARECAM" hazard "$WORK/report-scene.json" --profile "$PROFILE" --year 2027 \
  --step-s 600 --out "$WORK/r" --no-progress --daylight-saving eu --report "$WORK/r/report.pdf"
cp "$WORK/out" "$WORK/r-table.txt"
expect "report: a PDF" bash -c "head -c 5 '$WORK/r/report.pdf' | grep -q '%PDF-'"
pdftotext -layout "$WORK/r/report.pdf" "$WORK/r/report.txt"
tr -s ' ' <"$WORK/r/report.txt" >"$WORK/r/rows.txt"         # table rows, one line each
tr -s ' \n' '  ' <"$WORK/r/report.txt" >"$WORK/r/flat.txt"   # sentences across line breaks
expect "report: states the distance" grep -q "receptors within 100 m of an array" "$WORK/r/flat.txt"
# The stdout table's rows ("window-3  ellipse  8539  142.3  74  125  significant  not tolerable")
# of the pictured points: the observers, and the road's worst point (hazard.json names it).
WORST_ROAD=$(python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print([r["worst_point"] for r in d["receptors"] if r["name"]=="road"][0])' "$WORK/r/hazard.json")
rows=0
for point in window-3 window-west "$WORST_ROAD"; do
  expect "report names $point" grep -qF -- "$point" "$WORK/r/flat.txt"
  while read -r name model rest; do
    rows=$((rows + 1))
    # As the PDF's row has it: the model, then the same numbers and verdict words in order.
    expect "report: $name by $model: $rest" grep -qF -- "$model $rest" "$WORK/r/rows.txt"
  done < <(tr -s ' ' <"$WORK/r-table.txt" | grep -F -- "$point " | grep -E -- "^[^ ]+ (ellipse|circle) ")
done
expect "report: every pictured row checked" test "$rows" -eq 6
expect "report: receptor and minutes on one row" \
  grep -qE -- "window-3 \(observer\).* ellipse $(awk '$1 == "window-3" && $2 == "ellipse" { print $3 }' "$WORK/r-table.txt") " "$WORK/r/rows.txt"
expect "report: the route's worst point" grep -qF -- "road (route) $WORST_ROAD (worst)" "$WORK/r/rows.txt"
expect "report: verdict words" grep -qF "not tolerable" "$WORK/r/flat.txt"
expect "report: thresholds written out" grep -qF "> 30 min/day (exceeded)" "$WORK/r/flat.txt"
expect "report: the sun used" grep -qF "clear-sky: a clear sky's direct normal illuminance (IES RP-21" "$WORK/r/flat.txt"
expect "report: possible minutes" grep -qF "possible: the sun is taken to shine at every step it is up" "$WORK/r/flat.txt"
expect "report: the profile's route" grep -qF "route camera (luminance images)" "$WORK/r/flat.txt"
expect "report: civil clock times" grep -qE "[0-9]{2}:[0-9]{2}–[0-9]{2}:[0-9]{2} \(\+02:00\)" "$WORK/r/rows.txt"
expect "report: a circular-cone tool" grep -qF "What a circular-cone tool would have said" "$WORK/r/flat.txt"
expect "report: a measured profile is not SIMULATED" bash -c "! grep -q SIMULATED '$WORK/r/flat.txt'"
PAGES=$(pdfinfo "$WORK/r/report.pdf" | awk '/^Pages:/ { print $2 }')
# The scene, the results, the method, then two pages for each of the three pictured points.
expect "report: pages ($PAGES)" test "${PAGES:-0}" -ge 9
expect "report: page numbers" grep -qF "page $PAGES of $PAGES" "$WORK/r/flat.txt"
pdftoppm -r 50 -png "$WORK/r/report.pdf" "$WORK/r/page"
expect "report: every page renders" test "$(ls "$WORK/r"/page-*.png 2>/dev/null | wc -l)" -eq "${PAGES:-0}"
# A report that cannot be written is an error naming it (exit 1); bad input writes no report.
# A report that can never be written is refused before anything is computed (exit 2, nothing
# written); a missing directory on its way is made.
check "report: under a file" 2 "$GLARECAM" hazard "$SCENE" --profile "$PROFILE" --year 2027 \
  --step-s 3600 --out "$WORK/r2" --no-progress --report "$WORK/r/report.pdf/x.pdf"
expect "report: under a file names it" one_line_naming "$WORK/r/report.pdf/x.pdf"
expect "report: under a file writes nothing" test ! -e "$WORK/r2"
check "report: a directory" 2 "$GLARECAM" hazard "$SCENE" --profile "$PROFILE" --year 2027 \
  --step-s 3600 --out "$WORK/r2" --no-progress --report "$WORK/r"
expect "report: a directory is named" one_line_naming "is a directory"
check "report: a new directory" 0 "$GLARECAM" hazard "$SCENE" --profile "$PROFILE" --year 2027 \
  --step-s 3600 --out "$WORK/r4" --no-progress --report "$WORK/r4/new/sub/report.pdf"
expect "report: the new directory made" test -s "$WORK/r4/new/sub/report.pdf"
check "report: bad input" 2 "$GLARECAM" hazard "$SCENE" --profile "$PROFILE" --year 2027 \
  --step-s 7 --out "$WORK/r3" --no-progress --report "$WORK/r3.pdf"
expect "report: bad input writes none" test ! -e "$WORK/r3.pdf"

# A profile from simulated stacks: marked on stderr, in the table, in every event and hazard.json.
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); d["simulated"]=True; json.dump(d,open(sys.argv[2],"w"))' \
  "$PROFILE" "$WORK/sim-profile.json"
check "simulated profile" 0 "$GLARECAM" hazard "$SCENE" --profile "$WORK/sim-profile.json" --year 2027 \
  --step-s 600 --out "$WORK/sim" --no-progress
expect "simulated: warned on stderr" grep -qF "warning: SIMULATED profile of module \"Standard module\"" "$WORK/err"
expect "simulated: the table's first line" bash -c "head -1 '$WORK/out' | grep -qF 'SIMULATED profile of module'"
expect "simulated: every event" awk -F, 'NR > 1 { n++; if ($10 != "true") bad = 1 } END { exit bad || !n }' "$WORK/sim/events.csv"
expect "simulated: hazard.json's warnings" grep -qF '"SIMULATED profile of module' "$WORK/sim/hazard.json"
check "simulated report" 0 "$GLARECAM" hazard "$SCENE" --profile "$WORK/sim-profile.json" --year 2027 \
  --step-s 3600 --out "$WORK/sim-r" --no-progress --report "$WORK/sim-r/report.pdf"
expect "simulated: the report says so" bash -c "pdftotext '$WORK/sim-r/report.pdf' - | grep -qF 'SIMULATED: stacks of the simulated camera'"

# Observers that can never see an array's front: computed (0 minutes), warned naming both.
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); d["observers"].append({"name": "in-the-house", "position_m": [0, 2, 5]}); json.dump(d,open(sys.argv[2],"w"))' \
  "$SCENE" "$WORK/behind.json"
check "observer behind the array" 0 "$GLARECAM" hazard "$WORK/behind.json" --profile "$PROFILE" \
  --year 2027 --step-s 3600 --out "$WORK/behind" --no-progress
expect "observer behind: warned naming both" grep -qF \
  'warning: '"$WORK"'/behind.json: observer "in-the-house" (observers[2]) is behind or on the plane of array "roof-north" (arrays[0])' "$WORK/err"
expect "observer behind: in hazard.json" grep -qF 'observer \"in-the-house\" (observers[2]) is behind' "$WORK/behind/hazard.json"

check "json" 0 "$GLARECAM" hazard "$SCENE" --profile "$PROFILE" --year 2027 --step-s 3600 \
  --out "$WORK/j" --json --models cone:0.5 --criteria ch --no-progress
expect "--json prints hazard.json" grep -q '"schema": "glarecam.hazard/1"' "$WORK/out"
expect "--json has the cone" grep -q '"cone:0.5"' "$WORK/out"

# A year valid for the sun but unlikely meant: computed, and warned about on stderr.
check "two-digit year" 0 "$GLARECAM" hazard "$SCENE" --profile "$PROFILE" --year 27 --step-s 3600 \
  --out "$WORK/y" --no-progress
expect "two-digit year warned" grep -qF "warning: --year 27 is outside 1950" "$WORK/err"
expect "two-digit year: did you mean" grep -qF "did you mean 2027?" "$WORK/err"
check "a usual year" 0 "$GLARECAM" hazard "$SCENE" --profile "$PROFILE" --year 2027 --step-s 3600 \
  --out "$WORK/y2" --no-progress
expect "a usual year is not warned about" bash -c "! grep -q -- '--year' '$WORK/err'"

# An array's own profile, relative to the scene file.
mkdir -p "$WORK/own/profiles"
cp "$PROFILE" "$WORK/own/profiles/p.json"
sed 's|"vertices_m"|"profile": "profiles/p.json", "vertices_m"|' "$SCENE" >"$WORK/own/scene.json"
check "array's own profile" 0 "$GLARECAM" hazard "$WORK/own/scene.json" --year 2027 --step-s 3600 \
  --out "$WORK/own/out" --no-progress

# The sun's brightness: the clear sky by default, recorded; the reference sun; a weather file.
expect "clear-sky by default, recorded" grep -q '"kind": "clear-sky"' "$WORK/h/hazard.json"
expect "ocular minutes per class" grep -q '"ocular_minutes"' "$WORK/h/hazard.json"
expect "a monthly summary" grep -q '"minutes_per_month"' "$WORK/h/hazard.json"
expect "an ocular hazard plot" test -s "$WORK/h/ocular-glare-window-3.png"
expect "events give where the glare is seen" grep -q "glare_azimuth_deg,glare_elevation_deg,distance_m,sun_azimuth_deg" "$WORK/h/events.csv"
check "reference sun" 0 "$GLARECAM" hazard "$SCENE" --profile "$TABLE_PROFILE" --sun reference \
  --year 2027 --step-s 600 --out "$WORK/ref" --no-progress
expect "reference sun recorded" grep -q '"kind": "reference"' "$WORK/ref/hazard.json"
# No --sun and a profile without a ladder: the reference sun, warned naming the profile.
check "no ladder, no --sun" 0 "$GLARECAM" hazard "$SCENE" --profile "$TABLE_PROFILE" \
  --year 2027 --step-s 600 --out "$WORK/fallback" --no-progress
expect "no ladder: warned naming it" grep -qF "warning: $TABLE_PROFILE: the profile has no contour ladder" "$WORK/err"
expect "no ladder: the reference sun, recorded" grep -q '"kind": "reference"' "$WORK/fallback/hazard.json"
expect "no ladder: the same as --sun reference" cmp -s "$WORK/fallback/events.csv" "$WORK/ref/events.csv"
python3 - "$WORK/weather.epw" <<'PY'
import sys
lines = ["LOCATION,Zurich,ZH,CHE,test,066600,47.37,8.54,1.0,410.0",
         "DESIGN CONDITIONS,0", "TYPICAL/EXTREME PERIODS,0", "GROUND TEMPERATURES,0",
         "HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0", "COMMENTS 1,constant 60 klx", "COMMENTS 2,",
         "DATA PERIODS,1,1,Data,Sunday, 1/ 1,12/31"]
days = [31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31]
for month, count in enumerate(days, 1):
    for day in range(1, count + 1):
        for hour in range(1, 25):
            fields = [2027, month, day, hour, 60, "?9?9?9?9E0?9?9?9?9?9?9?9?9?9?9?9?9?9*9?9?9?9",
                      20, 10, 52, 101325, 9999, 9999, 9999, 9999, 9999, 9999, 999999, 60000,
                      999999, 9999, 180, 0, 0, 0, 9999, 99999, 9, 999999999, 999, 999, 999, 999,
                      999, 999, 99]
            lines.append(",".join(str(f) for f in fields))
open(sys.argv[1], "w").write("\n".join(lines) + "\n")
PY
check "weather file" 0 "$GLARECAM" hazard "$SCENE" --profile "$PROFILE" --sun weather "$WORK/weather.epw" \
  --year 2027 --step-s 3600 --out "$WORK/wx" --no-progress
expect "weather: expected minutes" grep -q '"minutes": "expected' "$WORK/wx/hazard.json"
expect "weather: the station" grep -q '"station": "Zurich"' "$WORK/wx/hazard.json"
check "sigma model" 0 "$GLARECAM" hazard "$SCENE" --profile "$PROFILE" --models ellipse,sigma:2 \
  --year 2027 --step-s 3600 --out "$WORK/sigma" --no-progress
expect "sigma model in the table" grep -qE "^window-3 +sigma:2" "$WORK/out"

# Scene version 2: a window facing its array, a road, a terrace and a house in the way.
python3 -c 'import json,sys
d=json.load(open(sys.argv[1])); d["schema"]="glarecam.hazard-scene/2"
d["observers"][0]["facing_azimuth_deg"]=180
d["routes"]=[{"name":"road","points_m":[[-40,40,1.1],[40,40,1.1]],"spacing_m":20,"direction":"both"}]
d["areas"]=[{"name":"terrace","vertices_m":[[-5,25,0],[5,25,0],[5,31,0],[-5,31,0]],"spacing_m":3}]
d["obstructions"]=[{"name":"house","footprint_m":[[20,20],[30,20],[30,30],[20,30]],"height_m":8}]
json.dump(d,open(sys.argv[2],"w"))' "$SCENE" "$WORK/v2.json"
check "scene v2" 0 "$GLARECAM" hazard "$WORK/v2.json" --profile "$PROFILE" --year 2027 --step-s 3600 \
  --out "$WORK/v2" --no-progress
expect "v2: the road's worst point" grep -qE "^road@[0-9]+m +ellipse" "$WORK/out"
expect "v2: only the road's worst point" test "$(grep -cE '^road@[0-9]+m +(ellipse|circle) ' "$WORK/out")" -eq 2
expect "v2: the road's points counted" grep -qE "^route road: 5 points, the worst road@[0-9]+m" "$WORK/out"
expect "v2: receptors with their worst point" grep -q '"worst_point"' "$WORK/v2/hazard.json"
expect "v2: a picture of the road's worst point only" bash -c "test \$(ls '$WORK/v2'/glare-road* | wc -l) -eq 2"

# Bad inputs: exit 2, one line naming the problem, no output directory.
bad() {  # bad NAME EXPECTED_TEXT SCENE_FILE [OPTIONS...] (--year 2027 --step-s 3600 unless given)
  local name=$1 text=$2 scene=$3
  shift 3
  local defaults=(--year 2027 --step-s 3600)
  [[ " $* " == *" --year "* || " $* " == *" --step-s "* ]] && defaults=()
  rm -rf "$WORK/bad"
  check "$name" 2 "$GLARECAM" hazard "$scene" "${defaults[@]}" --out "$WORK/bad" --no-progress "$@"
  expect "$name: one line naming it" one_line_naming "$text"
  expect "$name: nothing written" test ! -e "$WORK/bad"
}
edit() {  # edit NAME SED-EXPRESSION: a copy of the example scene, changed
  sed "$2" "$SCENE" >"$WORK/$1.json"
  echo "$WORK/$1.json"
}
bad "negative distance" "--max-distance -5 is not a positive distance in metres" "$SCENE" \
  --profile "$PROFILE" --max-distance -5
# A command with SCENE beside the subcommand merge: an option's error is named as such, not as an
# unknown command SCENE.
bad "distance not a number" "--max-distance = abc" "$SCENE" --profile "$PROFILE" --max-distance abc
bad "screening every pair" "a screening needs a finite distance" "$SCENE" --profile "$PROFILE" \
  --screen --max-distance inf
bad "shard without screening" "--shard: only with --screen" "$SCENE" --profile "$PROFILE" \
  --shard 0/2
bad "shard past N" "I counts from 0 and must be below N" "$SCENE" --profile "$PROFILE" --screen \
  --shard 2/2
bad "wrong schema" "schema" "$(edit schema 's/hazard-scene\/1/hazard-scene\/9/')" --profile "$PROFILE"
bad "latitude" "site.latitude_deg 95° is outside" "$(edit lat 's/"latitude_deg": 47.37/"latitude_deg": 95/')" --profile "$PROFILE"
bad "text coordinate" "arrays[0].vertices_m[1][0] must be a number, not" \
  "$(edit text 's/\[6, 0, 9\]/["6", 0, 9]/')" --profile "$PROFILE"
bad "two vertices" "has 2 vertices" \
  "$(edit two 's/\[\[-6, 0, 9\], \[6, 0, 9\], \[6, 5.2, 6\], \[-6, 5.2, 6\]\]/[[-6, 0, 9], [6, 0, 9]]/')" --profile "$PROFILE"
bad "self-intersecting" "crosses itself (edges 1–2 and 3–0 cross)" \
  "$(edit cross 's/\[6, 5.2, 6\], \[-6, 5.2, 6\]/[-6, 5.2, 6], [3, 5.2, 6]/')" --profile "$PROFILE"
# Vertex 2 moved 0.5 m along the roof's normal (0, 0.5, 0.866): named, not vertex 0.
bad "not planar" "is not planar (vertex 2 lies 0.500 m off the plane of the others)" \
  "$(edit planar 's/\[6, 5.2, 6\]/[6, 5.45, 6.433]/')" --profile "$PROFILE"
bad "unknown array key" 'arrays[0] has an unknown key "profil" (did you mean "profile"?)' \
  "$(edit profil 's/"vertices_m"/"profil": "p.json", "vertices_m"/')" --profile "$PROFILE"
bad "unknown observer key" 'observers[0] has an unknown key "hour" (did you mean "hours"?)' \
  "$(edit hour 's/"hours"/"hour"/')" --profile "$PROFILE"
bad "unknown site key" 'site has an unknown key "elevation" (did you mean "elevation_m"?)' \
  "$(edit elevation 's/"elevation_m"/"elevation"/')" --profile "$PROFILE"
bad "duplicate observer" "repeats the observer name" "$(edit dup 's/window-west/window-3/')" --profile "$PROFILE"
bad "no observers" "observers is empty" \
  "$(python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); d["observers"]=[]; print(json.dumps(d))' "$SCENE" >"$WORK/noobs.json"; echo "$WORK/noobs.json")" --profile "$PROFILE"
bad "no arrays" "arrays is empty" \
  "$(python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); d["arrays"]=[]; print(json.dumps(d))' "$SCENE" >"$WORK/noarr.json"; echo "$WORK/noarr.json")" --profile "$PROFILE"
bad "missing scene" "nothing.json" "$WORK/nothing.json" --profile "$PROFILE"
bad "no profile" "has no profile" "$SCENE"
bad "missing profile" "none.json" "$SCENE" --profile "$WORK/none.json"
bad "wrong-schema profile" "schema" "$SCENE" --profile "$SCENE"
bad "unknown model" 'unknown model "elipse" (did you mean ellipse?)' "$SCENE" --profile "$PROFILE" --models elipse
bad "bad cone" "cone:DEG" "$SCENE" --profile "$PROFILE" --models cone:0
bad "unknown criterion" 'unknown criterion "de"' "$SCENE" --profile "$PROFILE" --criteria de
bad "year out of range" "--year 7000" "$SCENE" --profile "$PROFILE" --year 7000 --step-s 3600
bad "step not dividing a day" "--step-s 7" "$SCENE" --profile "$PROFILE" --year 2027 --step-s 7
bad "no ladder for the clear sky" "has no contour ladder" "$SCENE" --profile "$TABLE_PROFILE" --sun clear-sky
bad "unknown sun" '--sun "cloudy"' "$SCENE" --profile "$PROFILE" --sun cloudy
bad "weather without a file" "--sun weather needs the weather file" "$SCENE" --profile "$PROFILE" --sun weather
bad "a short weather file" "freiburg-two-days.epw" "$SCENE" --profile "$PROFILE" \
  --sun weather "$SOURCE_DIR/tests/data/weather/freiburg-two-days.epw"
bad "bad sigma" "sigma:MRAD" "$SCENE" --profile "$PROFILE" --models sigma:-1
bad "v2 key in a v1 scene" 'routes is a key of glarecam.hazard-scene/2' \
  "$(python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); d["routes"]=[]; print(json.dumps(d))' "$SCENE" >"$WORK/v1routes.json"; echo "$WORK/v1routes.json")" --profile "$PROFILE"
bad "a bad obstruction" "obstructions[0]" \
  "$(python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); d["schema"]="glarecam.hazard-scene/2"; d["obstructions"]=[{"name":"w","footprint_m":[[0,0],[1,0],[1,1]],"height_m":-2}]; print(json.dumps(d))' "$SCENE" >"$WORK/badobs.json"; echo "$WORK/badobs.json")" --profile "$PROFILE"

finish
