#!/bin/sh
# Issue 19 B3: bidir's VPL strategy against its bundle strategy, region by region, on the glossy
# Cornell box with the sphere's vertex normals and with its faces shaded flat (the measurement is
# tests/modes/bidir/BidirB3Experiment.cpp, a disabled test). Writes results.txt beside this script.
# Usage: experiments/bidir-b3/run.sh [build dir]   (B3_SEEDS, B3_FRAMES, B3_SPP override 8, 64, 1024)
set -e
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-build}
cd "$here/../.."
"$build/tests/test_bidir" --gtest_also_run_disabled_tests --gtest_filter='BidirB3.*' | tee "$here/results.txt"
