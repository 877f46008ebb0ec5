#!/usr/bin/env bash
# Installs the Debian 12 packages glarecam needs, and only the missing ones (idempotent:
# re-running refreshes nothing and installs nothing when all are present).
#
#   scripts/install-deps.sh          everything: build, test, benchmark, package, fuzz (make deps)
#   scripts/install-deps.sh --demo   what `make demo` needs: build glarecam and glarecamd (every
#                                    hardware backend included) and run scripts/demo.sh
#   scripts/install-deps.sh --cluster  only what `make cluster-check` adds: Slurm and munge
#                                    (scripts/cluster-check; in neither of the others)
#   --list                           print the packages, one a line, and install nothing
set -euo pipefail

usage() {
  echo "usage: scripts/install-deps.sh [--demo | --cluster] [--list]" >&2
  exit 2
}

profile=all
list=false
for arg in "$@"; do
  case "$arg" in
    --demo) profile=demo ;;
    --cluster) profile=cluster ;;
    --list) list=true ;;
    -h | --help)
      sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'
      exit 0
      ;;
    *)
      echo "install-deps: unknown argument '$arg'" >&2
      usage
      ;;
  esac
done

# What the programs are built from and run with: `make demo` installs only these.
DEMO_PACKAGES=(
  # toolchain
  build-essential cmake ninja-build pkg-config ca-certificates
  # core: images, data formats, logging, CLI
  libpng-dev libdeflate-dev libtiff-dev libopenexr-dev nlohmann-json3-dev libtomlplusplus-dev
  libspdlog-dev libfmt-dev libcli11-dev
  # vision and maths (libopencv-dev carries OpenCV's CMake package config)
  libopencv-dev libeigen3-dev libceres-dev
  # the glare hazard's polygon clipping (obstructions, fields of view)
  libpolyclipping-dev
  # screening a district: Boost.Geometry's R-tree (header-only)
  libboost-dev
  # geographic scenes: PROJ (geodetic to local east-north-up; proj-bin's cct checks it in the
  # tests) and pugixml (KML)
  libproj-dev proj-bin libpugixml-dev
  # pictures and data sheets
  libcairo2-dev fonts-dejavu-core
  # rig hardware: cameras, GPIO, I2C, systemd (the backends are built when their package is
  # found: a demo build without them would stay without them, CMake keeps the first answer)
  libaravis-dev libusb-1.0-0-dev libcamera-dev libgpiod-dev libi2c-dev libsystemd-dev
  # the illuminance instrument (Modbus RTU/TCP) and its simulator
  libmodbus-dev
  # glarecamd's status page
  libcpp-httplib-dev
)

# What only the tests, the benchmark, the package and the fuzzing need.
DEVELOPER_PACKAGES=(
  git clang-format
  # scripts/check-layering, doc-examples, uncertainty-coverage
  python3
  # the fake GenICam camera (arv-fake-gv-camera-0.8) and arv-tool for the Aravis tests
  aravis-tools aravis-tools-cli
  # the benchmark's peer of the sun position
  libnova-dev
  # make package: CPack DEB (dpkg-shlibdeps), lintian
  dpkg-dev lintian
  # systemd-analyze (the units' tests)
  systemd
  # tests and benchmarks (pdftotext: the data sheet's rendering test reads the PDF's words)
  libgtest-dev libgmock-dev libbenchmark-dev poppler-utils
  # the status page in a browser (glarecamd_tests: headless Chromium takes a screenshot)
  chromium
  # the sanitizer build and its fuzz targets (libFuzzer: libclang-rt-19-dev)
  clang-19 libclang-rt-19-dev
)

# A one-node Slurm for `make cluster-check` (scripts/cluster-check, docs/cluster.md): slurmctld,
# slurmd and the client commands, and munge for their authentication. Only on request.
CLUSTER_PACKAGES=(slurm-wlm munge)

PACKAGES=("${DEMO_PACKAGES[@]}")
if [[ $profile == all ]]; then
  PACKAGES+=("${DEVELOPER_PACKAGES[@]}")
elif [[ $profile == cluster ]]; then
  PACKAGES=("${CLUSTER_PACKAGES[@]}")
fi

if $list; then
  printf '%s\n' "${PACKAGES[@]}"
  exit 0
fi

if [[ $(id -u) -ne 0 ]]; then
  SUDO=sudo
else
  SUDO=
fi

missing=()
for pkg in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$pkg")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present ($profile)"
  exit 0
fi

echo "install-deps: installing ${#missing[@]} packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update
$SUDO apt-get install -y --no-install-recommends "${missing[@]}"
