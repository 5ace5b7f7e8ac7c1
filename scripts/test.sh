#!/usr/bin/env bash
# Quick start, step 2: install what is missing, build if needed, run the whole test suite through ctest.
# Every Vulkan test runs with the validation layers on; any validation error fails it.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
scripts/install-deps.sh
scripts/build.sh
cd build
# ctest starts the longest tests first when it knows their times (CTestCostData.txt); a clean clone
# gets the times measured here, so that a 100-second test does not start last and run alone.
if [[ ! -s Testing/Temporary/CTestCostData.txt && -s "$root/tests/CTestCostData.txt" ]]; then
    mkdir -p Testing/Temporary
    cp "$root/tests/CTestCostData.txt" Testing/Temporary/CTestCostData.txt
fi
# One llvmpipe thread per test: ctest already runs one test per core, and two tests each asking
# lavapipe for every core spend their time handing work between threads (a clean clone's suite on
# 2 cores: 1091 s of tests with lavapipe's default, 920 s with one thread each, 2026-11-29). A
# caller's own LP_NUM_THREADS wins; other Vulkan drivers ignore it.
export LP_NUM_THREADS=${LP_NUM_THREADS:-1}
ctest --output-on-failure --parallel "$(nproc)" "$@"
