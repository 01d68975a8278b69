#!/usr/bin/env bash
# The README's first command: install, build, and run the main job — every
# method on every reference scene against the ray-traced ground truth, with
# the chart of time against error (out/demo/chart.png) and the CSV behind it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
./build/penumbra info
./build/penumbra demo --out out/demo
