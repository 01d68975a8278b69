#!/usr/bin/env bash
# The README's first command: install, build, and run the main job.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
./build/penumbra info
./build/penumbra example --out out/example
./build/penumbra shade --method vssm --shadow-map out/example/shadow_map.exr \
  --receivers out/example/receivers.exr --out out/example/vssm.exr --light-size 0.05
./build/penumbra shade --method vsm --radius 4 --shadow-map out/example/shadow_map.exr \
  --receivers out/example/receivers.exr --out out/example/vsm.exr
echo "wrote out/example/vsm.exr and out/example/vssm.exr (channel Y: visibility)"
