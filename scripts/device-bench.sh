#!/usr/bin/env bash
# The GPU benchmark kit's one call (benchmarks, not pass/fail): on the machine's Vulkan device, within
# a time budget (default 8 minutes),
#   1. every mode's milliseconds per pass and iteration ([TO12] Table 1's shape): each configuration
#      renders 1 + 5F iterations with checkpoints after 1, 1 + 2F and 1 + 3F; from the last three pass
#      totals, a pass's cost per iteration and per resolve, without set-up, first-use shader
#      compilation or the GPU's clock ramp (the first 1 + 2F iterations are a warm-up);
#   2. bundle build + walk against the rasterization floor, both build backends, Sponza and the bunny;
#   3. each mode against the path tracer at equal time on this machine's cores (the experiment runner;
#      relMSE against a 1024-spp reference; each mode against the path tracer judged by the same
#      reference: full GI, or cut to 4 segments for bidir and 2 for raster and skylight; the
#      summary also gives the ratios with the reference's own noise taken off);
#   4. the atlas in texel space (bundlelab bench texels, point-lit Cornell box): its error over every
#      texel against the path tracer baking the same texels, and per view count against the path tracer;
# and writes OUTDIR/summary.md (one document of tables) and OUTDIR/summary.json. A step that would
# overrun the budget is skipped and listed as skipped; a failed render is listed with its exit status.
# Runs from the unpacked kit (scripts/device-kit.sh) or from a checkout with build/bundlelab.
#
#   scripts/device-bench.sh OUTDIR [--quick] [--budget SECONDS] [--device D] [--only STEP]...
#   --quick: tiny sizes and budgets (the test runs it on lavapipe), not for figures.
#   --only STEP: run this step (passes, bundles, equal-time, texels; repeatable), the others not at all
#   (their budget shares stay: a step still ends where the full run's would).
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:?usage: device-bench.sh OUTDIR [--quick] [--budget SECONDS] [--device D] [--only STEP]...}
shift
quick=0 budget=480 device=() only=()
while (($#)); do
    case $1 in
        --quick) quick=1 ;;
        --budget) budget=$2; shift ;;
        --device) device=(--device "$2"); shift ;;
        --only)
            (($# >= 2)) || { echo "device-bench: --only needs a step (passes, bundles, equal-time, texels)" >&2; exit 2; }
            case $2 in passes|bundles|equal-time|texels) only+=("$2") ;;
                *) echo "device-bench: --only $2: not a step (passes, bundles, equal-time, texels)" >&2; exit 2 ;; esac
            shift ;;
        *) echo "device-bench: unknown option $1" >&2; exit 2 ;;
    esac
    shift
done
if [[ -x "$root/bin/bundlelab" ]]; then
    bl=$root/bin/bundlelab
    export LD_LIBRARY_PATH=$root/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
else
    bl=$root/build/bundlelab
