#!/usr/bin/env bash
# Benchmark (not a test) of mode atlas, the shape of [HHGM10] Table 1: milliseconds per direction
# split into bundle build + sort and exchange + update (host wall clock around each submission:
# lavapipe's GPU timestamps put the compute passes at ~0.1 ms, far from their real cost, so they are
# listed apart), for bundle 512^2..2048^2 and atlas 1024^2..2048^2 on the Cornell box (area light),
# and hits exchanged per second. Per-direction cost without warm-up: each configuration renders
# WARM and WARM + N directions and takes (total(WARM + N) - total(WARM)) / N per pass (lavapipe
# compiles on first use); REPEATS runs, the median is reported. The view is 32^2 with one sample
# (not part of a direction's cost).
#
#   experiments/atlas-bench.sh [N] [REPEATS] [OUTDIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
n=${1:-8}
repeats=${2:-3}
out=${3:-$root/out/bench/atlas-mode}
warm=1
bl=${BL_BUNDLELAB:-$root/build/bundlelab}
scene=$root/data/cornell-box/cornell.toml
mkdir -p "$out"
for atlas in 1024 2048; do
    for bundle in 512 1024 2048; do
        for r in $(seq 1 "$repeats"); do
            for it in $warm $((warm + n)); do
                "$bl" render "$scene" --mode atlas --iterations "$it" --width 32 --height 32 --seed "$r" \
                    --set atlas_resolution="$atlas" --set bundle_resolution="$bundle" --set view_samples=1 \
                    --out "$out/a$atlas-b$bundle-r$r-i$it.exr" >"$out/a$atlas-b$bundle-r$r-i$it.log" 2>&1
            done
        done
    done
done
/usr/bin/python3 - "$out" "$n" "$repeats" "$warm" <<'PY'
import json, statistics, sys
out, n, repeats, warm = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
def load(a, b, r, i):
    d = json.load(open(f"{out}/a{a}-b{b}-r{r}-i{i}.json"))
    return {p["name"]: p["total_ms"] for p in d["passes"]}, dict(d["counters"]) if isinstance(d["counters"], list) else d["counters"]
passes = ["build + sort (wall)", "exchange + update (wall)", "bundle build", "bundle sort", "exchange", "update"]
print(f"| atlas | bundle | build + sort ms | exchange + update ms | ms / direction | GPU timestamps build / sort / exchange / update ms | hits / direction | hits exchanged / s |")
print("|---|---|---|---|---|---|---|---|")
for a in (1024, 2048):
    for b in (512, 1024, 2048):
        per = {p: [] for p in passes}
        hits = []
        for r in range(1, repeats + 1):
            t0, _ = load(a, b, r, warm)
            t1, c = load(a, b, r, warm + n)
            for p in passes:
                per[p].append((t1.get(p, 0.0) - t0.get(p, 0.0)) / n)
            hits.append(float(c.get("bundle_nodes_last", 0.0)))
        med = {p: statistics.median(v) for p, v in per.items()}
        total = med["build + sort (wall)"] + med["exchange + update (wall)"]
        h = statistics.median(hits)
        print(f"| {a}^2 | {b}^2 | {med['build + sort (wall)']:.0f} | {med['exchange + update (wall)']:.0f} | {total:.0f} | "
              f"{med['bundle build']:.0f} / {med['bundle sort']:.1f} / {med['exchange']:.1f} / {med['update']:.1f} | "
              f"{h:.3g} | {h / total * 1e3:.3g} |")
PY
