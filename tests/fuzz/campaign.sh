#!/usr/bin/env bash
# A longer fuzzing campaign than CI's (docs/ci.md, "Fuzzing"): each target in
# turn for SECONDS, in libFuzzer's fork mode so that one finding does not end
# the campaign (every crash, leak, timeout and out-of-memory input is kept in
# OUT_DIR/artifacts), from the seed corpus plus what earlier runs found
# (OUT_DIR/corpus/TARGET). Logs in OUT_DIR/TARGET.log; the last status line of
# each gives the executions, coverage (cov: edges, ft: features) and findings.
#
#   tests/fuzz/campaign.sh BUILD_DIR SECONDS OUT_DIR [TARGET...]
set -euo pipefail
build=${1:?usage: campaign.sh BUILD_DIR SECONDS OUT_DIR [TARGET...]}
seconds=${2:?usage: campaign.sh BUILD_DIR SECONDS OUT_DIR [TARGET...]}
out=${3:?usage: campaign.sh BUILD_DIR SECONDS OUT_DIR [TARGET...]}
shift 3
targets=("$@")
((${#targets[@]})) || targets=(exr_reader_fuzz scene_json_fuzz sdf_grid_fuzz)
declare -A seeds=([exr_reader_fuzz]=exr [scene_json_fuzz]=scene [sdf_grid_fuzz]=grid)
[[ -d $out/seeds ]] || bash "$(dirname "$0")/make_corpus.sh" "$build" "$out/seeds"
mkdir -p "$out/artifacts"
for target in "${targets[@]}"; do
  mkdir -p "$out/corpus/$target"
  "$build/tests/fuzz/$target" -fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1 \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 \
    -artifact_prefix="$out/artifacts/$target-" "$out/corpus/$target" "$out/seeds/${seeds[$target]}" \
    >"$out/$target.log" 2>&1 || true
  echo "$target: $(grep -E '^#[0-9]+: cov:' "$out/$target.log" | tail -n 1)"
done