fi
[[ -x "$bl" ]] || { echo "device-bench: no bundlelab binary at $bl" >&2; exit 1; }
python=python3
command -v /usr/bin/python3 >/dev/null && python=/usr/bin/python3
wanted() { ((${#only[@]} == 0)) || [[ " ${only[*]} " == *" $1 "* ]]; }
# A reused OUTDIR: the steps not run this time must not show an earlier run's figures.
wanted passes || rm -rf "$out/passes"
wanted bundles || rm -rf "$out/bundles"
wanted equal-time || rm -rf "$out/equal-time" "$out/equal-time.log" "$out/equal-time.toml"
mkdir -p "$out"/passes "$out"/bundles "$out"/texels
start=$(date +%s)
# Each step owns a share of the budget (passes to 40 %, bundles to 58 %, equal time to 86 %, the atlas in
# texel space the rest), so a
# slow device still reaches every step; a render that would start with under 20 s left is skipped.
step_end=$start
step() { step_end=$((start + budget * $1 / 100)); }
remaining() { echo $((step_end - $(date +%s))); }
log() { echo "[$(($(date +%s) - start)) s] $*" | tee -a "$out/log.txt"; }
# status EXIT_CODE: a step's line in steps.txt; 124 is `timeout` ending it at the budget (skipped).
status() { case $1 in 0) echo ok ;; 124) echo "skipped (budget: stopped at its share)" ;; *) echo "failed (exit $1)" ;; esac; }
: >"$out/steps.txt" # one line per render / benchmark: kind, name, status

# The device. A machine whose loader finds no driver by itself (a container with the NVIDIA driver
# mounted, say) gets the ICD files where they usually lie.
if ! "$bl" devices >"$out/devices.txt" 2>&1 || [[ ! -s "$out/devices.txt" ]]; then
    for icd in /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json /usr/share/vulkan/icd.d/nvidia_icd.json \
               /etc/vulkan/icd.d/nvidia_icd.json; do
        if [[ -f "$icd" ]]; then
            export VK_DRIVER_FILES=$icd VK_ICD_FILENAMES=$icd
            "$bl" devices >"$out/devices.txt" 2>&1 && [[ -s "$out/devices.txt" ]] && break
            unset VK_DRIVER_FILES VK_ICD_FILENAMES # this one did not work: leave the loader's own search
        fi
    done
fi
log "devices: $(tr '\n' ' ' <"$out/devices.txt")"
{
    echo "revision: $(cat "$root/REVISION" 2>/dev/null || git -C "$root" rev-parse --short=12 HEAD 2>/dev/null || echo unknown)"
    echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
    echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), $(nproc) hardware threads"
    command -v nvidia-smi >/dev/null && echo "gpu: $(nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2>/dev/null | head -1)"
    echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
    echo "quick: $quick"
} >"$out/machine.txt"

cornell=$root/data/cornell-box/cornell-point.toml
cornell_area=$root/data/cornell-box/cornell.toml
sponza=$root/data/external/sponza-point.toml
bunny_env=$root/data/external/bunny-envmap.toml
bunny=$root/../shared/data/bunny/mcguire/bunny.obj

step 40
# 1. Per-pass times. Each line: mode, scene name, scene file, extra iterations F, settings.
if ((quick)); then
    width=64 height=36
    configs=(
        "raster cornell $cornell 1 shadow_resolution=64"
        "bidir cornell $cornell 1 pairs_per_frame=2 bundle_resolution=32 shadow_resolution=64 vpl_shadow_resolution=16 rsm_resolution=16"
        "multibounce cornell $cornell 1 bundle_count=2 paths_per_pixel=1 bundle_resolution=32"
        "atlas cornell $cornell 1 atlas_resolution=32 bundle_resolution=32 shadow_resolution=64 view_samples=1"
        "skylight sky-blocks $root/data/analytic/sky-blocks.toml 1 bundle_resolution=32"
    )
else
    width=640 height=360
    # F sized so that the 2F warm-up iterations hold the GPU busy for a few hundred milliseconds: on
    # an H200, multibounce with F = 4 (8 warm-up iterations, ~60 ms) still ran at low clocks in one
    # of two runs (26.7 against 7.0 ms GPU per iteration).
    configs=(
        "raster cornell $cornell 32"
        "raster sponza $sponza 32"
        "raster cornell-area $cornell_area 32"
        "bidir cornell $cornell 8"
        "bidir sponza $sponza 8"
        "multibounce cornell $cornell 16"
        "multibounce sponza $sponza 8"
        "multibounce cornell-area $cornell_area 16"
        "atlas cornell $cornell 64"
        "atlas sponza $sponza 32"
        "skylight bunny-envmap $bunny_env 64"
    )
