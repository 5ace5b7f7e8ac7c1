#!/usr/bin/env bash
# cli_test.sh CASE BUNDLELAB OUTDIR: one end-to-end case of the CLI. Exits non-zero on failure.
set -uo pipefail
case_name=$1
bl=$2
out=$3/$case_name
rm -rf "$out" && mkdir -p "$out"

fail() { echo "FAIL: $*"; exit 1; }
# needs_shared FILE: skip the case (exit 77, ctest's SKIP_RETURN_CODE) where a file of ../shared, the
# seed papers' scenes beside the repository, is not here; the message names it.
needs_shared() {
    [[ -e "$1" ]] || { echo "SKIP: needs $(realpath -m "$1"), which is not here (../shared, beside the repository)"; exit 77; }
}
# expect_error CMD...: the command must exit non-zero, print "bundlelab: error:" and $expected.
expect_error() {
    local log="$out/stderr.txt"
    "$@" >"$out/stdout.txt" 2>"$log"
    local rc=$?
    cat "$log"
    [[ $rc -ne 0 ]] || fail "exit code 0 for: $*"
    grep -qF -- "$expected" "$log" || fail "message lacks '$expected'"
}

case "$case_name" in
render_writes_outputs)
    "$bl" render data/cornell-box/cornell-point.toml --mode raster --width 64 --height 48 --spp 2 \
        --set shadow_resolution=128 --out "$out/img.exr" | tee "$out/log.txt" || fail "render failed"
    for f in img.exr img.png img.json; do [[ -s "$out/$f" ]] || fail "missing $f"; done
    grep -q '"iterations": 2' "$out/img.json" || fail "json lacks iterations"
    grep -q '"shadow_resolution": "128"' "$out/img.json" || fail "json lacks resolved settings"
    grep -q '"device": "llvmpipe\|"device": "' "$out/img.json" || fail "json lacks device"
    grep -q "shade" "$out/log.txt" || fail "no per-pass timings printed"
    ;;
render_frames)
    # An animated scene as a frame schedule: one image set per frame at start + f / fps, each the
    # same as a still rendered at that scene time; set-up time reported beside iteration time.
    "$bl" render data/cornell-box/cornell-animated.toml --mode raster --width 32 --height 32 --spp 2 \
        --set shadow_resolution=64 --frames 3 --fps 4 --scene-time 0.5 --out "$out/a.exr" | tee "$out/log.txt" \
        || fail "frames render failed"
    for f in 0 1 2; do
        for ext in exr png json; do [[ -s "$out/a.frame000$f.$ext" ]] || fail "missing a.frame000$f.$ext"; done
        grep -q "\"frame\": $f," "$out/a.frame000$f.json" || fail "frame $f: json lacks its frame number"
        grep -q '"setup_seconds": [0-9]' "$out/a.frame000$f.json" || fail "frame $f: json lacks setup_seconds"
    done
    [[ ! -e "$out/a.exr" && ! -e "$out/a.frame0003.exr" ]] || fail "files beyond the three frames"
    grep -q '"scene_time": 1,' "$out/a.frame0002.json" || fail "frame 2 should be at 0.5 + 2 / 4 = 1 s"
    grep -q "set-up" "$out/log.txt" || fail "set-up time not printed"
    "$bl" render data/cornell-box/cornell-animated.toml --mode raster --width 32 --height 32 --spp 2 \
        --set shadow_resolution=64 --scene-time 1 --out "$out/still.exr" >/dev/null || fail "still render failed"
    cmp -s "$out/a.frame0002.png" "$out/still.png" || fail "frame 2 differs from a still at scene time 1"
    cmp -s "$out/a.frame0000.png" "$out/a.frame0002.png" && fail "frames 0 and 2 are the same image"
    expected="--fps"
    expect_error "$bl" render data/cornell-box/cornell-animated.toml --mode raster --frames 2 --fps 0 --out "$out/x.exr"
    ;;
