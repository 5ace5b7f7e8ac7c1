#!/usr/bin/env bash
# Benchmark (not a test): the atlas generator on one large mesh (issue 21 item 3: "a 1M-triangle
# atlas in under a minute with progress shown"). McGuire's bunny (144k triangles) subdivided once
# (576k) and twice (2.3M), each atlas at SIZE^2; prints each build's summary line.
#
#   experiments/bench/atlas-single-mesh.sh [SIZE] [OUTDIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
size=${1:-2048}
out=${2:-$root/out/bench/atlas-single-mesh}
mkdir -p "$out"
src=$root/../shared/data/bunny/mcguire/bunny.obj
for levels in 1 2; do
    mesh=$out/bunny-x$levels.obj
    [[ -s $mesh ]] || /usr/bin/python3 "$root/experiments/bench/subdivide-obj.py" "$src" "$mesh" $levels
    "$root/build/bundlelab" atlas "$mesh" --size "$size" 2>&1 | tail -2
done
