#!/usr/bin/env bash
# Benchmark (not a test): the atlas generator on Sponza, the Stanford bunny and the dragon at
# SIZE^2 (the issue's targets: utilization >= 0.70, 0 flipped, 0 overlapping texels, 0 uncovered
# triangles, max stretch <= 2, Sponza in <= 10 s on 2 cores). Each scene runs REPEATS times; the
# table gives the median time (the atlas itself is deterministic).
#
#   experiments/bench/atlas.sh [SIZE] [REPEATS] [OUTDIR] [-- extra bundlelab atlas options]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
size=${1:-2048}
repeats=${2:-3}
out=${3:-$root/out/bench/atlas}
shift $(($# < 3 ? $# : 3))
[[ "${1:-}" == "--" ]] && shift
bl=$root/build/bundlelab
shared=$root/../shared/data
mkdir -p "$out"
for scene in sponza-dabrovic/sponza.obj bunny/stanford/bun_zipper.ply dragon/dragon_43k_ascii.ply; do
    name=$(basename "${scene%.*}")
    for r in $(seq 1 "$repeats"); do
        "$bl" atlas "$shared/$scene" --size "$size" --out "$out/$name.png" --report "$out/$name.$r.json" "$@" >/dev/null
    done
done
/usr/bin/python3 - "$out" "$size" "$repeats" <<'PY'
import json, statistics, sys
out, size, repeats = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
lines = [f"# Atlas generator at {size}x{size} ({repeats} runs each, median time)", "",
         "| scene | triangles | charts | utilization | texels/unit | mean stretch | max stretch | flipped | overlapping | uncovered | non-manifold | seconds (median) |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|"]
for name in ("sponza", "bun_zipper", "dragon_43k_ascii"):
    runs = [json.load(open(f"{out}/{name}.{r}.json")) for r in range(1, repeats + 1)]
    j = runs[0]
    lines.append(f"| {name} | {j['triangles']} | {j['charts']} | {j['utilization']:.4f} | {j['texels_per_unit']:.5g} | "
                 f"{j['mean_stretch']:.4f} | {j['max_stretch']:.4f} | {j['flipped_triangles']} | {j['overlapping_texels']} | "
                 f"{j['uncovered_triangles']} | {j['non_manifold_faces']} | "
                 f"{statistics.median(r['seconds'] for r in runs):.2f} ({', '.join('%.2f' % r['seconds'] for r in runs)}) |")
open(f"{out}/summary.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
