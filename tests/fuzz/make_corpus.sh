#!/usr/bin/env bash
# Generates the fuzzers' seed corpus (docs/ci.md, "Fuzzing"); nothing of it is
# committed. From a build with -DPENUMBRA_FUZZ=ON:
#
#   tests/fuzz/make_corpus.sh BUILD_DIR OUT_DIR [PENUMBRA_CLI]
#
# OUT_DIR/exr    exr_seeds: every compression, scanline and tiled, FLOAT/HALF/UINT
# OUT_DIR/deep   deep_exr_seeds: deep maps as penumbra writes them and as others might
# OUT_DIR/scene  scene_seeds: every built-in scene as JSON
# OUT_DIR/ambient  a rig and a volume list, as docs/ambient.md writes them
# OUT_DIR/grid   `penumbra sdf-bake` of each of those scenes, at the finest voxel
#                (from 32 down to 0.5, halving) whose grid stays under 64 KB, so
#                that mutations rather than copies of megabytes take the fuzzer's
#                time (coarse first: a too-fine bake of `large` takes a minute)
set -euo pipefail
build=${1:?usage: make_corpus.sh BUILD_DIR OUT_DIR}
out=${2:?usage: make_corpus.sh BUILD_DIR OUT_DIR}
cli=${3:-$build/penumbra} # the CLI that bakes the grid seeds: any build's
mkdir -p "$out/exr" "$out/deep" "$out/scene" "$out/grid" "$out/ambient"
"$build/tests/fuzz/exr_seeds" "$out/exr"
"$build/tests/fuzz/deep_exr_seeds" "$out/deep"
"$build/tests/fuzz/scene_seeds" "$out/scene"
cat >"$out/ambient/rig.json" <<'JSON'
{"lights": [
  {"direction": [0, 1, 0], "color": [1.0, 0.95, 0.9], "intensity": 1.0},
  {"direction": [0, -1, 0], "intensity": -0.3}
]}
JSON
cat >"$out/ambient/volumes.json" <<'JSON'
{"volumes": [
  {"shape": "box", "center": [0, 1, 0], "half_size": [3, 1.5, 2], "rotation_degrees": [0, 30, 0],
   "scale_bias": 1.05, "falloff_delay": 0.5},
  {"shape": "sphere", "center": [4, 0, 1], "radius": 2},
  {"shape": "box", "center": [0, 0, 0], "half_size": [1, 1, 1], "axes": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}
]}
JSON
for scene in "$out"/scene/*.json; do
  name=$(basename "$scene" .json)
  for voxel in 32 16 8 4 2 1 0.5; do
    "$cli" sdf-bake --scene "$scene" --out "$out/grid/try.pnsdf" --voxel "$voxel" >/dev/null
    (($(stat -c %s "$out/grid/try.pnsdf") < 65536)) || break
    mv "$out/grid/try.pnsdf" "$out/grid/$name.pnsdf"
  done
  rm -f "$out/grid/try.pnsdf"
done
echo "$(ls "$out/grid" | wc -l) grid seeds in $out/grid"
