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
echo "alpha_deg,limit_cd_m2,lmax_cd_m2,true_lmax_cd_m2,glare,valid_fraction,stack" >"$summary.tmp"
table=$(printf "%-7s %-12s %-14s %-14s %-6s %s" "alpha" "limit" "Lmax" "true Lmax" "glare" "picture")
for i in "${!ALPHAS[@]}"; do
  alpha=${ALPHAS[$i]}
  stack="$OUT/stacks/alpha-$(printf %02d "$alpha")"
  echo "demo: [$((i + 1))/${#ALPHAS[@]}] alpha $alpha°: capturing (simulated rig) and processing" >&2
  "$BIN/glarecam" simulate --out "$stack" --alpha "$alpha" --seed "$((i + 1))" >/dev/null
  "$BIN/glarecam" process --no-progress "$stack" >/dev/null
  # result.json and truth.json are pretty-printed one key per line: pick the values out.
  value() { grep -m1 "\"$2\"" "$1" | sed 's/.*: *//; s/,$//'; }
  result="$stack/result/result.json"
  limit=$(value "$result" limit_cd_m2)
  lmax=$(value "$result" max_cd_m2)
  truth=$(value "$stack/truth.json" luminance_max_cd_m2)
  glare=$(value "$result" glare)
  valid=$(value "$result" valid_fraction)
  echo "$alpha,$limit,$lmax,$truth,$glare,$valid,$stack" >>"$summary.tmp"
  table+=$'\n'$(printf "%-7s %-12.0f %-14.0f %-14.0f %-6s %s" "$alpha" "$limit" "$lmax" "$truth" "$glare" \
    "$stack/result/luminance.png")
done
mv "$summary.tmp" "$summary"
echo "$table"
echo "demo: wrote $summary and ${#ALPHAS[@]} processed stacks under $OUT/stacks/" >&2