render_partial_budget)
    "$bl" render data/cornell-box/cornell.toml --mode raster --width 32 --height 32 --time 0.2 \
        --out "$out/t.exr" || fail "time budget render failed"
    [[ -s "$out/t.exr" ]] || fail "missing output"
    ;;
info)
    "$bl" info data/cornell-box/cornell.toml | tee "$out/info.txt" || fail "info failed"
    grep -q "triangles        32" "$out/info.txt" || fail "triangle count"
    grep -q "emissive meshes  1" "$out/info.txt" || fail "emissive count"
    ;;
modes)
    "$bl" modes | tee "$out/modes.txt" || fail "modes failed"
    grep -q "shadow_resolution = 1024 texels" "$out/modes.txt" || fail "parameter listing"
    ;;
plan)
    "$bl" plan data/cornell-box/cornell.toml --mode raster | tee "$out/plan.txt" || fail "plan failed"
    grep -q "skip  light shadow cubes: no point or spot lights  \[light-shadow-cubes: no-point-or-spot-lights\]" "$out/plan.txt" ||
        fail "plan reason and its code"
    "$bl" plan data/cornell-box/cornell.toml --mode multibounce --set bundles=imperfect | tee "$out/plan-set.txt" ||
        fail "plan --set failed"
    grep -q "\[surface-points: imperfect-bundles\]" "$out/plan-set.txt" || fail "plan of the --set settings"
    ;;
bad_scene)
    printf '[camera]\nresolution = [512, 0]\n' >"$out/bad.toml"
    expected="bad.toml:2: camera.resolution: value 0 outside [1, 16384]"
    expect_error "$bl" render "$out/bad.toml" --mode raster --out "$out/x.exr"
    ;;
missing_file)
    expected="nothere.toml: file not found"
    expect_error "$bl" render nothere.toml --mode raster --out "$out/x.exr"
    ;;
unknown_mode)
    expected="unknown mode 'rasterr' (available: "
    expect_error "$bl" render data/cornell-box/cornell.toml --mode rasterr --out "$out/x.exr"
    # the list names the real modes, whatever their order
    for m in raster reference skylight; do
        grep -qE "available: .*\b$m\b" "$out/stderr.txt" || fail "mode list lacks $m"
    done
    ;;
unknown_parameter)
    expected="mode raster: unknown parameter 'shadow_res'"
    expect_error "$bl" render data/cornell-box/cornell.toml --mode raster --set shadow_res=5 --out "$out/x.exr"
    ;;
bad_parameter_value)
    expected="mode raster: parameter 'shadow_resolution' = 5 outside [16, 8192]"
    expect_error "$bl" render data/cornell-box/cornell.toml --mode raster --set shadow_resolution=5 --out "$out/x.exr"
    ;;
bad_output_extension)
    expected="the output must be an .exr file"
    expect_error "$bl" render data/cornell-box/cornell.toml --mode raster --out "$out/x.png"
    ;;
absurd_resolution)
    expected="--width"
    expect_error "$bl" render data/cornell-box/cornell.toml --mode raster --width 100000000 --out "$out/x.exr"
    ;;
nan_vertex)
    printf 'v 0 0 0\nv 1 0 0\nv 0 nan 1\nf 1 2 3\n' >"$out/nan.obj"
    expected="nan.obj:3: value 'nan' is not finite"
    expect_error "$bl" info "$out/nan.obj"
    ;;
truncated_hdr)
    # stb's reader spun forever on a cut .hdr; ours names the file and what is missing, at once.
    needs_shared ../shared/data/envmap/classroom-sky.hdr
    head -c 200000 ../shared/data/envmap/classroom-sky.hdr >"$out/cut.hdr" || fail "no classroom-sky.hdr to cut"
    printf '[[mesh]]\nfile = "%s"\n[environment]\nfile = "cut.hdr"\n' "$PWD/data/analytic/meshes/floor.obj" \
        >"$out/env.toml"
    expected="cut.hdr: Radiance HDR: truncated: the file ends at byte 200000 inside scanline"
    expect_error timeout 60 "$bl" info "$out/env.toml"
    expect_error timeout 60 "$bl" render "$out/env.toml" --mode raster --width 8 --height 8 --out "$out/x.exr"
    ;;
