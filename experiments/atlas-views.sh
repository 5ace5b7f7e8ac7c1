#!/usr/bin/env bash
# Benchmark (not a test) of mode atlas: the cost of N views of one solution (issue 11, Speed: "the
# atlas is view-independent, so also report the cost of N views"). The first view pays set-up (atlas,
# tables, pipelines) + the directions + one resolve; every further view of the same atlas pays one
# resolve only: view_samples jittered camera samples per pixel, each a G-buffer, the atlas uv raster
# and the shade pass, then the read-back (the atlas itself is not touched). Measured two ways on the
# Cornell box (1024^2 atlas, 512^2 bundles, DIRS directions), per view size and view_samples:
#   - GPU timestamps of the resolve passes (gbuffer + atlas view + shade) per resolve, from the JSON
#     record of a run with a checkpoint after every direction (DIRS + 1 resolves);
#   - host wall clock: (process time with DIRS checkpoints - without) / DIRS, which also counts
#     writing the checkpoint's EXR + PNG + JSON (an upper bound of a view's cost).
# REPEATS runs each, medians.
#
#   experiments/atlas-views.sh [DIRS] [REPEATS] [OUTDIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
dirs=${1:-8}
repeats=${2:-3}
out=${3:-$root/out/bench/atlas-views}
bl=${BL_BUNDLELAB:-$root/build/bundlelab}
scene=$root/data/cornell-box/cornell.toml
mkdir -p "$out"
ckpt=()
for i in $(seq 1 "$dirs"); do ckpt+=(--checkpoint "$i"); done
for size in 128 512; do
    for vs in 1 16; do
        for r in $(seq 1 "$repeats"); do
            for kind in plain views; do
                extra=()
                [ "$kind" = views ] && extra=("${ckpt[@]}")
                name=s$size-v$vs-r$r-$kind
                t0=$(date +%s.%N)
                "$bl" render "$scene" --mode atlas --iterations "$dirs" --width "$size" --height "$size" --seed "$r" \
                    --set atlas_resolution=1024 --set bundle_resolution=512 --set view_samples="$vs" --set first_shot=off \
                    "${extra[@]}" --out "$out/$name.exr" >"$out/$name.log" 2>&1
                t1=$(date +%s.%N)
                echo "$t0 $t1" >"$out/$name.time"
            done
        done
    done
done
/usr/bin/python3 - "$out" "$dirs" "$repeats" <<'PY'
import json, statistics, sys
out, dirs, repeats = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
def wall(name):
    t0, t1 = map(float, open(f"{out}/{name}.time").read().split())
    return t1 - t0
print("| view | view_samples | first view s: set-up + directions + resolve (process wall, "
      f"{dirs} directions) | set-up s | ms / direction | further view ms, GPU: gbuffer + atlas view + shade | "
      "further view ms, host wall incl. writing the image | further views per first view |")
print("|---|---|---|---|---|---|---|---|")
for size in (128, 512):
    for vs in (1, 16):
        first, setup, perdir, gpu, host = [], [], [], [], []
        for r in range(1, repeats + 1):
            plain = json.load(open(f"{out}/s{size}-v{vs}-r{r}-plain.json"))
            views = json.load(open(f"{out}/s{size}-v{vs}-r{r}-views.json"))
            first.append(wall(f"s{size}-v{vs}-r{r}-plain"))
            setup.append(plain["setup_seconds"])
            perdir.append(plain["wall_seconds"] / dirs * 1e3)
            p = {q["name"]: q for q in views["passes"]}
            resolves = dirs + 1
            gpu.append(sum(p[n]["total_ms"] for n in ("gbuffer", "atlas view", "shade") if n in p) / resolves)
            host.append((wall(f"s{size}-v{vs}-r{r}-views") - wall(f"s{size}-v{vs}-r{r}-plain")) / dirs * 1e3)
        m = statistics.median
        print(f"| {size}^2 | {vs} | {m(first):.2f} | {m(setup):.2f} | {m(perdir):.0f} | {m(gpu):.1f} | {m(host):.0f} | "
              f"{m(first) * 1e3 / max(m(host), 1e-9):.0f} |")
PY
