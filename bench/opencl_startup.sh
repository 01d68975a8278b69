#!/usr/bin/env bash
# OpenCL start-up of one method (issue 10 item 11): the wall time of
#   penumbra shade --backend opencl --method vsm
# on a 320x320 shadow map and 320x240 receivers, with a fresh cache directory
# (cold: every program built from source by the driver) and again with the
# cache that run left (warm), median and minimum of RUNS runs each, in ms.
#
#   bench/opencl_startup.sh [RUNS] PENUMBRA_BINARY [PENUMBRA_BINARY...]
#
# Several binaries (say main's build and this one) are measured in one run,
# their runs interleaved so that the shared machine's load falls on all alike.
# A binary finds its own libpenumbra (RUNPATH), so builds do not mix.
set -euo pipefail

runs=5
if [[ "${1:-}" =~ ^[0-9]+$ ]]; then runs=$1; shift; fi
if [[ $# -eq 0 ]]; then
    echo "usage: $0 [RUNS] PENUMBRA_BINARY [PENUMBRA_BINARY...]" >&2
    exit 2
fi
unset POCL_CACHE_DIR  # the cache must live under PENUMBRA_CACHE_DIR, which each run chooses

work=$(mktemp -d /tmp/penumbra-startup.XXXXXX)
trap 'rm -rf "$work"' EXIT
"$1" render-scene contact --map-size 320 --view-size 320x240 --samples 1 \
    --shadow-map "$work/sm.exr" --receivers "$work/rx.exr" --truth "$work/gt.exr" >/dev/null

# Milliseconds of one shade run with the cache directory $2.
shade_ms() {
    local start end
    start=$(date +%s%N)
    PENUMBRA_CACHE_DIR="$2" "$1" shade --backend opencl --method vsm --shadow-map "$work/sm.exr" \
        --receivers "$work/rx.exr" --out "$work/out.exr" >/dev/null
    end=$(date +%s%N)
    echo $(((end - start) / 1000000))
}

median() { sort -n | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
# The fastest run: on a shared machine other jobs only add time, so it is the least disturbed.
minimum() { sort -n | head -1; }
stat_of() { tr ' ' '\n' <<<"$2" | grep . | "$1"; }

declare -A cold warm
for ((r = 0; r < runs; ++r)); do
    for ((b = 1; b <= $#; ++b)); do
        bin=${!b}
        cache="$work/cache-$b-$r"
        cold[$b]+="$(shade_ms "$bin" "$cache") "
        warm[$b]+="$(shade_ms "$bin" "$cache") "
        rm -rf "$cache"
    done
done

printf '%-50s %12s %12s %12s %12s\n' "binary ($runs runs)" "cold median" "warm median" "cold min" "warm min"
for ((b = 1; b <= $#; ++b)); do
    printf '%-50s %12s %12s %12s %12s\n' "${!b}" "$(stat_of median "${cold[$b]}")" "$(stat_of median "${warm[$b]}")" \
        "$(stat_of minimum "${cold[$b]}")" "$(stat_of minimum "${warm[$b]}")"
done