unrepresentable_intensity)
    # Finite as a double, infinite as a float: every mode rendered it black.
    sed 's/^intensity = .*/intensity = [1e39, 1, 1]/' data/analytic/point-over-plane.toml >"$out/p.toml"
    cp -r data/analytic/meshes "$out/"
    expected="p.toml:21: light[0].intensity: value 1e+39 is beyond the largest 32-bit float"
    expect_error "$bl" render "$out/p.toml" --mode raster --width 8 --height 8 --out "$out/x.exr"
    ;;
lost_work)
    # 3e38 W/sr (a float) 0.1 over the plane: below the light the radiance, 0.5 / pi * 3e38 / 0.01,
    # overflows to inf and every such sample is refused. With only that spot in view the render
    # holds no sample at all: refused, nothing written, the checkpoint already written kept.
    cp -r data/analytic/meshes "$out/"
    sed -e 's/^intensity = .*/intensity = [3e38, 3e38, 3e38]/' -e 's/^position  = .*/position = [0.0, 0.1, 0.0]/' \
        -e 's/^position   = .*/position   = [0.0, 0.5, 0.0]/' -e 's/^up         = .*/up = [0.0, 0.0, 1.0]/' \
        data/analytic/point-over-plane.toml >"$out/hot.toml"
    sed 's/^fov        = .*/fov = 10.0/' "$out/hot.toml" >"$out/all.toml"
    sed 's/^fov        = .*/fov = 120.0/' "$out/hot.toml" >"$out/some.toml"
    expected="raster: every one of its 128 samples was lost"
    expect_error "$bl" render "$out/all.toml" --mode raster --width 8 --height 8 --spp 2 --checkpoint 1 \
        --set shadow_resolution=64 --out "$out/all.exr"
    grep -qF "raster: 128 samples of 128 refused as NaN or infinite (non_finite_samples)" "$out/stderr.txt" ||
        fail "no warning with the count"
    [[ ! -e "$out/all.exr" ]] || fail "a meaningless image was written"
    [[ -s "$out/all.1.exr" ]] || fail "the checkpoint written before the refusal is gone"
    # Part of the view overflows: a warning with the count, exit 0, the image written.
    "$bl" render "$out/some.toml" --mode raster --width 8 --height 8 --set shadow_resolution=64 \
        --out "$out/some.exr" 2>"$out/some.txt" || { cat "$out/some.txt"; fail "partly lost render refused"; }
    cat "$out/some.txt"
    grep -qE "raster: [0-9]+ samples of 64 refused as NaN or infinite" "$out/some.txt" || fail "no lost-work warning"
    [[ -s "$out/some.exr" ]] || fail "missing output"
    ;;