fi
wanted passes || configs=()
for config in "${configs[@]}"; do
    read -r mode name scene frames settings <<<"$config"
    sets=()
    for kv in $settings; do sets+=(--set "$kv"); done
    dir=$out/passes/$mode-$name
    mkdir -p "$dir"
    n=$((1 + 5 * frames))
    rm -f "$dir"/run* # a reused OUTDIR must not summarise an older run
    left=$(remaining)
    if ((left < 20)); then
        echo "passes $mode-$name skipped (budget)" >>"$out/steps.txt"; log "skip $mode $name"; continue
    fi
    log "passes: $mode $name, $n iterations"
    # One process, checkpoints after iterations 1, 1 + 2F and 1 + 3F, the end after 1 + 5F: every
    # checkpoint resolves the image (atlas times its resolve passes), so the last two differences hold
    # F and 2F iterations plus one resolve each; their difference is F iterations alone (set-up,
    # first-use shader compilation and resolves left out), and the resolve is what remains of the
    # first. The first checkpoint gives the first iteration's figures; the 2F iterations after it are
    # a warm-up: an H200 running a host-bound mode (atlas on Sponza) sat at low clocks for its first
    # tens of iterations, and a difference across that ramp gave negative per-iteration times.
    timeout "$left" "$bl" render "$scene" --mode "$mode" --width "$width" --height "$height" --iterations "$n" \
        --checkpoint 1 --checkpoint $((1 + 2 * frames)) --checkpoint $((1 + 3 * frames)) "${sets[@]}" "${device[@]}" \
        --out "$dir/run.exr" >"$dir/run.log" 2>&1
    rc=$?
    echo "passes $mode-$name $(status $rc)" >>"$out/steps.txt"
done

step 58
# 2. Bundles against the floor.
if ((quick)); then
    bench_scenes=("cornell $root/data/cornell-box/cornell.toml"); res=(--resolution 64 --resolution 128); dirs=2
else
    bench_scenes=("sponza $sponza" "bunny $bunny"); res=(--resolution 512 --resolution 1024 --resolution 2048); dirs=8
fi
wanted bundles || bench_scenes=()
for entry in "${bench_scenes[@]}"; do
    read -r name scene <<<"$entry"
    for backend in raster compute; do
        left=$(remaining)
        if ((left < 20)); then
            echo "bundles $name-$backend skipped (budget)" >>"$out/steps.txt"; continue
        fi
        log "bundles: $name, $backend"
        timeout "$left" "$bl" bench bundles "$scene" "${res[@]}" --directions "$dirs" --backend "$backend" "${device[@]}" \
            --json "$out/bundles/$name-$backend.json" >"$out/bundles/$name-$backend.log" 2>&1
        rc=$?
        echo "bundles $name-$backend $(status $rc)" >>"$out/steps.txt"
    done
done

step 86
# 3. Equal time against the path tracer (the runner; one GPU task at a time, the path tracer on all cores).
if ((quick)); then
    seconds=0.5 spp=16 resolution=16 mb="bundle_count = 2, paths_per_pixel = 1, bundle_resolution = 32" area_variants=""
    bd="pairs_per_frame = 2, bundle_resolution = 32, shadow_resolution = 64, vpl_shadow_resolution = 16, rsm_resolution = 16"
    at="atlas_resolution = 32, bundle_resolution = 32, shadow_resolution = 64, view_samples = 1"
    scenes="[[scene]]
name = \"cornell-point\"
file = \"$cornell\"
resolution = [$resolution, $resolution]"
    gi_scenes='["cornell-point"]' direct_scenes='["cornell-point"]' sky_mode=""
else
    seconds=6 spp=1024 resolution=128 mb="" bd="" at=""
    # On the area-lit box: multibounce's emitters by bundle hits alone ([TO12]) beside its default MIS
    # with emitter points, and atlas's exchange alone beside its default first shot.
    area_variants="[[mode]]
