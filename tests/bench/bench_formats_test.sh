#!/usr/bin/env bash
# glarecam-bench takes Google Benchmark's flags as any benchmark binary does: the report on stdout
# in the format --benchmark_format names (one JSON document, one CSV table, or the console's),
# --benchmark_out writing a file too, and glarecam's ratio lines under the console table or on
# stderr beside JSON and CSV. Two cheap benchmarks (a year of sun positions, and of one window's
# glare) give one ratio. Times are never checked, only formats.
set -u
BENCH=$1
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
source "$(dirname "$0")/../apps/cli_test_lib.sh"

FILTER=(--benchmark_filter='^(sun/year_spa|hazard/year)(/|$)' --benchmark_min_time=0.01)
RATIO='ratio hazard/year ÷ sun/year_spa = '

json_names() {  # json_names FILE: the benchmarks' names in a JSON report, one a line
  python3 -c 'import json, sys; print("\n".join(b["name"] for b in json.load(open(sys.argv[1]))["benchmarks"]))' "$1"
}

check "json" 0 "$BENCH" "${FILTER[@]}" --benchmark_format=json
expect "json: stdout is one JSON document with both" \
  bash -c "[[ \$(python3 -c 'import json, sys; print(len(json.load(open(sys.argv[1]))[\"benchmarks\"]))' '$WORK/out') == 2 ]]"
expect "json: the names as Google Benchmark gives them" grep -q "^sun/year_spa" <(json_names "$WORK/out")
expect "json: the ratio on stderr" grep -qF "$RATIO" "$WORK/err"
expect "json: no ratio on stdout" bash -c "! grep -q '^ratio' '$WORK/out'"

check "csv" 0 "$BENCH" "${FILTER[@]}" --benchmark_format=csv
expect "csv: a header" grep -q '^name,iterations,real_time,cpu_time,time_unit' "$WORK/out"
expect "csv: a row each" bash -c "[[ \$(grep -c '^\"\\(sun/year_spa\\|hazard/year\\)' '$WORK/out') -eq 2 ]]"
expect "csv: the ratio on stderr" grep -qF "$RATIO" "$WORK/err"
expect "csv: no ratio on stdout" bash -c "! grep -q '^ratio' '$WORK/out'"

check "console with a JSON file" 0 "$BENCH" "${FILTER[@]}" --benchmark_out="$WORK/bench.json" \
  --benchmark_out_format=json
expect "console: a table" grep -qE '^sun/year_spa +[0-9.]+ ms' "$WORK/out"
expect "console: the ratio under it" grep -qF "$RATIO" "$WORK/out"
expect "--benchmark_out: the JSON file" grep -q "^hazard/year" <(json_names "$WORK/bench.json")

# Google Benchmark's CSV reporter aborts when benchmarks have different counters (these two do):
# glarecam-bench hands it every run at once, so its header names every counter.
check "a CSV file beside JSON" 0 "$BENCH" "${FILTER[@]}" --benchmark_format=json \
  --benchmark_out="$WORK/bench.csv" --benchmark_out_format=csv
expect "CSV file: a row each" bash -c "[[ \$(grep -c '^\"\\(sun/year_spa\\|hazard/year\\)' '$WORK/bench.csv') -eq 2 ]]"
expect "CSV file: every counter in its header" grep -q '^name,.*"steps"' "$WORK/bench.csv"

check "an unknown flag is a usage error" 2 "$BENCH" --benchmark_no_such_flag
check "an unknown format is a usage error" 2 "$BENCH" --benchmark_format=xml
finish
