#!/usr/bin/env bash
# view_test.sh CASE BUNDLELAB OUTDIR: `bundlelab view` end to end, headless under Xvfb (xvfb-run
# starts one on a free display) with lavapipe and the validation layers on: any validation error,
# an object still alive when the window closes included, fails the run (exit 3).
set -uo pipefail
case_name=$1
bl=$2
out=$3/$case_name
rm -rf "$out" && mkdir -p "$out"
fail() { echo "FAIL: $*"; exit 1; }
[[ "$case_name" == no_display ]] || command -v xvfb-run >/dev/null ||
    { echo "SKIP: xvfb-run not installed (Debian: xvfb; scripts/install-deps.sh installs it)"; exit 77; }
view() { xvfb-run -a -s "-screen 0 640x480x24" "$bl" view "$@"; }
scene=data/cornell-box/cornell-point.toml
# scene_with_printed_camera LOG N SCENE OUT: SCENE with its [camera] block replaced by the N-th one
# the viewer printed (key P) into LOG, mesh paths made absolute.
scene_with_printed_camera() {
    awk -v n="$2" '/^\[camera\]/ { k++ } k == n && /^(\[camera\]|position|target|up|fov|fov_axis|resolution)/' "$1" >"$4.camera"
    sed '/^\[camera\]/,/^$/d' "$3" >"$4.body"
    { cat "$4.camera"; echo; cat "$4.body"; } | sed "s#\"meshes/#\"$(pwd)/$(dirname "$3")/meshes/#" >"$4"
}

case "$case_name" in
no_display)
    env -u DISPLAY -u WAYLAND_DISPLAY "$bl" view "$scene" --mode raster >"$out/log.txt" 2>&1 && fail "view ran without a display"
    cat "$out/log.txt"
    grep -q "bundlelab view needs a display" "$out/log.txt" || fail "no clear message"
    ;;
still_equals_render)
    # A still frame after N iterations is render's image for the same camera, seed and iterations,
    # to the bit, in a progressive mode and a real-time one.
    printf 'iterate 3\nscreenshot %s\n' "$out/still.exr" >"$out/still.txt"
    for mode in multibounce bidir; do
        args=(--width 48 --height 40 --seed 7 --set bundle_resolution=64)
        view "$scene" --mode $mode "${args[@]}" --script "$out/still.txt" --validation >"$out/$mode.txt" 2>&1 ||
            { cat "$out/$mode.txt"; fail "view $mode"; }
        "$bl" render "$scene" --mode $mode "${args[@]}" --iterations 3 --out "$out/render.exr" >/dev/null || fail "render $mode"
        cmp "$out/still.exr" "$out/render.exr" || fail "$mode: the viewer's still frame differs from render's"
        [[ -s "$out/still.view.png" ]] || fail "$mode: no picture of the window"
    done
    ;;
camera_path)
    # A scripted camera path: a pose, an orbit drag and a wheel step each restart the estimate at a
    # new camera; the pose printed with P is the scripted one, in the scene file's [camera] form,
    # and rendering that block gives the viewer's image.
    cat >"$out/path.txt" <<SCRIPT
pose 278 273 -700 278 273 0
iterate 2
screenshot $out/posed.exr
key P
drag 40 -10
scroll 1
iterate 2
screenshot $out/moved.exr
key P
key C
key L
key O
SCRIPT
    view "$scene" --mode raster --width 40 --height 40 --script "$out/path.txt" --validation >"$out/log.txt" 2>&1 ||
        { cat "$out/log.txt"; fail "view"; }
    grep -q "^position   = \[278, 273, -700\]" "$out/log.txt" || { cat "$out/log.txt"; fail "P did not print the scripted pose"; }
    [[ $(grep -c "^\[camera\]" "$out/log.txt") -eq 2 ]] || fail "expected two [camera] blocks"
    ! cmp -s "$out/posed.exr" "$out/moved.exr" || fail "the drag and the wheel did not move the camera"
    # The second block, pasted into the scene file, renders the viewer's moved image.
    scene_with_printed_camera "$out/log.txt" 2 "$scene" "$out/moved-scene.toml"
    "$bl" render "$out/moved-scene.toml" --mode raster --iterations 2 --out "$out/rendered.exr" >/dev/null ||
        { cat "$out/moved-scene.toml"; fail "render of the printed camera"; }
    "$bl" compare "$out/rendered.exr" "$out/moved.exr" | tee "$out/compare.txt"
    awk '$1 == "relmse" && $2 > 1e-8 { bad = 1 } END { exit bad }' "$out/compare.txt" || fail "the printed camera renders another image"
    ;;
