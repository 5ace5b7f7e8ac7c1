#!/usr/bin/env bash
# Configures and builds Release into build/. Incremental: a second run rebuilds only what changed.
# Reconfigures when the git revision moved, so outputs record the revision they were built from.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
head=$(git rev-parse HEAD 2>/dev/null || echo none)
if [[ ! -f build/build.ninja || "$(cat build/.bl-head 2>/dev/null)" != "$head" ]]; then
    cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
    echo "$head" >build/.bl-head
fi
cmake --build build --parallel "$(nproc)"