imported_scenes)
    # Mitsuba 3 and glTF scenes through every command a TOML scene goes through (info, plan, render
    # in the reference and a GPU mode, compare, run), each against its hand-written TOML twin: the
    # reference path tracer gives the same image from either with the same seed (float rounding of
    # the importers' transforms, bounded as in tests/modes/reference/MitsubaTwinTest.cpp: relMSE 1e-5).
    # The glTF camera's field of view is vertical (yfov), the TOML twin's horizontal: they agree at
    # the twin's square aspect only, so that pair renders square. The Mitsuba files are ../shared's:
    # without it only the glTF pair runs (and says so).
    pairs=("data/cornell-box/cornell-point.gltf data/cornell-box/cornell-point.toml 16")
    for xml in "cornell-box/mitsuba-cbox/cbox-rgb.xml data/external/mitsuba-cbox.toml" \
               "glossy/veach-mis/veach_mis.xml data/external/veach-mis.toml"; do
        read -r file twin <<<"$xml"
        if [[ -e ../shared/data/$file ]]; then
            pairs+=("../shared/data/$file $twin 24")
        else
            echo "note: ../shared/data/$file is not here; its pair is left out"
        fi
    done
    scenes=""
    for pair in "${pairs[@]}"; do
        read -r scene twin width <<<"$pair"
        name=$(basename "$scene")
        "$bl" info "$scene" >"$out/$name.info" || fail "info $scene"
        "$bl" info "$twin" >"$out/$name.twin.info" || fail "info $twin"
        diff <(grep -E "^(triangles|point lights|emissive meshes) " "$out/$name.info") \
             <(grep -E "^(triangles|point lights|emissive meshes) " "$out/$name.twin.info") || fail "$scene: not its twin's scene"
        grep -q "^mapped " "$out/$name.info" || fail "$scene: info states no mapping"
        "$bl" plan "$scene" --mode multibounce >"$out/$name.plan" || fail "plan $scene"
        grep -q "run " "$out/$name.plan" || fail "$scene: empty plan"
        for s in "$scene" "$twin"; do
            "$bl" render "$s" --mode reference --width "$width" --height 16 --spp 4 --seed 3 --out "$out/$(basename "$s").exr" \
                >/dev/null || fail "reference render of $s"
        done
        "$bl" compare "$out/$name.exr" "$out/$(basename "$twin").exr" --metric relmse --json >"$out/$name.cmp" ||
            fail "compare $scene"
        cat "$out/$name.cmp"
        /usr/bin/python3 -c "import json, sys; v = json.load(open(sys.argv[1]))['relmse']; sys.exit(0 if v < 1e-5 else 1)" \
            "$out/$name.cmp" || fail "$scene: its reference image is not its twin's"
        "$bl" render "$scene" --mode multibounce --width 24 --height 16 --iterations 2 --set bundle_count=4 \
            --set bundle_resolution=64 --out "$out/$name-mb.exr" >/dev/null || fail "multibounce render of $scene"
        scenes+=$(printf '[[scene]]\nfile = "%s"\nresolution = [16, 16]\n' "$PWD/$scene")
        scenes+=$'\n'
    done
    printf '[experiment]\nname = "imported"\niterations = 2\n[reference]\nspp = 4\n%s[[mode]]\nmode = "raster"\nsettings = { shadow_resolution = 64 }\n' \
        "$scenes" >"$out/imported.toml"
    "$bl" run "$out/imported.toml" --out "$out/results" >"$out/run.txt" 2>&1 || { cat "$out/run.txt"; fail "run"; }
    [[ $(tail -n +2 "$out/results/results.csv" | wc -l) -eq ${#pairs[@]} ]] || fail "run: not one result row per imported scene"
    ;;
run_lost_work)
    # The experiment runner applies the same verdict: the all-overflowing view fails its task (error.txt,
    # no result), an area light raster leaves out is a warning, and the run exits non-zero.
    cp -r data/analytic/meshes "$out/"
    sed -e 's/^intensity = .*/intensity = [3e38, 3e38, 3e38]/' -e 's/^position  = .*/position = [0.0, 0.1, 0.0]/' \
        -e 's/^position   = .*/position   = [0.0, 0.5, 0.0]/' -e 's/^up         = .*/up = [0.0, 0.0, 1.0]/' \
        -e 's/^fov        = .*/fov = 10.0/' data/analytic/point-over-plane.toml >"$out/all.toml"
    printf '[experiment]\nname = "lost"\niterations = 1\n[reference]\nenabled = false\n[[scene]]\nfile = "all.toml"\nresolution = [8, 8]\n[[scene]]\nfile = "%s"\nresolution = [8, 8]\n[[mode]]\nmode = "raster"\nsettings = { shadow_resolution = 64, emitter_points = 0 }\n' \
        "$PWD/data/cornell-box/cornell.toml" >"$out/lost.toml"
    "$bl" run "$out/lost.toml" --out "$out/results" >"$out/stdout.txt" 2>"$out/stderr.txt" && fail "run exit code 0"
    cat "$out/stderr.txt"
    grep -qF "raster: every one of its 64 samples was lost" "$out/stderr.txt" || fail "no refusal in the log"
    grep -qF "raster: the scene's area light is left out of the image" "$out/stderr.txt" || fail "no left-out warning"
    grep -qF "every one of its 64 samples was lost" "$out"/results/tasks/*-all-*/error.txt || fail "no error.txt"
    ls "$out"/results/tasks/*-all-*/result.csv 2>/dev/null && fail "a result row for a refused task"
    ls "$out"/results/tasks/*-cornell-*/result.csv >/dev/null || fail "the good task has no result"
    ;;
lost_vpls)
    # A spot aimed at the open sky over the plane: every VPL bidir traces escapes. Those are samples
    # of zero, not lost work (the true image is black), so the image is written; but that every one
    # of them carries no light is said with the count, not left to the JSON record.
    cp -r data/analytic/meshes "$out/"
    sed 's/^intensity = .*/intensity = [10, 10, 10]\ntype = "spot"\ndirection = [0, 1, 0]\ncone_angle = 30/' \
        data/analytic/point-over-plane.toml >"$out/up.toml"
    "$bl" render "$out/up.toml" --mode bidir --width 16 --height 16 --iterations 2 --out "$out/up.exr" \
        2>"$out/stderr.txt" || { cat "$out/stderr.txt"; fail "an image of zero samples was refused"; }
    grep -qF "bidir: all 42 VPLs carry no light" "$out/stderr.txt" || { cat "$out/stderr.txt"; fail "no warning with the count"; }
    [[ -e "$out/up.exr" ]] || fail "no image"
    ;;
lights_left_out)
    # An area-lit box in raster without emitter points: the area light lights nothing there, said
    # once at render time.
    "$bl" render data/cornell-box/cornell.toml --mode raster --width 8 --height 8 --set shadow_resolution=64 \
        --set emitter_points=0 --out "$out/r.exr" 2>"$out/stderr.txt" || fail "render failed"
    [[ $(grep -c "raster: the scene's area light is left out of the image" "$out/stderr.txt") -eq 1 ]] ||
        { cat "$out/stderr.txt"; fail "no single warning for the area light"; }
    "$bl" render data/cornell-box/cornell-point.toml --mode raster --width 8 --height 8 --set shadow_resolution=64 \
        --out "$out/p.exr" 2>"$out/point.txt" || fail "render failed"
    grep -q "left out" "$out/point.txt" && fail "a warning for a scene the mode renders whole"
    "$bl" render data/cornell-box/cornell.toml --mode raster --width 8 --height 8 --set shadow_resolution=64 \
        --set emitter_shadow_resolution=64 --out "$out/a.exr" 2>"$out/area.txt" || fail "render failed"
    grep -q "left out" "$out/area.txt" && fail "a warning for an area light raster renders (emitter points)"
    ;;
