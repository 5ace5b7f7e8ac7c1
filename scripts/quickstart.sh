#!/usr/bin/env bash
# Quick start, step 1: install what is missing, build, and run the main job on the built-in default.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
scripts/install-deps.sh
scripts/build.sh
out=out/quickstart
mkdir -p "$out"
build/bundlelab render data/cornell-box/cornell.toml --mode raster --spp 16 --out "$out/cornell-raster.exr"
echo
echo "quickstart: results in $root/$out (cornell-raster.exr, cornell-raster.png, cornell-raster.json)"