atlas_keeps_solution)
    # Atlas's exchange does not depend on the camera: a camera move re-resolves the same estimate,
    # which goes on refining; it equals render's image from the new camera after as many iterations.
    a=(--width 40 --height 40 --seed 5 --set atlas_resolution=64 --set bundle_resolution=64 --set view_samples=2)
    printf 'iterate 3\ndrag 60 0\nframes 1\nkey P\nscreenshot %s\n' "$out/moved.exr" >"$out/path.txt"
    view data/cornell-box/cornell.toml --mode atlas "${a[@]}" --script "$out/path.txt" --validation >"$out/log.txt" 2>&1 ||
        { cat "$out/log.txt"; fail "view"; }
    grep -q '"iterations": 4' "$out/moved.json" || fail "the move restarted the estimate"
    scene_with_printed_camera "$out/log.txt" 1 data/cornell-box/cornell.toml "$out/moved-scene.toml"
    "$bl" render "$out/moved-scene.toml" --mode atlas "${a[@]}" --iterations 4 --out "$out/rendered.exr" >/dev/null ||
        fail "render of the printed camera"
    "$bl" compare "$out/rendered.exr" "$out/moved.exr" | tee "$out/compare.txt"
    # Equal but for the order of float atomic adds in the exchange (relMSE ~1e-19 between two runs).
    awk '$1 == "relmse" && $2 > 1e-12 { bad = 1 } END { exit bad }' "$out/compare.txt" || fail "not render's image"
    ;;
live_setting)
    # A bad value from the keys or a script is refused with the CLI's own text; a good one restarts
    # the estimate with it.
    printf 'iterate 1\nset shadow_resolution=abc\nset shadow_resolution=128\niterate 1\nscreenshot %s\n' "$out/set.exr" >"$out/set.txt"
    view "$scene" --mode raster --width 32 --height 32 --script "$out/set.txt" --validation >"$out/log.txt" 2>&1 &&
        fail "a script with a refused setting exited 0"
    "$bl" render "$scene" --mode raster --set shadow_resolution=abc --out "$out/x.exr" 2>"$out/cli.txt" && fail "render took abc"
    grep -qF "$(cat "$out/cli.txt")" "$out/log.txt" || { cat "$out/log.txt" "$out/cli.txt"; fail "not the CLI's error text"; }
    grep -q '"shadow_resolution": "128"' "$out/set.json" || fail "the good value was not applied"
    ;;
bad_script)
    printf 'iterate 1\npose 1 2 three 4 5 6\n' >"$out/bad.txt"
    view "$scene" --mode raster --width 32 --height 32 --script "$out/bad.txt" >"$out/log.txt" 2>&1 && fail "bad script accepted"
    grep -qF "$out/bad.txt:2: pose: 'three' is not a finite number" "$out/log.txt" || { cat "$out/log.txt"; fail "no file:line"; }
    ;;
play)
    # A keyframed scene plays: each shown frame a new estimate at its scene time, logged.
    printf 'frames 3\n' >"$out/play.txt"
    view data/cornell-box/cornell-animated.toml --mode raster --width 32 --height 32 --play --fps 4 \
        --frame-iterations 2 --script "$out/play.txt" --frame-log "$out/frames.csv" --validation >"$out/log.txt" 2>&1 ||
        { cat "$out/log.txt"; fail "view --play"; }
    cat "$out/frames.csv"
    grep -q "^2,0.5,2," "$out/frames.csv" || fail "frame 2 at scene time 0.5 s (4 fps) with 2 iterations"
    ;;
*)
    fail "unknown case $case_name"
    ;;
esac
echo "PASS"