setting_trades)
    # A shadow cube too coarse for the box: said once at render time, with the setting that fixes it.
    "$bl" render data/cornell-box/cornell-point.toml --mode raster --width 8 --height 8 --set shadow_resolution=16 \
        --out "$out/r.exr" 2>"$out/stderr.txt" || fail "render failed"
    [[ $(grep -c "raster: the 16^2 shadow cube of light 0 misses .*fix: shadow_resolution=" "$out/stderr.txt") -eq 1 ]] ||
        { cat "$out/stderr.txt"; fail "no single warning for the coarse shadow cube"; }
    # plan shows the same check: a block a third of the Cornell box's short one on a floor ten times
    # the box's, so the floor sets the bounding sphere and a 16^2 bundle's pixel is wider than the
    # block (the walks, contact taps included, miss it: +4.2 %).
    cat >"$out/block.toml" <<EOF
[camera]
position = [148.0, 150.0, -20.0]
target = [148.0, 20.0, 144.0]
fov = 50.0
resolution = [16, 16]
[[material]]
name = "white"
albedo = [0.7, 0.7, 0.7]
[[mesh]]
file = "$PWD/data/stress/scenes/meshes/cornell-floor.obj"
material = "white"
scale = 10.0
translate = [-2500.0, 0.0, -2500.0]
[[mesh]]
file = "$PWD/data/stress/scenes/meshes/cornell-shortblock.obj"
material = "white"
scale = 0.3
translate = [100.0, 0.0, 100.0]
[[light]]
position = [160.0, 600.0, 0.0]
intensity = [100000.0, 100000.0, 100000.0]
EOF
    "$bl" plan "$out/block.toml" --mode multibounce --set bundle_resolution=16 >"$out/plan.txt" || fail "plan failed"
    grep -q "warn  multibounce: bundles of 16^2 pixels .*fix: bundle_resolution=" "$out/plan.txt" ||
        { cat "$out/plan.txt"; fail "plan lacks the bundle check"; }
    # The defaults on the Cornell box trade nothing worth a word.
    for m in raster multibounce bidir atlas; do
        "$bl" plan data/cornell-box/cornell-point.toml --mode $m >"$out/$m.txt" || fail "plan $m failed"
        grep -q "warn" "$out/$m.txt" && { cat "$out/$m.txt"; fail "a warning for $m at its defaults"; }
    done
    "$bl" plan data/cornell-box/cornell.toml --mode skylight >"$out/skylight.txt" || fail "plan skylight failed"
    grep -q "warn" "$out/skylight.txt" && { cat "$out/skylight.txt"; fail "a warning for skylight at its defaults"; }
    # bidir's VPL strategy with one bounce builds no bundle on a scene without environment: its
    # bundle_resolution trades nothing there (MIS, which builds them, is judged; over the bounding
    # sphere, since bidir fits its frames to the visible points by default).
    "$bl" plan "$out/block.toml" --mode bidir --set strategy=vpl --set bounces=1 --set fit=scene \
        --set bundle_resolution=16 >"$out/bidir-vpl.txt" || fail "plan bidir vpl failed"
    grep -q "bundles of 16^2" "$out/bidir-vpl.txt" && { cat "$out/bidir-vpl.txt"; fail "a bundle warning where bidir builds none"; }
    "$bl" plan "$out/block.toml" --mode bidir --set strategy=mis --set bounces=1 --set fit=scene \
        --set bundle_resolution=16 >"$out/bidir-mis.txt" || fail "plan bidir mis failed"
    grep -q "warn  bidir: bundles of 16^2" "$out/bidir-mis.txt" || { cat "$out/bidir-mis.txt"; fail "no bundle warning for MIS"; }
    # The runner checks once per scene, resolution, mode and settings, not once per seed: three
    # seeds say the warning once and point the other two tasks to it.
    cat >"$out/trades.toml" <<EOF
