#!/usr/bin/env bash
# CI's sanitizer job (docs/ci.md): an AddressSanitizer + UBSan build (gcc) of
# the library, the CLI and the tests into ./build-asan; the whole test suite
# (OpenCL on PoCL included) and tests/sanitize/cli_bad_input.sh run on it. Every
# sanitizer report goes to a file under build-asan/sanitizer-logs; the job
# fails if a test fails or if any report is there. Driver leaks (PoCL, LLVM,
# the ICD loader) are suppressed by tests/sanitize/lsan.supp, each entry
# explained there; a second pass checks the OpenCL tests with precise stacks.
set -euo pipefail
cd "$(dirname "$0")/.."
build=build-asan
# -g1: line tables are all a sanitizer report needs; full -g (variable
# tracking of the large kernel entry points) made this build the longest step
# of CI. Two CPU ISAs, the scalar oracle and the widest this machine runs
# (avx512 where it has it, else avx2, else sse4.2): every test runs once per
# ISA, so all four made this stage most of CI's 30 minutes, and an ISA the
# machine cannot run would be compiled under ASan and never tested. The other
# ISAs compile the same descriptions with other lane counts; the main job
# tests their results on every kernel (docs/ci.md).
widest_isa() {
  local flags
  flags=$(grep -m1 '^flags' /proc/cpuinfo || true)
  if [[ $flags =~ avx512f && $flags =~ avx512cd && $flags =~ avx512bw && $flags =~ avx512dq && $flags =~ avx512vl ]]; then
    echo avx512
  elif [[ $flags =~ avx2 && $flags =~ fma ]]; then
    echo avx2
  else
    echo sse4_2
  fi
}
# No OpenCL seed (cmake/penumbra_cl_seed.cmake): it would run the driver under
# the sanitizers at build time, and this job tests the source builds.
isas="scalar;$(widest_isa)"
echo "sanitizer job: CPU ISAs $isas"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
  -DPENUMBRA_SANITIZE=address,undefined -DPENUMBRA_BENCH=OFF "-DPENUMBRA_CPU_ISAS=$isas" -DPENUMBRA_CL_SEED=OFF
cmake --build "$build" -j"$(nproc)"

logs="$PWD/$build/sanitizer-logs"
rm -rf "$logs" && mkdir -p "$logs"
supp="$PWD/tests/sanitize"
# log_path: ASan and LSan reports of every process, the CLI runs inside the
# tests included, land in files, so a report is counted even where a test
# tolerates the exit status. detect_leaks: on (LSan is part of ASan on x86-64
# Linux). gcc's UBSan ignores log_path and prints to stderr: abort_on_error
# turns its finding into SIGABRT, which no test mistakes for a refusal, and
# the tests' whole output (LastTest.log) is searched for its reports.
# use_sigaltstack=0: at a thread's exit gcc 12's ASan unmaps whatever
# alternate signal stack the thread has, assuming it is its own; a library
# that installs a malloc'd one in its threads (79040 bytes here, 64 KiB plus
# this CPU's MINSIGSTKSZ, the size LLVM's signal handlers allocate, in the
# processes that start PoCL) makes that unmap fail, and ASan aborts with
# "failed to deallocate ... unable to unmap" (exit 1, the report in log_path):
# every CLI test failed so on the Zen 5 VM, not on the Xeon before it. ASan
# then reports a stack overflow without its own signal stack.
export ASAN_OPTIONS="log_path=$logs/asan:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1:use_sigaltstack=0"
export LSAN_OPTIONS="suppressions=$supp/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:abort_on_error=1"
export PENUMBRA_CACHE_DIR="$PWD/$build/cache"

