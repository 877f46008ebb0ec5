#!/usr/bin/env bash
# scripts/check-layering: passes on the tree as it is, and fails, naming the file and line, on each
# kind of violation planted in a copy of it: an upward include (render's headers from below render,
# anything above core from render), a vendor header outside its backend, Cairo outside render/,
# and a library linking a library above it.
set -uo pipefail
ROOT=${1:?usage: check_layering_test.sh REPOSITORY_ROOT}
CHECK="$ROOT/scripts/check-layering"
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

out=$("$CHECK" "$ROOT" 2>&1) || fail "the tree itself: $out"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
copy() {
  rm -rf "$work/tree" && mkdir -p "$work/tree"
  for d in core calibration render pipeline capture sun rig daemon hazard apps tests bench scripts; do
    [[ -d $ROOT/$d ]] && cp -r "$ROOT/$d" "$work/tree/"
  done
  rm -rf "$work/tree/tests/data"
}

# plant FILE LINE EXPECTED: appends LINE to FILE in a fresh copy; the check must fail with
# EXPECTED (a fixed string) in its output.
plant() {
  local file=$1 line=$2 expected=$3
  copy
  mkdir -p "$(dirname "$work/tree/$file")"
  echo "$line" >> "$work/tree/$file"
  local status=0
  out=$("$CHECK" "$work/tree" 2>&1) || status=$?
  [[ $status -eq 1 ]] || fail "$file + '$line': exit $status, want 1"
  grep -qF -- "$expected" <<<"$out" || fail "$file + '$line': want '$expected' in: $out"
}

plant rig/rig_config.h '#include "daemon/capture_daemon.h"' \
  'rig/rig_config.h:'
plant rig/rig_config.h '#include "daemon/capture_daemon.h"' \
  'rig/ may include only core, rig, sun'
plant core/image.h '#include "calibration/hdr_merge.h"' 'core/ may include only core'
plant sun/solar_position.cpp '#include "capture/camera.h"' 'sun/ may include only core, sun'
plant core/image.h '#include "render/canvas.h"' 'core/ may include only core'
plant calibration/hdr_merge.cpp '#include "render/text.h"' \
  'calibration/ may include only calibration, core'
plant render/text.cpp '#include "pipeline/result.h"' 'render/ may include only core, render'
plant pipeline/datasheet.cpp '#include <cairo.h>' 'Cairo only in render/'
plant hazard/hazard_chart.cpp '#include <cairo-svg.h>' 'Cairo only in render/'
plant tests/pipeline/datasheet_test.cpp '#include <cairo.h>' 'Cairo only in render/'
plant daemon/capture_daemon.cpp '#include <arv.h>' 'Aravis only in capture/aravis/'
plant capture/camera_registry.cpp '#include <gpiod.h>' 'libgpiod only in'
plant daemon/hardware/illuminance_session.cpp '#include <modbus/modbus.h>' 'libmodbus only in'
plant pipeline/process_stack.cpp '#include <systemd/sd-daemon.h>' 'libsystemd only in'
plant tests/core/new_test.cpp '#include "support/sim_support.h"' 'which needs capture'
plant rig/CMakeLists.txt 'target_link_libraries(glarecam_rig PUBLIC glarecam_daemon)' \
  'glarecam_rig links glarecam_daemon'
plant render/CMakeLists.txt 'target_link_libraries(glarecam_render PUBLIC glarecam_pipeline)' \
  'glarecam_render links glarecam_pipeline'

# Allowed: a backend's own vendor header, Cairo in render/, an include down the layers (render's
# headers from pipeline and hazard).
copy
echo '#include <arv.h>' >> "$work/tree/capture/aravis/aravis_backend.cpp"
echo '#include <cairo.h>' >> "$work/tree/render/text.cpp"
echo '#include "sun/solar_position.h"' >> "$work/tree/rig/rig_config.cpp"
echo '#include "render/plot_axes.h"' >> "$work/tree/pipeline/sweep.cpp"
echo '#include "render/canvas.h"' >> "$work/tree/hazard/scene.cpp"
out=$("$CHECK" "$work/tree" 2>&1) || fail "allowed includes refused: $out"

# Usage
"$CHECK" a b >/dev/null 2>&1; [[ $? -eq 2 ]] || fail "two arguments: want exit 2"
"$CHECK" /nonexistent >/dev/null 2>&1; [[ $? -eq 2 ]] || fail "a missing root: want exit 2"

if [[ $failures -gt 0 ]]; then
  echo "check_layering_test: $failures failures" >&2
  exit 1
fi
echo "check_layering_test: all checks passed"
