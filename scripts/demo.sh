#!/usr/bin/env bash
# make demo: a simulated rig sweeps the angle of incidence, captures a bracketed stack at each
# alpha, processes it, and writes a summary table beside the per-stack results.
# Usage: scripts/demo.sh BIN_DIR OUT_DIR
set -euo pipefail
BIN=${1:-build/bin}
OUT=${2:-demo-out}
ALPHAS=(5 10 20 30 40 50 60 70 80)  # the paper's Table III angles

mkdir -p "$OUT/stacks"
summary="$OUT/summary.csv"
echo "alpha_deg,limit_cd_m2,lmax_cd_m2,true_lmax_cd_m2,vertical_deg,horizontal_deg,true_vertical_deg,true_horizontal_deg,fwhm_vertical_deg,fwhm_horizontal_deg,glare,valid_fraction,stack" >"$summary.tmp"

# result.json and truth.json are pretty-printed with two spaces per level, one key per line:
# field FILE KEY [OBJECT [INDENT]] prints KEY's value at INDENT spaces (default 2) within the
# top-level OBJECT (or at the top level, without OBJECT); nothing when it is not there (e.g. an
# ellipse that is null).
field() {
  awk -v key="\"$2\":" -v object="${3:-}" -v indent="${4:-2}" '
    BEGIN { pad = sprintf("%" indent "s", ""); inside = (object == "") }
    !inside && $0 ~ "^  \"" object "\": " { inside = 1; next }
    inside && object != "" && $0 ~ /^  [^ ]/ { exit }  # the object ended
    inside && index($0, pad key) == 1 {
      sub(/^[^:]*: */, ""); sub(/,$/, ""); print; exit
    }' "$1"
}

table=$(printf "%-6s %-8s %-22s %-16s %-16s %-5s %s" "alpha" "limit" "Lmax (true) cd/m²" \
  "vertical° (true)" "horizontal° (true)" "glare" "picture")
for i in "${!ALPHAS[@]}"; do
  alpha=${ALPHAS[$i]}
  stack="$OUT/stacks/alpha-$(printf %02d "$alpha")"
  echo "demo: [$((i + 1))/${#ALPHAS[@]}] alpha $alpha°: capturing (simulated rig) and processing" >&2
  "$BIN/glarecam" simulate --out "$stack" --alpha "$alpha" --seed "$((i + 1))" >/dev/null
  "$BIN/glarecam" process --no-progress "$stack" >/dev/null
  result="$stack/result/result.json"
  truth="$stack/truth.json"
  limit=$(field "$result" limit_cd_m2 limit 4)
  lmax=$(field "$result" max_cd_m2 luminance 4)
  true_lmax=$(field "$truth" luminance_max_cd_m2)
  vertical=$(field "$result" vertical_deg limit 6)
  horizontal=$(field "$result" horizontal_deg limit 6)
  true_vertical=$(field "$truth" vertical limit_axes_deg 4)
  true_horizontal=$(field "$truth" horizontal limit_axes_deg 4)
  fwhm_vertical=$(field "$result" vertical_deg fwhm 6)
  fwhm_horizontal=$(field "$result" horizontal_deg fwhm 6)
  glare=$(field "$result" glare)
  valid=$(field "$result" valid_fraction luminance 4)
  echo "$alpha,$limit,$lmax,$true_lmax,${vertical:-},${horizontal:-},${true_vertical:-},${true_horizontal:-},${fwhm_vertical:-},${fwhm_horizontal:-},$glare,$valid,$stack" >>"$summary.tmp"
  axes() { [[ -n $1 ]] && printf "%.2f (%.2f)" "$1" "$2" || printf "-"; }
  table+=$'\n'$(printf "%-6s %-8.0f %-22s %-16s %-16s %-5s %s" "$alpha" "$limit" \
    "$(printf "%.3g (%.3g)" "$lmax" "$true_lmax")" "$(axes "$vertical" "$true_vertical")" \
    "$(axes "$horizontal" "$true_horizontal")" "$glare" "$stack/result/luminance.png")
done
mv "$summary.tmp" "$summary"
echo "$table"
echo "demo: wrote $summary and ${#ALPHAS[@]} processed stacks under $OUT/stacks/" >&2