[experiment]
name = "trades"
seeds = [0, 1, 2]
iterations = 1
[[scene]]
name = "box"
file = "$PWD/data/cornell-box/cornell-point.toml"
resolution = [8, 8]
[[mode]]
mode = "raster"
settings = { shadow_resolution = 16 }
EOF
    "$bl" run "$out/trades.toml" --out "$out/trades" 2>"$out/run-stderr.txt" >/dev/null || { cat "$out/run-stderr.txt"; fail "run failed"; }
    [[ $(grep -c "raster: the 16^2 shadow cube of light 0 misses" "$out/run-stderr.txt") -eq 1 ]] ||
        { cat "$out/run-stderr.txt"; fail "the trade warning not said exactly once over three seeds"; }
    [[ $(grep -c "setting warning(s) as for task" "$out/run-stderr.txt") -eq 2 ]] ||
        { cat "$out/run-stderr.txt"; fail "the other seeds do not point to the first task's warning"; }
    ;;
validation_clean)
    needs_shared ../shared/data/sponza-dabrovic/sponza.obj
    "$bl" render data/external/sponza-point.toml --mode raster --width 96 --height 64 --validation \
        --set shadow_resolution=128 --out "$out/s.exr" 2>"$out/stderr.txt" || { cat "$out/stderr.txt"; fail "render failed"; }
    if grep -q "validation" "$out/stderr.txt"; then cat "$out/stderr.txt"; fail "validation messages"; fi
    ;;
