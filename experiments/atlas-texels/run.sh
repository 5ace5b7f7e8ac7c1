#!/usr/bin/env bash
# The atlas judged in texel space (issue 21 item 2): `bundlelab bench texels` on the area-lit and the
# point-lit Cornell box, 64^2 camera, atlas 128^2, bundles 256^2. Writes <scene>.log, .csv, .exr here.
# Run from the repository root: experiments/atlas-texels/run.sh [BUNDLELAB]
set -euo pipefail
bl=${1:-build/bundlelab}
here=experiments/atlas-texels
for scene in cornell cornell-point; do
    "$bl" bench texels "data/cornell-box/$scene.toml" --width 64 --height 64 \
        --set atlas_resolution=128 --set bundle_resolution=256 \
        --directions 16 --directions 64 --directions 256 --directions 1024 \
        --bake-spp 1 --bake-spp 4 --bake-spp 16 --bake-spp 64 --bake-spp 256 --reference-spp 4096 \
        --image-spp 1 --image-spp 4 --image-spp 16 --image-spp 64 --image-spp 256 --image-spp 1024 \
        --image-reference-spp 16384 --csv "$here/$scene.csv" --exr "$here/$scene.exr" 2>&1 | tee "$here/$scene.log"
done
