#!/usr/bin/env bash
# Benchmark (not a test): where bundle build + walk time goes against the rasterization floor, on
# Sponza (66k triangles) and the bunny (144k) at 64^2 (almost no fragments: the per-triangle part)
# and 512^2 to 2048^2. Each resolution's medians come from `bundlelab bench bundles`; a least-
# squares line through (fragments, ms) per scene and pass separates a per-bundle part (vertex
# work, triangle setup and binning of every triangle, the head reset) from a per-fragment part
# (rasterization + fragment shader for the floor; + head exchange and node store for the build;
# one list step for the walk).
#   experiments/bench/bundles-breakdown.sh [OUTDIR] [DIRECTIONS] [BUNDLELAB] [BACKEND: raster | compute]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
out=${1:-$root/out/bench/bundles-breakdown}
directions=${2:-8}
bl=${3:-$root/build/bundlelab}
backend=${4:-raster}
shared=$root/../shared/data
mkdir -p "$out"
res=(--resolution 64 --resolution 512 --resolution 1024 --resolution 2048 --backend "$backend")
uptime | tee "$out/load.txt"
"$bl" bench bundles "$root/data/external/sponza-point.toml" "${res[@]}" --directions "$directions" --json "$out/sponza.json" | tee "$out/sponza.txt"
"$bl" bench bundles "$shared/bunny/mcguire/bunny.obj" "${res[@]}" --directions "$directions" --json "$out/bunny.json" | tee "$out/bunny.txt"
uptime | tee -a "$out/load.txt"
/usr/bin/python3 "$(dirname "$0")/bundles-breakdown.py" "$out"/sponza.json "$out"/bunny.json | tee "$out/breakdown.md"
