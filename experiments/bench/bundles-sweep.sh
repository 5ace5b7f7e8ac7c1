#!/usr/bin/env bash
# Benchmark sweep (not a test): bundle build / traversal / floor across resolutions and triangle
# counts (Cornell box 32 -> dragon 43k -> Sponza 66k -> bunny 144k -> synthetic 1M).
#   experiments/bench/bundles-sweep.sh [OUTDIR] [DIRECTIONS]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
out=${1:-$root/out/bench/bundles}
directions=${2:-4}
bl=$root/build/bundlelab
shared=$root/../shared/data
mkdir -p "$out"
res=(--resolution 256 --resolution 512 --resolution 1024 --resolution 2048)
"$bl" bench bundles "$root/data/cornell-box/cornell.toml" "${res[@]}" --directions "$directions" --json "$out/cornell.json"
"$bl" bench bundles "$shared/dragon/dragon_43k_ascii.ply" "${res[@]}" --directions "$directions" --json "$out/dragon.json"
"$bl" bench bundles "$root/data/external/sponza-point.toml" "${res[@]}" --directions "$directions" --json "$out/sponza.json"
"$bl" bench bundles "$shared/bunny/mcguire/bunny.obj" "${res[@]}" --directions "$directions" --json "$out/bunny.json"
"$bl" bench bundles --synthetic 1000000 "${res[@]}" --directions "$directions" --json "$out/synthetic-1m.json"
