#!/usr/bin/env bash
# Benchmark (not a test): speed of the reference path tracer on McGuire's Cornell box at 256^2,
# and its error against the independent Tungsten reference (1024 spp) at equal samples.
#
#   experiments/bench/reference-speed.sh [SPP] [THREADS] [OUTDIR]
#
# Two renders with different seeds give our own variance (relMSE(a, b) = 2 v_ours); against
# Tungsten, relMSE(a, T) = v_ours + v_tungsten (+ bias^2, which the image means show is tiny).
# Equal-error time is the time our tracer needs to bring v_ours down to v_tungsten (v ~ 1/spp).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
spp=${1:-1024}
threads=${2:-2}
out=${3:-$root/out/bench/reference-speed}
bl=$root/build/bundlelab
ref=$root/../shared/references/cornell-mcguire/mcguire-CornellBox-Original_256_1024spp.exr
mkdir -p "$out"
for seed in 0 1; do
    "$bl" render "$root/data/external/cornell-mcguire.toml" --mode reference --spp "$spp" --seed "$seed" \
        --set threads="$threads" --out "$out/seed$seed.exr" | tee "$out/seed$seed.log"
done
"$bl" compare "$out/seed0.exr" "$out/seed1.exr" --json >"$out/self.json"
"$bl" compare "$out/seed0.exr" "$ref" --json >"$out/tungsten.json"
/usr/bin/python3 - "$out" "$spp" <<'PY'
import json, sys
out, spp = sys.argv[1], int(sys.argv[2])
runs = [json.load(open(f"{out}/seed{s}.json")) for s in (0, 1)]
self_ = json.load(open(f"{out}/self.json"))
tung = json.load(open(f"{out}/tungsten.json"))
wall = sorted(r["wall_seconds"] for r in runs)
v_ours = self_["relmse"] / 2
v_tungsten = max(tung["relmse"] - v_ours, 1e-12)
wall_mean = sum(wall) / len(wall)
equal_error_spp = spp * v_ours / v_tungsten
lines = [
    f"# Reference speed: McGuire Cornell box, 256x256, {spp} spp, threads={runs[0]['settings']['threads']}",
    "",
    "- wall time per run: " + ", ".join("%.1f s" % w for w in wall),
    "- samples/s: " + ", ".join("%.4g" % r["samples_per_second"] for r in runs),
    "- rays/s: " + ", ".join("%.4g" % r["counters"]["rays_per_second"] for r in runs),
    "- mean ratio against Tungsten: " + ", ".join("%.5f" % x for x in tung["mean_ratio"]),
    f"- block-ratio RMS (8x8) against Tungsten: {tung['block_ratio_rms']:.4f}",
    f"- relMSE per image: ours {v_ours:.3e}, Tungsten (1024 spp) {v_tungsten:.3e}",
    f"- equal error: ours needs {equal_error_spp:.0f} spp = {wall_mean * equal_error_spp / spp:.1f} s wall "
    f"(Tungsten: 1024 spp in about 50-80 s on this kind of machine)",
]
open(f"{out}/summary.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
