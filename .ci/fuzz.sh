#!/usr/bin/env bash
# CI's fuzz runs (docs/ci.md): the libFuzzer targets of tests/fuzz built with
# clang (-fsanitize=fuzzer,address,undefined) into ./build-fuzz, a seed corpus
# made by tests/fuzz/make_corpus.sh, then each target for FUZZ_SECONDS
# (default 12). A crash, a sanitizer report, a leak, an input slower than 10 s
# or one allocating over 1 GiB fails the run; the input is kept in
# build-fuzz/artifacts for the report.
set -euo pipefail
cd "$(dirname "$0")/.."
build=build-fuzz
seconds=${FUZZ_SECONDS:-12}
# The readers need no OpenCL, no SIMD kernels (scalar only: the three SIMD
# kernel objects were most of this build), no tests or benchmarks.
# -g1: line tables are all a crash report's stack needs; -O1: a shorter build,
# and the fixed number of runs below took about as long (as in the sanitizer job).
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DPENUMBRA_FUZZ=ON \
  -DPENUMBRA_OPENCL=OFF -DPENUMBRA_TESTS=OFF -DPENUMBRA_BENCH=OFF -DPENUMBRA_CPU_ISAS=scalar
# The fuzzers and the seed writers only. The grid seeds are `penumbra sdf-bake`
# output: the main job's Release CLI writes them (the same writer, and the
# CLI's sources were a third of this build); alone, this job builds its own.
targets=(exr_reader_fuzz deep_exr_reader_fuzz scene_json_fuzz sdf_grid_fuzz ambient_json_fuzz
  exr_seeds deep_exr_seeds scene_seeds)
cli=build/penumbra
[[ -x $cli ]] || { targets+=(penumbra); cli=$build/penumbra; }
cmake --build "$build" -j"$(nproc)" --target "${targets[@]}"
echo "fuzz job: built at $SECONDS s"

rm -rf "$build/corpus" "$build/artifacts"
bash tests/fuzz/make_corpus.sh "$build" "$build/corpus/seeds" "$cli"
echo "fuzz job: corpus made at $SECONDS s"
rm -rf "$build/logs"
mkdir -p "$build/artifacts" "$build/logs"
# A fixed seed and a fixed number of runs per target (about FUZZ_SECONDS on an
# idle 2-core machine: EXR ~1,500 runs/s, deep EXR ~700, scene JSON ~9,000, grids ~4,500,
# ambient JSON ~9,000), so
# that CI's verdict does not depend on the machine's speed: the same inputs are
# tried every time; twice FUZZ_SECONDS caps a slow machine. Longer campaigns:
# tests/fuzz/campaign.sh.
# fuzz_target SEEDS FUZZER RATE: one target's runs, its output in logs/, its
# exit status in logs/FUZZER.status.
fuzz_target() {
  local seeds=$1 fuzzer=$2 rate=$3
  mkdir -p "$build/corpus/$seeds"
  local code=0
  "$build/tests/fuzz/$fuzzer" -seed=1 -runs=$((rate * seconds)) -max_total_time=$((2 * seconds)) -timeout=10 -rss_limit_mb=2048 \
    -malloc_limit_mb=1024 -print_final_stats=1 -artifact_prefix="$build/artifacts/$fuzzer-" \
    "$build/corpus/$seeds" "$build/corpus/seeds/$seeds" >"$build/logs/$fuzzer.log" 2>&1 || code=$?
  echo "$code" >"$build/logs/$fuzzer.status"
}
# Two targets at a time, one a core: each is a single process, and run one
# after another they left the second core idle for the stage's last minute.
fuzzers=()
for target in exr:exr_reader_fuzz:1500 deep:deep_exr_reader_fuzz:700 scene:scene_json_fuzz:9000 grid:sdf_grid_fuzz:4500 ambient:ambient_json_fuzz:9000; do
  IFS=: read -r seeds fuzzer rate <<<"$target"
  while (($(jobs -rp | wc -l) >= 2)); do wait -n || true; done
  fuzz_target "$seeds" "$fuzzer" "$rate" &
  fuzzers+=("$fuzzer:$rate")
done
wait
status=0
for entry in "${fuzzers[@]}"; do
  IFS=: read -r fuzzer rate <<<"$entry"
  echo "--- $fuzzer, $((rate * seconds)) runs, seed 1"
  tail -n 40 "$build/logs/$fuzzer.log"
  code=$(cat "$build/logs/$fuzzer.status" 2>/dev/null || echo missing)
  [[ $code == 0 ]] || { echo "$fuzzer: exit status $code"; status=1; }
done
exit "$status"