status=0
# The slow-labelled 16384^2 cases run in the main job; under ASan they take
# minutes and their tables (4-13 GB) plus shadow memory crowd a 24 GiB machine.
# The fidelity sweeps (MomentFidelity: every moment method on every case
# against the float64 method, 20-55 s each here, the time in the reference)
# run on the scalar oracle only: the same kernels meet ASan on avx512 and
# OpenCL in every other kernel test, and the main job runs the sweeps on all.
# (ctest names a parameterised test 'Suite.Name/param  # GetParam() = ...'.)
# The demo's quick run (every method on every scene, 174 s under ASan, the
# longest test here by three times) runs in the main job only: its kernels
# meet ASan in their own tests, and the demo's host code in the other Demo
# tests, which stay.
# --repeat until-pass:2: a test that fails is run once more (LSan's own
# tracer can crash at exit, below); a real failure fails twice.
# The install tests (label install) configure and build two consumer
# projects: the main job runs them, and under ASan they test the compiler.
# The probe (label probe, scripts/probe.py --quick: ~930 CLI runs) runs in
# the main job only: under ASan it was 184 s alone and 300 s beside the rest
# (a quarter of this suite's CPU), and what it feeds the CLI meets the
# sanitizers here through the readers' fuzzers (.ci/fuzz.sh) and
# tests/sanitize/cli_bad_input.sh below.
# The OpenCL cases of the kernel tests run in the second pass below, a
# chosen set of them (under ASan they were 43% of this suite's time: each
# process starts PoCL, whose code ASan does not see; our host code around it
# is the same few launch and buffer functions for every kernel), and so do
# the runtime's and the cache repair's tests: as processes of a tenth of a
# second each, LSan's tracer crashed at their exit, while PoCL's threads
# were still starting, in both tries of four of them (docs/ci.md).
ctest --test-dir "$build" --output-on-failure -j2 --timeout 1800 -LE 'slow|install|probe' \
  -E '(MomentFidelity|MomentAgreement)\..*/(sse4_2|avx2|avx512|opencl)( |$)|/opencl( |$)|^OpenClRuntime\.|^OpenClCacheRepair\.|^Demo\.QuickRunCoversEveryMethodOnEverySceneWithoutNaN$' \
  --repeat until-pass:2 || status=1
# Second pass: the OpenCL tests, with full unwinding through the driver
# (8x slower) and suppressions by function only (lsan_precise.supp): a leak
# of an OpenCL object of ours, which lsan.supp's by-library entries would
# hide, shows here. Our OpenCL objects are made in a few places (the runtime,
# the program cache, the launch and buffer code every kernel shares), so the
# pass runs the runtime's and the cache's tests and the ones that launch
# every kernel (every method, every lookup entry, the blur, the fields), not
# every OpenCL test. The cache is warm by now.
precise_tests='OpenClRuntime.*:OpenClCacheRepair.*:*UninitializedOutput.EveryMethodWritesEveryPixel/opencl'
precise_tests+=':*ReceiverLookup.EveryLookupShapedEntryAgreesWithTheScalarOracle/opencl'
precise_tests+=':*BilateralTest.OddSizesAndLaneEdgeWidths/opencl:*SdfTest.OddSizesMatchPixelByPixel/opencl'
ASAN_OPTIONS="$ASAN_OPTIONS:fast_unwind_on_malloc=0" \
  LSAN_OPTIONS="suppressions=$supp/lsan_precise.supp:print_suppressions=0" \
  "$build/tests/penumbra_tests" --gtest_filter="$precise_tests" --gtest_brief=1 || status=1
bash tests/sanitize/cli_bad_input.sh "$build/penumbra" || status=1

if grep -l 'runtime error:' "$build/Testing/Temporary/LastTest.log" >/dev/null 2>&1; then
  echo "sanitizer job: UBSan reports in the tests' output:"
  grep -B2 -A12 'runtime error:' "$build/Testing/Temporary/LastTest.log" | head -n 80
  status=1
fi
# LeakSanitizer's tracer (the thread that stops the world for the leak check
# at exit) sometimes crashes by itself while PoCL's threads exit ("Tracer
# caught signal 11 ... LeakSanitizer has encountered a fatal error", seen once
# in 400 processes). Such a log holds no finding: the process's test failed
# and was run again by ctest's --repeat, and that run's own log counts. Any
# log with a finding in it counts, whatever else it holds.
tracer_crash_only() {
  grep -q 'LeakSanitizer has encountered a fatal error' "$1" &&
    ! grep -q -E 'ERROR: (AddressSanitizer|LeakSanitizer)|SUMMARY: ' "$1"
}
reports=()
for r in "$logs"/*; do
  [[ -e $r ]] || continue
  if tracer_crash_only "$r"; then
    echo "sanitizer job: LeakSanitizer's tracer crashed in one process (no finding; its test was rerun): $r"
    head -n 3 "$r"
    continue
  fi
  reports+=("$r")
done
if ((${#reports[@]})); then
  echo "sanitizer job: ${#reports[@]} report(s) outside the suppressions:"
  for r in "${reports[@]}"; do echo "--- $r"; head -n 60 "$r"; done
  status=1
else
  echo "sanitizer job: no sanitizer report outside the suppressions"
fi
exit "$status"
