#!/usr/bin/env bash
# [TO12] Table 1's shape for mode bidir: milliseconds per frame split per pass, 640x360, 21 VPLs +
# 21 bundles (the paper's K), on the device bundlelab picks (lavapipe here), for four
# configurations: the point-lit Cornell box and Sponza, each with VPLs from traced light rays (CPU)
# and from reflective shadow cubes (vpl_source = rsm, GPU). Warm-up is removed by differencing:
# each repeat renders 1 frame and 1 + F frames with the same settings, and the per-frame cost of a
# pass is (T(1 + F) - T(1)) / F (the first frame carries the lights' shadow cubes of a static
# scene); the table gives the median over the repeats. Wall = the mode's iterate() calls (CPU VPL
# rays and submission included); CPU = the process's user + system time per frame, all threads
# (lavapipe's included): on a shared machine it moves far less with the load than wall times do.
# OLD_BUNDLELAB=path/to/bundlelab (an older build) adds its evaluation pass, measured in the same
# repeats right after the current build's runs, so old and new see the same load.
#   experiments/bidir-table1.sh [BUILD_DIR] [REPEATS] [FRAMES] [OUT_DIR] [-- extra render options]
#   CONFIGS="cornell-traced sponza-rsm" restricts the configurations.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
repeats=${2:-3}
frames=${3:-4}
out=${4:-$root/results/bidir-table1}
shift $(( $# < 4 ? $# : 4 )) || true
[[ "${1:-}" == "--" ]] && shift
configs=${CONFIGS:-cornell-traced cornell-rsm sponza-traced sponza-rsm}
declare -A sceneOf=([cornell]="$root/data/cornell-box/cornell-point.toml" [sponza]="$root/data/external/sponza-point.toml")
mkdir -p "$out"
run() { # run BINARY TAG CONFIG REPEAT N [options...]
    local bin=$1 tag=$2 config=$3 r=$4 n=$5; shift 5
    # Mesa's shader cache off: every run compiles its pipelines, so the CPU-time difference of the
    # 1- and (1 + F)-frame runs is frames only (a cache shared with other jobs hits in one and not the other).
    MESA_SHADER_CACHE_DISABLE=true /usr/bin/time -f "%U %S" -o "$out/$config/$tag-r$r-n$n.time" "$bin" render "${sceneOf[${config%-*}]}" --mode bidir \
        --width 640 --height 360 --iterations "$n" --seed "$r" --set pairs_per_frame=21 --set vpl_source="${config#*-}" \
        "$@" --out "$out/$config/$tag-r$r-n$n.exr" >"$out/$config/$tag-r$r-n$n.log" 2>&1
}
for config in $configs; do
    [[ -n "${SUMMARY_ONLY:-}" ]] && break
    mkdir -p "$out/$config"
    # The machine may be shared: the load average before and after goes into the table.
    cut -d' ' -f1-3 /proc/loadavg >"$out/$config/load-before.txt"
    for r in $(seq 1 "$repeats"); do
        for n in 1 $((frames + 1)); do
            run "$build/bundlelab" new "$config" "$r" "$n" "$@"
            [[ -z "${OLD_BUNDLELAB:-}" ]] || run "$OLD_BUNDLELAB" old "$config" "$r" "$n" "$@"
        done
    done
    cut -d' ' -f1-3 /proc/loadavg >"$out/$config/load-after.txt"
done
/usr/bin/python3 - "$out" "$repeats" "$frames" "$configs" <<'PY'
import json, os, statistics, sys
out, repeats, frames, configs = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4].split()
paper = {"gbuffer": ("Create G-Buffer", 6.0), "RSM cubes + VPL sampling": ("Create Reflective Shadow Maps", 2.7),
         "shadow maps (first frame only)": ("Create Shadow Maps", 2.9), "bundle build": ("Create Ray-Bundle x21", 154.0),
         "shadow cube": ("Create VPL Shadow Map x21", 29.9), "evaluate": ("Compute Bidirectional Path Tracing x21", 5.5),
         "wall": ("Total", 77.8)}
def cpu(path):
    u, s = open(path).read().split()[-2:]
    return (float(u) + float(s)) * 1000.0
lines = []
for config in configs:
    d = f"{out}/{config}"
    rows = {}
    b = None
    for tag in ("new", "old"):
        if not os.path.exists(f"{d}/{tag}-r1-n1.json"):
            continue
        suffix = "" if tag == "new" else " (old build)"
        for r in range(1, repeats + 1):
            if not os.path.exists(f"{d}/{tag}-r{r}-n{frames + 1}.json"):
                continue
            a = json.load(open(f"{d}/{tag}-r{r}-n1.json")); bb = json.load(open(f"{d}/{tag}-r{r}-n{frames + 1}.json"))
            if tag == "new":
                b = bb
            pa = {p["name"]: p for p in a["passes"]}; pb = {p["name"]: p for p in bb["passes"]}
            if tag == "old":  # only the pass this comparison is about
                pb = {k: v for k, v in pb.items() if k == "evaluate"}
            for name, p in pb.items():
                if name in pa and pa[name]["count"] == p["count"]:
                    # Runs in the first frame only (the lights' cubes of a static scene): its time, once.
                    rows.setdefault(name + " (first frame only)" + suffix, []).append(pa[name]["total_ms"])
                else:
                    rows.setdefault(name + suffix, []).append((p["total_ms"] - pa.get(name, {"total_ms": 0.0})["total_ms"]) / frames)
            if tag == "new":
                ta = {k: v["total_ms"] for k, v in pa.items()}; tb = {k: v["total_ms"] for k, v in pb.items()}
                gpu = sum(tb.values()) - sum(ta.values())
                wall = (bb["wall_seconds"] - a["wall_seconds"]) * 1000.0
                rows.setdefault("wall", []).append(wall / frames)
                rows.setdefault("wall - GPU passes (CPU VPL rays, host, submission)", []).append((wall - gpu) / frames)
            rows.setdefault("process CPU time, all threads" + suffix, []).append(
                (cpu(f"{d}/{tag}-r{r}-n{frames + 1}.time") - cpu(f"{d}/{tag}-r{r}-n1.time")) / frames)
    if b is None:
        continue
    lines += [f"### {config}: {os.path.basename(b['scene'])}, vpl_source = {b['settings'].get('vpl_source', 'traced')}", "",
              f"device: {b['environment']['device']}; {b['environment'].get('hardware_threads', '?')} hardware threads; "
              f"640x360, defaults otherwise ({', '.join(f'{k}={v}' for k, v in b['settings'].items())})",
              f"median over the repeats (up to {repeats}) of (T(1+{frames}) - T(1)) / {frames}; every repeat's value beside it",
              "load average (1, 5, 15 min) before / after: " + open(f"{d}/load-before.txt").read().strip() + " / "
              + open(f"{d}/load-after.txt").read().strip(), "",
              "| pass | ms / frame (median) | repeats | [TO12] Table 1 (HD 6990, 1920x1088, 2x2 SS) |", "|---|---|---|---|"]
    for name, vals in rows.items():
        p = paper.get(name)
        lines.append(f"| {name} | {statistics.median(vals):.1f} | {', '.join(f'{v:.1f}' for v in vals)} | "
                     + (f"{p[0]}: {p[1]}" if p else "") + " |")
    lines.append("")
open(f"{out}/table1.md", "w").write("\n".join(lines))
print("\n".join(lines))
PY
