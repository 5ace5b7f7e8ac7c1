#!/usr/bin/env bash
# Quick start, step 1: install what is missing, build, and run the main job on the built-in default:
# the Cornell box rendered by `raster` (with its area light, and lit by a point light).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
scripts/install-deps.sh
scripts/build.sh
out=out/quickstart
mkdir -p "$out"
build/bundlelab render data/cornell-box/cornell.toml --mode raster --spp 16 --out "$out/cornell-raster.exr"
build/bundlelab render data/cornell-box/cornell-point.toml --mode raster --spp 16 --out "$out/cornell-point-raster.exr"
echo
echo "quickstart: results in $root/$out"
ls -1 "$out"
