#!/usr/bin/env bash
# The hole / redundant-node trade-off of imperfect bundles over splat_scale (tests/modes/multibounce/
# SplatCoverageTest.cpp): per scene, 16 directions of 128^2 pixels, 16384 points per direction.
# Usage: experiments/multibounce/splat-coverage.sh [BUILD_DIR] [DIRECTIONS] > splat-coverage.txt
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build}
directions=${2:-16}
for scene in data/cornell-box/cornell.toml data/external/bunny-envmap.toml data/external/sponza-point.toml; do
    echo "== $scene ($directions directions)"
    BL_SPLAT_CURVE_SCENE=$root/$scene BL_SPLAT_CURVE_DIRECTIONS=$directions \
        "$build/tests/test_multibounce" --gtest_filter='SplatCoverage.*' | grep '^splat_scale'
done
