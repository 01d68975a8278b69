#!/usr/bin/env bash
# A longer fuzzing campaign than CI's (docs/ci.md, "Fuzzing"): each target in
# turn for SECONDS, from the seed corpus plus what earlier runs found
# (OUT_DIR/corpus/TARGET, kept between campaigns). A finding ends that target's
# run (its input is kept in OUT_DIR/artifacts) and the campaign goes on with the
# next target. Logs in OUT_DIR/TARGET.log; printed per target: executions, and
# the coverage reached (cov: edges, ft: features, as libFuzzer counts them).
#
#   tests/fuzz/campaign.sh BUILD_DIR SECONDS OUT_DIR [TARGET...]
#   MALLOC_LIMIT_MB (default 1024): the largest single allocation allowed
set -euo pipefail
usage="usage: campaign.sh BUILD_DIR SECONDS OUT_DIR [TARGET...]"
build=${1:?$usage} seconds=${2:?$usage} out=${3:?$usage}
shift 3
targets=("$@")
((${#targets[@]})) || targets=(exr_reader_fuzz deep_exr_reader_fuzz scene_json_fuzz sdf_grid_fuzz)
declare -A seeds=([exr_reader_fuzz]=exr [deep_exr_reader_fuzz]=deep [scene_json_fuzz]=scene [sdf_grid_fuzz]=grid)
[[ -d $out/seeds ]] || bash "$(dirname "$0")/make_corpus.sh" "$build" "$out/seeds"
mkdir -p "$out/artifacts"
for target in "${targets[@]}"; do
  mkdir -p "$out/corpus/$target"
  rc=0
  "$build/tests/fuzz/$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
    -malloc_limit_mb="${MALLOC_LIMIT_MB:-1024}" -print_final_stats=1 \
    -artifact_prefix="$out/artifacts/$target-" "$out/corpus/$target" "$out/seeds/${seeds[$target]}" \
    >"$out/$target.log" 2>&1 || rc=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$out/$target.log")
  coverage=$(grep -oE 'cov: [0-9]+ ft: [0-9]+' "$out/$target.log" | tail -n 1)
  echo "$target: exit $rc, ${runs:-?} executions (at most $seconds s), $coverage"
done
