#!/usr/bin/env bash
# scripts/soak's checks fail when they should: against tests/scripts/fake_glarecamd.py (as
# glarecamd in a bin directory of its own), a run that behaves passes, and a descriptor leak, a
# memory leak (512 KiB a stack: about 37 MiB between the medians of the second quarter and the last half, against the 16 MiB allowed) and a lost
# stack each fail, naming what they found. Bad usage exits 2.
set -euo pipefail
SOURCE=$(cd "$(dirname "$0")/../.." && pwd)
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
mkdir "$WORK/bin"
cp "$SOURCE/tests/scripts/fake_glarecamd.py" "$WORK/bin/glarecamd"
soak() { python3 "$SOURCE/scripts/soak" --stacks 200 --sample-s 0.05 --out "$WORK/out" "$WORK/bin"; }

expect() {  # expect FAULT STATUS TEXT
  local status=0
  FAKE_FAULT=$1 soak >"$WORK/log" 2>&1 || status=$?
  if [[ $status -ne $2 ]] || ! grep -q -- "$3" "$WORK/log"; then
    echo "FAKE_FAULT=$1: expected status $2 and '$3', got $status:"; cat "$WORK/log"; exit 1
  fi
}
expect none 0 "200 stacks in"
expect fds 1 "FAILED: open descriptors grew"
expect rss 1 "FAILED: resident memory grew"
expect lose 1 "FAILED: stacks lost: 200 written, 199 on disk, 0 deleted by retention"
test -s "$WORK/out/soak.csv" && test -s "$WORK/out/soak.svg"

status=0
python3 "$SOURCE/scripts/soak" --stacks 3 "$WORK/bin" >/dev/null 2>&1 || status=$?
[[ $status -eq 2 ]] || { echo "--stacks 3: expected status 2, got $status"; exit 1; }
status=0
python3 "$SOURCE/scripts/soak" "$WORK/nowhere" >/dev/null 2>&1 || status=$?
[[ $status -eq 2 ]] || { echo "no glarecamd: expected status 2, got $status"; exit 1; }
echo "soak_test: ok"
