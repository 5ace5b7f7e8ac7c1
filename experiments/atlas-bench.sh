#!/usr/bin/env bash
# Benchmark (not a test) of mode atlas, the shape of [HHGM10] Table 1: milliseconds per direction
# split into bundle build / sort / exchange / update / glossy by GPU timestamps (GpuTimer puts a
# barrier after each start timestamp, so lavapipe's compute passes read their own time), for bundle
# 512^2..2048^2 and atlas 1024^2..2048^2 on the Cornell box (area light; SCENE= another scene, e.g.
# a glossy one, where the glossy passes run), beside the host wall clock per direction, and hits
# exchanged per second. Per-direction cost without warm-up or once-per-run passes: each
# configuration renders WARM and WARM + N directions and takes (total(WARM + N) - total(WARM)) / N
# per pass (lavapipe compiles on first use; set-up, direct atlas and the one resolve cancel);
# REPEATS runs, the median is reported. The view is 32^2 with one sample (not part of a direction's
# cost). "glossy" sums every pass named glossy*, "other" any further pass that runs per direction
# (its count grows with the directions: the glossy gather's camera G-buffer).
#
#   [SCENE=file.toml] [ATLASES="1024 2048"] [BUNDLES="512 1024 2048"] experiments/atlas-bench.sh [N] [REPEATS] [OUTDIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
n=${1:-8}
repeats=${2:-3}
out=${3:-$root/out/bench/atlas-mode}
warm=1
bl=${BL_BUNDLELAB:-$root/build/bundlelab}
scene=${SCENE:-$root/data/cornell-box/cornell.toml}
atlases=${ATLASES:-1024 2048}
bundles=${BUNDLES:-512 1024 2048}
mkdir -p "$out"
for atlas in $atlases; do
    for bundle in $bundles; do
        for r in $(seq 1 "$repeats"); do
            for it in $warm $((warm + n)); do
                "$bl" render "$scene" --mode atlas --iterations "$it" --width 32 --height 32 --seed "$r" \
                    --set atlas_resolution="$atlas" --set bundle_resolution="$bundle" --set view_samples=1 --set first_shot=off \
                    --out "$out/a$atlas-b$bundle-r$r-i$it.exr" >"$out/a$atlas-b$bundle-r$r-i$it.log" 2>&1
            done
        done
    done
done
/usr/bin/python3 - "$out" "$n" "$repeats" "$warm" "$atlases" "$bundles" <<'PY'
import json, statistics, sys
out, n, repeats, warm = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
atlases, bundles = [int(a) for a in sys.argv[5].split()], [int(b) for b in sys.argv[6].split()]
def load(a, b, r, i):
    d = json.load(open(f"{out}/a{a}-b{b}-r{r}-i{i}.json"))
    return {p["name"]: (p["total_ms"], p["count"]) for p in d["passes"]}, d["counters"]
named = ["bundle build", "bundle sort", "exchange", "update"]
wall = ["build + sort (wall)", "direction (wall)", "exchange + update (wall)"]
print("| atlas | bundle | build | sort | exchange | update | glossy | other | GPU sum | wall ms / direction | "
      "hits / direction | hits exchanged / s (wall) |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
for a in atlases:
    for b in bundles:
        per, hits = {}, []
        for r in range(1, repeats + 1):
            t0, _ = load(a, b, r, warm)
            t1, c = load(a, b, r, warm + n)
            # passes that run per direction (their count grows with it); once-per-run ones cancel
            row = {p: (ms - t0.get(p, (0.0, 0))[0]) / n for p, (ms, k) in t1.items() if k > t0.get(p, (0.0, 0))[1]}
            split = {p: row.get(p, 0.0) for p in named}
            split["glossy"] = sum(v for p, v in row.items() if p.startswith("glossy"))
            split["other"] = sum(v for p, v in row.items() if p not in named + wall and not p.startswith("glossy"))
            split["gpu"] = sum(split[p] for p in named + ["glossy", "other"])
            split["wall"] = sum(row.get(p, 0.0) for p in wall)
            for p, v in split.items():
                per.setdefault(p, []).append(v)
            hits.append(float(c.get("bundle_nodes_last", 0.0)))
        m = {p: statistics.median(v) for p, v in per.items()}
        h = statistics.median(hits)
        print(f"| {a}^2 | {b}^2 | " + " | ".join(f"{m[p]:.1f}" for p in named + ["glossy", "other", "gpu"]) +
              f" | {m['wall']:.0f} | {h:.3g} | {h / m['wall'] * 1e3:.3g} |")
PY
