#!/usr/bin/env bash
# Quick start, step 2: install what is missing, build if needed, run the whole test suite through ctest.
# Every Vulkan test runs with the validation layers on; any validation error fails it.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
scripts/install-deps.sh
scripts/build.sh
cd build
ctest --output-on-failure --parallel "$(nproc)" "$@"
