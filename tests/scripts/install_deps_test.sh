#!/usr/bin/env bash
# scripts/install-deps.sh: `make demo` installs only what the programs need (no test, benchmark,
# packaging or sanitizer toolchain: on a fresh machine those were two thirds of its time), every
# demo package is also in the full list, and bad arguments are refused with exit 2.
set -euo pipefail
script="$(dirname "$0")/../../scripts/install-deps.sh"
fail() { echo "FAIL: $*" >&2; exit 1; }

demo=$(bash "$script" --demo --list)
all=$(bash "$script" --list)
[[ -n $demo ]] || fail "--demo --list printed nothing"
for pkg in $demo; do
  grep -qx -- "$pkg" <<<"$all" || fail "demo package $pkg is not in the full list"
done
for pkg in libgtest-dev libgmock-dev libbenchmark-dev chromium clang-19 libclang-rt-19-dev \
           lintian poppler-utils aravis-tools python3; do
  grep -qx -- "$pkg" <<<"$all" || fail "$pkg missing from the full list"
  if grep -qx -- "$pkg" <<<"$demo"; then fail "the demo installs $pkg, which only the tests need"; fi
done
# What the build of glarecam and glarecamd cannot do without.
for pkg in build-essential cmake ninja-build libopencv-dev libceres-dev libcairo2-dev \
           libsystemd-dev libcpp-httplib-dev libmodbus-dev; do
  grep -qx -- "$pkg" <<<"$demo" || fail "the demo does not install $pkg"
done
# The cluster profile: Slurm and munge alone, in neither of the others (make cluster-check only).
cluster=$(bash "$script" --cluster --list)
for pkg in slurm-wlm munge; do
  grep -qx -- "$pkg" <<<"$cluster" || fail "--cluster does not install $pkg"
  if grep -qx -- "$pkg" <<<"$all"; then fail "the full list installs $pkg, which only --cluster needs"; fi
done
[[ $(wc -l <<<"$cluster") -eq 2 ]] || fail "--cluster lists more than Slurm and munge: $cluster"
bash "$script" --help | grep -q -- "--cluster" || fail "--help does not describe --cluster"
# No package twice.
[[ -z $(sort <<<"$all" | uniq -d) ]] || fail "listed twice: $(sort <<<"$all" | uniq -d | tr '\n' ' ')"

set +e
out=$(bash "$script" --bogus --list 2>&1)
status=$?
set -e
[[ $status -eq 2 ]] || fail "--bogus exited $status, expected 2"
grep -q "unknown argument '--bogus'" <<<"$out" || fail "--bogus: $out"
bash "$script" --help | grep -q -- "--demo" || fail "--help does not describe --demo"
echo "install-deps: $(wc -l <<<"$demo") demo packages of $(wc -l <<<"$all")"
