#!/usr/bin/env bash
# [TO12] Table 1's shape for mode bidir: milliseconds per frame split per pass, 640x360, 21 VPLs +
# 21 bundles (the paper's K) on the point-lit Cornell box, on the device bundlelab picks (lavapipe
# here). Warm-up is removed by differencing: each repeat renders 1 frame and 1 + F frames with the
# same settings, and the per-frame cost of a pass is (T(1 + F) - T(1)) / F (the first frame carries
# the shader compilation and the lights' shadow cubes of a static scene); the table gives the
# median over the repeats. Wall = the mode's iterate() calls (CPU VPL rays and submission included).
#   experiments/bidir-table1.sh [BUILD_DIR] [REPEATS] [FRAMES] [OUT_DIR] [-- extra render options]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
repeats=${2:-3}
frames=${3:-4}
out=${4:-$root/results/bidir-table1}
shift $(( $# < 4 ? $# : 4 )) || true
[[ "${1:-}" == "--" ]] && shift
mkdir -p "$out"
scene="$root/data/cornell-box/cornell-point.toml"
# The machine may be shared: the load average before and after goes into the table.
[[ -n "${SUMMARY_ONLY:-}" ]] || cut -d' ' -f1-3 /proc/loadavg >"$out/load-before.txt"
for r in $(seq 1 "$repeats"); do
    [[ -n "${SUMMARY_ONLY:-}" ]] && break
    for n in 1 $((frames + 1)); do
        "$build/bundlelab" render "$scene" --mode bidir --width 640 --height 360 --iterations "$n" --seed "$r" \
            --set pairs_per_frame=21 "$@" --out "$out/r$r-n$n.exr" >"$out/r$r-n$n.log" 2>&1
    done
done
[[ -n "${SUMMARY_ONLY:-}" ]] || cut -d' ' -f1-3 /proc/loadavg >"$out/load-after.txt"
/usr/bin/python3 - "$out" "$repeats" "$frames" <<'PY'
import json, statistics, sys
out, repeats, frames = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
paper = {"gbuffer": ("Create G-Buffer", 6.0), "VPL rays (CPU)": ("Create Reflective Shadow Maps", 2.7),
         "shadow maps (first frame only)": ("Create Shadow Maps", 2.9), "bundle build": ("Create Ray-Bundle x21", 154.0),
         "shadow cube": ("Create VPL Shadow Map x21", 29.9), "evaluate": ("Compute Bidirectional Path Tracing x21", 5.5)}
rows = {}
for r in range(1, repeats + 1):
    a = json.load(open(f"{out}/r{r}-n1.json")); b = json.load(open(f"{out}/r{r}-n{frames + 1}.json"))
    pa = {p["name"]: p for p in a["passes"]}; pb = {p["name"]: p for p in b["passes"]}
    for name, p in pb.items():
        if name in pa and pa[name]["count"] == p["count"]:
            # Runs in the first frame only (the lights' cubes of a static scene): its time, once.
            rows.setdefault(name + " (first frame only)", []).append(pa[name]["total_ms"])
        else:
            rows.setdefault(name, []).append((p["total_ms"] - pa.get(name, {"total_ms": 0.0})["total_ms"]) / frames)
    pa = {k: v["total_ms"] for k, v in pa.items()}; pb = {k: v["total_ms"] for k, v in pb.items()}
    gpu = sum(pb.values()) - sum(pa.values())
    wall = (b["wall_seconds"] - a["wall_seconds"]) * 1000.0
    rows.setdefault("wall", []).append(wall / frames)
    rows.setdefault("wall - GPU passes (CPU VPL rays, host, submission)", []).append((wall - gpu) / frames)
device = b["environment"]["device"]
lines = [f"device: {device}; 640x360, 21 pairs, defaults otherwise ({', '.join(f'{k}={v}' for k, v in b['settings'].items())})",
         f"median over {repeats} repeats of (T(1+{frames}) - T(1)) / {frames}; every repeat's value beside it",
         "load average (1, 5, 15 min) before / after: " + open(f"{out}/load-before.txt").read().strip() + " / "
         + open(f"{out}/load-after.txt").read().strip() + f" on {b['environment'].get('hardware_threads', '?')} hardware threads", "",
         "| pass | ms / frame (median) | repeats | [TO12] Table 1 (HD 6990, 1920x1088, 2x2 SS) |", "|---|---|---|---|"]
for name, vals in rows.items():
    p = paper.get(name)
    lines.append(f"| {name} | {statistics.median(vals):.1f} | {', '.join(f'{v:.1f}' for v in vals)} | "
                 + (f"{p[0]}: {p[1]}" if p else ("Total: 77.8" if name == "wall" else "")) + " |")
open(f"{out}/table1.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
