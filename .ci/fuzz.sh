#!/usr/bin/env bash
# CI's fuzz runs (docs/ci.md): the libFuzzer targets of tests/fuzz built with
# clang (-fsanitize=fuzzer,address,undefined) into ./build-fuzz, a seed corpus
# made by tests/fuzz/make_corpus.sh, then each target for FUZZ_SECONDS
# (default 45). A crash, a sanitizer report, a leak, an input slower than 10 s
# or one allocating over 1 GiB fails the run; the input is kept in
# build-fuzz/artifacts for the report.
set -euo pipefail
cd "$(dirname "$0")/.."
build=build-fuzz
seconds=${FUZZ_SECONDS:-45}
# The readers need no OpenCL, the fuzz build no tests or benchmarks.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DPENUMBRA_FUZZ=ON \
  -DPENUMBRA_OPENCL=OFF -DPENUMBRA_TESTS=OFF -DPENUMBRA_BENCH=OFF
cmake --build "$build" -j"$(nproc)"

rm -rf "$build/corpus" "$build/artifacts"
bash tests/fuzz/make_corpus.sh "$build" "$build/corpus/seeds"
mkdir -p "$build/artifacts"
status=0
for target in exr:exr_reader_fuzz scene:scene_json_fuzz grid:sdf_grid_fuzz; do
  seeds=${target%%:*} fuzzer=${target#*:}
  mkdir -p "$build/corpus/$seeds"
  echo "--- $fuzzer, $seconds s"
  "$build/tests/fuzz/$fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -malloc_limit_mb=1024 -print_final_stats=1 -artifact_prefix="$build/artifacts/$fuzzer-" \
    "$build/corpus/$seeds" "$build/corpus/seeds/$seeds" 2>&1 | tail -n 40 || status=1
done
exit "$status"
