#!/usr/bin/env bash
# Installs everything penumbra needs on Debian 12 (run as root). Every
# dependency is a Debian package: the toolchain, xsimd, oneTBB, OpenEXR, the
# OpenCL ICD loader with its C and C++ headers, PoCL (an OpenCL CPU driver, so
# the OpenCL backend runs on any machine), GoogleTest, Google Benchmark,
# nlohmann-json, zlib, libdeflate (inflates EXR ZIP chunks), OpenEXR's tools (exrheader: a test
# checks that other tools read our deep files); OpenCV only as a benchmark and test peer; matplotlib for
# the charts; clang with its compiler-rt (libFuzzer, ASan, UBSan) for CI's fuzz
# targets (.ci/fuzz.sh; gcc's own sanitizers serve the sanitizer job); pybind11, Python's headers and
# pytest for the Python module and its tests (python/, tests/python).
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
packages=(
  cmake ninja-build g++ pkg-config clang libclang-rt-14-dev
  libxsimd-dev libtbb-dev libopenexr-dev openexr zlib1g-dev libdeflate-dev nlohmann-json3-dev
  ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers pocl-opencl-icd clinfo
  libgtest-dev libgmock-dev libbenchmark-dev
  libopencv-dev libopencv-contrib-dev
  python3-matplotlib python3-numpy
  pybind11-dev python3-dev python3-pytest
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  apt-get update -q
  apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