atlas_report)
    "$bl" atlas data/cornell-box/cornell.toml --size 256 --out "$out/atlas.png" --report "$out/atlas.json" \
        || fail "atlas failed"
    [[ -s "$out/atlas.png" ]] || fail "no chart image"
    for key in utilization charts mean_stretch max_stretch flipped_triangles overlapping_texels \
               uncovered_triangles seconds; do
        grep -q "\"$key\": " "$out/atlas.json" || fail "report lacks $key"
    done
    grep -q '"charts": 16' "$out/atlas.json" || fail "the Cornell box should give 16 charts"
    grep -q '"overlapping_texels": 0' "$out/atlas.json" || fail "overlapping texels"
    # A fixed density spills onto pages; one no page or memory can hold is a clear error.
    "$bl" atlas data/cornell-box/cornell.toml --texels-per-unit 0.4 --page-size 256 --report "$out/pages.json" \
        || fail "paged atlas failed"
    grep -q '"pages": [2-9]' "$out/pages.json" || fail "0.4 texels per unit should need several 256^2 pages"
    expected="more than the 256 M an atlas may have"
    expect_error "$bl" atlas data/cornell-box/cornell.toml --texels-per-unit 200
    expected="larger than a 256^2 page"
    expect_error "$bl" atlas data/cornell-box/cornell.toml --texels-per-unit 0.5 --page-size 256
    # NaN passes CLI11's Range; every floating-point option refuses it by name.
    expected="--cone: value 'nan' is not finite"
    expect_error "$bl" atlas data/cornell-box/cornell.toml --cone nan
    expected="--texels-per-unit: value 'inf' is not finite"
    expect_error "$bl" atlas data/cornell-box/cornell.toml --texels-per-unit inf
    ;;
bench_texels)
    # The atlas judged over every texel against the path tracer baking the same texels: the table,
    # the CSV and the texel sides as EXR layers; an atlas whose texels were read back on the wrong
    # side or index would sit at relMSE ~1 against the bake, not near the baker's own noise.
    "$bl" bench texels data/cornell-box/cornell.toml --width 16 --height 16 --set atlas_resolution=32 \
        --set bundle_resolution=64 --directions 8 --directions 32 --bake-spp 4 --reference-spp 64 --image-spp 4 \
        --image-reference-spp 16 --csv "$out/t.csv" --exr "$out/t.exr" >"$out/log.txt" 2>&1 || { cat "$out/log.txt"; fail "bench texels failed"; }
    grep -q "^| atlas | 32 directions |" "$out/log.txt" || { cat "$out/log.txt"; fail "no atlas row"; }
    grep -q "charts' border texels" "$out/log.txt" || fail "no border/interior split"
    awk -F, '$1 == "atlas" && $2 == 32 { ok = ($4 > 0 && $4 < 0.2) } END { exit !ok }' "$out/t.csv" ||
        { cat "$out/t.csv"; fail "atlas texel relMSE at 32 directions not in (0, 0.2)"; }
    awk -F, '$1 == "baker" { ok = ($4 > 0 && $4 < 0.2) } END { exit !ok }' "$out/t.csv" ||
        { cat "$out/t.csv"; fail "baker texel relMSE not in (0, 0.2)"; }
    "$bl" stats "$out/t.exr" >"$out/stats.txt" || fail "stats failed"
    for layer in atlas.front atlas.back reference.front reference.back; do
        grep -q "^$layer 32x32 " "$out/stats.txt" || { cat "$out/stats.txt"; fail "no layer $layer"; }
    done
    expected="is animated; the texel-space reference bakes one moment"
    expect_error "$bl" bench texels data/cornell-box/cornell-animated.toml
    # An output that cannot be written is refused before any work, not after it.
    expected="--csv $out/missing/t.csv: the directory $out/missing does not exist"
    expect_error "$bl" bench texels data/cornell-box/cornell.toml --csv "$out/missing/t.csv"
    ;;
*)
    fail "unknown case $case_name"
    ;;
esac
echo "PASS: $case_name"