mode     = \"multibounce\"
label    = \"multibounce-bundles\"
scenes   = [\"cornell-area\"]
settings = { emitter_sampling = \"bundles\" }

[[mode]]
mode     = \"atlas\"
label    = \"atlas-exchange\"
scenes   = [\"cornell-area\"]
settings = { first_shot = \"off\" }
"
    scenes="[[scene]]
name = \"cornell-point\"
file = \"$cornell\"
resolution = [$resolution, $resolution]

[[scene]]
name = \"cornell-area\"
file = \"$cornell_area\"
resolution = [$resolution, $resolution]

[[scene]]
name = \"bunny-envmap\"
file = \"$bunny_env\"
resolution = [$resolution, $resolution]"
    # The full-GI modes on the Cornell boxes; direct light (raster, skylight under the probe) against
    # the path tracer cut to 2 segments.
    gi_scenes='["cornell-point", "cornell-area"]' direct_scenes='["cornell-point", "cornell-area", "bunny-envmap"]'
    sky_mode="[[mode]]
mode      = \"skylight\"
scenes    = [\"bunny-envmap\"]
reference = { max_segments = 2 }
"
fi
cat >"$out/equal-time.toml" <<EOF
# Written by scripts/device-bench.sh: every mode at equal wall time against the path tracer.
[experiment]
name        = "device-equal-time"
seeds       = [0]
seconds     = $seconds
checkpoints = "log"

[reference]
spp      = $spp
settings = { max_segments = 64 }

$scenes

[[mode]]
mode   = "reference"
label  = "path-tracer"
scenes = $gi_scenes

[[mode]]
mode     = "multibounce"
scenes   = $gi_scenes
settings = { $mb }

$area_variants
[[mode]]
mode      = "reference"
label     = "path-tracer-4"
scenes    = ["cornell-point"]
settings  = { max_segments = 4 }
reference = { max_segments = 4 }

[[mode]]
mode      = "bidir"
scenes    = ["cornell-point"]
settings  = { $bd }
reference = { max_segments = 4 }   # bidir computes paths of up to two bounces

[[mode]]
mode     = "atlas"
scenes   = $gi_scenes
settings = { $at }

[[mode]]
mode      = "reference"
label     = "path-tracer-2"
scenes    = $direct_scenes
settings  = { max_segments = 2 }
reference = { max_segments = 2 }

[[mode]]
mode      = "raster"
scenes    = $direct_scenes
reference = { max_segments = 2 }   # raster computes direct light
$sky_mode
EOF
left=$(remaining)
if ! wanted equal-time; then
    :
elif ((left < 60)); then
    echo "equal-time all skipped (budget)" >>"$out/steps.txt"
else
    log "equal time: $seconds s per task"
    timeout "$left" "$bl" run "$out/equal-time.toml" --out "$out/equal-time" "${device[@]}" >"$out/equal-time.log" 2>&1
    rc=$?
    echo "equal-time all $(status $rc)" >>"$out/steps.txt"
fi

step 100
# 4. The atlas in texel space (bundlelab bench texels): its error over every texel against the path
# tracer baking the same texels, and per view count against the path tracer (on this machine's cores).
if ((quick)); then
    texel_args=(--width 16 --height 16 --set atlas_resolution=32 --set bundle_resolution=64 --directions 4 --directions 8
                --bake-spp 4 --reference-spp 16 --image-spp 4 --image-reference-spp 16)
else
    # Sized for its ~70 s share on a GPU machine (16 cores for the references): experiments/atlas-texels
    # has the same at 1024 directions and 4096-path references on lavapipe.
    texel_args=(--width 64 --height 64 --set atlas_resolution=128 --set bundle_resolution=256 --directions 16
                --directions 64 --directions 256 --bake-spp 1 --bake-spp 4 --bake-spp 16 --bake-spp 64
                --bake-spp 256 --reference-spp 1024 --image-spp 1 --image-spp 4 --image-spp 16 --image-spp 64
                --image-spp 256 --image-reference-spp 4096)
fi
rm -f "$out"/texels/cornell-point.* # a skipped step must not show an earlier run's tables
left=$(remaining)
if ! wanted texels; then
    :
elif ((left < 20)); then
    echo "texels cornell-point skipped (budget)" >>"$out/steps.txt"
else
    log "texels: cornell-point"
    # Line-buffered, so that a step stopped at its share keeps the rows it printed.
    timeout "$left" stdbuf -oL "$bl" bench texels "$cornell" "${texel_args[@]}" "${device[@]}" --csv "$out/texels/cornell-point.csv" \
        >"$out/texels/cornell-point.log" 2>&1
    rc=$?
    echo "texels cornell-point $(status $rc)" >>"$out/steps.txt"
fi

log "summary"
"$python" "$root/scripts/device-bench-summary.py" "$out"
rc=$?
log "done in $(($(date +%s) - start)) s"
exit $rc
