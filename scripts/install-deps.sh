#!/usr/bin/env bash
# Installs every Debian 12 package glarecam needs to build, test, benchmark and run,
# for all parts of the project (hardware backends included). Idempotent: re-running
# only refreshes the package lists and installs what is missing.
set -euo pipefail

PACKAGES=(
  # toolchain
  build-essential cmake ninja-build pkg-config git ca-certificates clang-format
  # scripts/check-layering
  python3
  # core: images, data formats, logging, CLI
  libpng-dev libdeflate-dev libtiff-dev libopenexr-dev nlohmann-json3-dev libtomlplusplus-dev
  libspdlog-dev libfmt-dev libcli11-dev
  # vision and maths (libopencv-dev carries OpenCV's CMake package config)
  libopencv-dev libeigen3-dev libceres-dev
  # pictures and data sheets
  libcairo2-dev fonts-dejavu-core
  # rig hardware: cameras, GPIO, I2C, sun position, systemd
  libaravis-dev libusb-1.0-0-dev aravis-tools aravis-tools-cli libcamera-dev libgpiod-dev
  libi2c-dev libnova-dev libsystemd-dev
  # glarecamd's status page
  libcpp-httplib-dev
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
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${#missing[@]} packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update
$SUDO apt-get install -y --no-install-recommends "${missing[@]}"
