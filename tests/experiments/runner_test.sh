#!/usr/bin/env bash
# runner_test.sh CASE BUNDLELAB OUTDIR: end-to-end tests of `bundlelab run` and `bundlelab report`.
set -uo pipefail
case_name=$1
bl=$2
out=$3/$case_name
config=tests/experiments/tiny.toml
rm -rf "$out" && mkdir -p "$out"
fail() { echo "FAIL: $*"; exit 1; }
count_done() { ls "$out"/results/tasks/*/done.json 2>/dev/null | wc -l; }

case "$case_name" in
resume)
    "$bl" run "$config" --out "$out/results" >"$out/first.txt" 2>&1 || { cat "$out/first.txt"; fail "first run"; }
    [[ $(count_done) -eq 8 ]] || fail "expected 8 finished tasks, got $(count_done)"
    [[ $(wc -l <"$out/results/results.csv") -eq 9 ]] || fail "results.csv should have 8 rows"
    for f in task.json metrics.csv passes.csv environment.json final.exr final.png final.pfm iter-1.exr; do
        [[ -s "$out/results/tasks/0000-cornell-pt-s0/$f" ]] || fail "missing $f"
    done
    grep -q "^4," "$out/results/tasks/0000-cornell-pt-s0/metrics.csv" || fail "no checkpoint at iteration 4"
    # A second run runs nothing again: every task's files stay as they were (how long it takes is
    # the benchmarks' business, not a pass/fail test's).
    stamps() { stat -c '%n %Y' "$out"/results/tasks/*/done.json "$out"/results/tasks/*/final.exr; }
    stamps >"$out/stamps-before.txt"
    sleep 1
    "$bl" run "$config" --out "$out/results" >"$out/second.txt" 2>&1 || fail "second run"
    grep -q "8 already finished" "$out/second.txt" || { cat "$out/second.txt"; fail "finished tasks not skipped"; }
    stamps | diff "$out/stamps-before.txt" - || fail "the second run rewrote finished tasks"
    # A task killed mid-way (no done.json, a half-written file) is redone; nothing else is.
    victim="$out/results/tasks/0003-cornell-raster-shadow_resolution_64-s1"
    rm "$victim/done.json"
    echo "garbage" >"$victim/final.exr"
    before=$(stat -c %Y "$out/results/tasks/0000-cornell-pt-s0/done.json")
    sleep 1
    "$bl" run "$config" --out "$out/results" >"$out/third.txt" 2>&1 || fail "third run"
    grep -q "7 already finished" "$out/third.txt" || { cat "$out/third.txt"; fail "expected exactly one task redone"; }
    [[ -s "$victim/done.json" ]] || fail "killed task not redone"
    [[ $(stat -c %Y "$out/results/tasks/0000-cornell-pt-s0/done.json") -eq $before ]] || fail "a finished task ran again"
    [[ $(wc -l <"$out/results/results.csv") -eq 9 ]] || fail "results.csv lost rows"
    ;;
frames)
    # An animated scene as a frame schedule: every frame rendered and recorded with its scene time,
    # set-up and iteration seconds; frame 0 stays the judged one.
    config=tests/experiments/frames.toml
    "$bl" run "$config" --out "$out/results" >"$out/log.txt" 2>&1 || { cat "$out/log.txt"; fail "run"; }
    task="$out/results/tasks/0000-cornell-raster-s0"
    for f in 0 1 2; do [[ -s "$task/final.frame000$f.exr" ]] || fail "missing frame $f"; done
    [[ ! -e "$task/final.frame0003.exr" ]] || fail "a fourth frame"
    [[ $(wc -l <"$task/frames.csv") -eq 4 ]] || { cat "$task/frames.csv"; fail "frames.csv should have 3 rows"; }
    grep -q "^2,1,2," "$task/frames.csv" || { cat "$task/frames.csv"; fail "frame 2 at scene time 2 / 2 fps = 1 s, 2 iterations"; }
    head -1 "$out/results/results.csv" | grep -q ",wall_seconds,setup_seconds," || fail "results.csv lacks setup_seconds"
    # Every row's set-up seconds is a positive number (column 10).
    awk -F, 'NR > 1 && !($10 > 0) { bad = 1 } END { exit bad }' "$out/results/results.csv" || fail "set-up time missing"
    grep -q '"setup_seconds": ' "$task/done.json" || fail "done.json lacks setup_seconds"
    # Frames differ (the camera dollies in); two renders of one frame do not.
    cmp -s "$task/final.frame0000.exr" "$task/final.frame0002.exr" && fail "frames 0 and 2 are the same image"
    cmp -s "$task/final.frame0000.exr" "$task/final.exr" || fail "final.exr is not frame 0"
    ;;
slices)
    "$bl" run "$config" --out "$out/results" --task-index 1 --task-count 2 >"$out/log.txt" 2>&1 || fail "slice run"
    [[ $(count_done) -eq 4 ]] || fail "slice 1 of 2 should run 4 tasks, ran $(count_done)"
    [[ -s "$out/results/tasks/0001-cornell-pt-s1/done.json" ]] || fail "odd task missing"
    [[ ! -e "$out/results/tasks/0000-cornell-pt-s0/done.json" ]] || fail "even task ran"
    "$bl" run "$config" --out "$out/results" --task-index 0 --task-count 2 -j 2 >"$out/log2.txt" 2>&1 || fail "slice 0"
    [[ $(count_done) -eq 8 ]] || fail "both slices should give 8 tasks"
    ;;
bad_config)
    printf '[experiment]\nname = "x"\n[[scene]]\nfile = "%s/data/cornell-box/cornell.toml"\n[[mode]]\nmode = "raster"\ngrid = { shadow_resolution = [5] }\n' "$PWD" >"$out/bad.toml"
    "$bl" run "$out/bad.toml" --out "$out/results" 2>"$out/err.txt" && fail "bad config accepted"
    grep -q "bad.toml:7: mode 'raster' grid: parameter 'shadow_resolution' = 5 outside" "$out/err.txt" || { cat "$out/err.txt"; fail "message"; }
    [[ ! -d "$out/results/tasks" ]] || fail "tasks started despite the bad config"
    ;;
report_browser)
    "$bl" run "$config" --out "$out/results" >"$out/run.txt" 2>&1 || { cat "$out/run.txt"; fail "run"; }
    "$bl" report "$out/results" || fail "report"
    for f in report.html report.md plots/cornell-relmse-vs-time.png plots/cornell-relmse-vs-time.svg plots/passes.png; do
        [[ -s "$out/results/$f" ]] || fail "missing $f"
    done
    chrome=$(command -v chromium || true)
    [[ -n "$chrome" ]] || fail "chromium is not installed (scripts/install-deps.sh installs it)"
    flags=(--headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking
           --disable-component-update --disable-sync --user-data-dir="$out/profile" --virtual-time-budget=5000)
    "$chrome" "${flags[@]}" --dump-dom "file://$out/results/report.html" >"$out/dom.html" 2>"$out/chrome.log"
    grep -q 'id="bl-status" data-status="ok"' "$out/dom.html" || { grep -o 'bl-status[^<]*' "$out/dom.html"; fail "viewer did not load without errors"; }
    grep -q "images loaded" "$out/dom.html" || fail "viewer shows no images"
    "$chrome" "${flags[@]}" --window-size=1400,2400 --screenshot="$out/screenshot.png" "file://$out/results/report.html" 2>>"$out/chrome.log"
    [[ -s "$out/screenshot.png" ]] || fail "no screenshot"
    /usr/bin/python3 - "$out/screenshot.png" <<'PY' || fail "screenshot is blank"
import sys
import matplotlib.image as mpimg
img = mpimg.imread(sys.argv[1])
# A page showing plots and the viewer's canvas has many distinct colours; a blank page has one.
colours = len({tuple((px * 255).astype(int)) for px in img[::7, ::7, :3].reshape(-1, 3)})
print("distinct colours:", colours)
sys.exit(0 if colours > 200 else 1)
PY
    echo "screenshot: $out/screenshot.png"
    ;;
suite_summary)
    # experiments/suite/summary.py on a made-up results directory whose figures are known: the
    # path tracer's relMSE = the reference's noise 1e-4 + its own 1e-4 * 1024 / 2048 spp; atlas
    # 1.1e-3, of which 1e-3 its own. Measured ratio 1.1e-3 / 1.5e-4 = 7.33x; noise-corrected
    # 1e-3 / 5e-5 = 20x (22x if the noise were not taken off, 6.67x against the path tracer's
    # measured relMSE less the noise read as 1.5e-4). Raster is judged against another reference
    # (direct light, noise 1e-5, whose JSON says 4096 spp where the config says 1024), so against
    # path-tracer-2 (its own 1e-5 * 4096 / 4096 = 1e-5, measured 2e-5): 3.5e-5 / 1e-5 = 3.5x,
    # 4.5e-5 / 2e-5 = 2.25x measured (14x if the config's 1024 were read; against the full-GI
    # path tracer 0.7x).
    r="$out/results"
    mkdir -p "$r/tasks/pt" "$r/tasks/atlas" "$r/tasks/pt2" "$r/tasks/raster"
    printf '[reference]\nspp = 1024\n' >"$r/experiment.toml"
    for t in pt atlas pt2 raster; do
        printf 'iteration,wall_seconds,relmse\n1,0.5,0.5\n2,1.0,0.05\n' >"$r/tasks/$t/metrics.csv"
    done
    for t in pt atlas; do echo "../../references/box-full.exr" >"$r/tasks/$t/reference.txt"; done
    for t in pt2 raster; do echo "../../references/box-direct.exr" >"$r/tasks/$t/reference.txt"; done
    mkdir -p "$r/references" && echo '{"scene": "box", "spp": 4096, "noise_relmse": 1e-5}' >"$r/references/box-direct.json"
    {
        echo "scene,mode,label,seed,iterations,wall_seconds,relmse,mean_ratio_r,mean_ratio_g,mean_ratio_b,reference_noise_relmse,dir"
        echo "box,reference,path-tracer,0,2048,10,1.5e-4,1,1,1,1e-4,tasks/pt"
        echo "box,reference,path-tracer,1,2048,10,1.5e-4,1,1,1,1e-4,tasks/pt"
        echo "box,atlas,atlas,0,40,10,1.1e-3,1,1,1,1e-4,tasks/atlas"
        echo "box,atlas,atlas,1,40,10,1.1e-3,1,1,1,1e-4,tasks/atlas"
        echo "box,reference,path-tracer-2,0,4096,10,2e-5,1,1,1,1e-5,tasks/pt2"
        echo "box,raster,raster,0,300,10,4.5e-5,1,1,1,1e-5,tasks/raster"
    } >"$r/results.csv"
    /usr/bin/python3 experiments/suite/summary.py "$r" >"$out/report.md" || fail "summary.py failed"
    grep -q '^| box | atlas | 40 | 0.0011 | 1 | — | — | .* | path-tracer | 7.33x | 20x |$' "$out/report.md" ||
        { cat "$out/report.md"; fail "atlas row: expected measured 7.33x, noise-corrected 20x"; }
    grep -q '^| box | raster | 300 | 4.5e-05 | 1 | — | — | .* | path-tracer-2 | 2.25x | 3.5x |$' "$out/report.md" ||
        { cat "$out/report.md"; fail "raster row: expected 2.25x and 3.5x against path-tracer-2 (4096 spp from its JSON)"; }
    grep -q '^| box | path-tracer-2 | 1e-05 | 1e-05 | 1e-05 |$' "$out/report.md" ||
        { cat "$out/report.md"; fail "path-tracer-2 check row: noise, predicted and measured 1e-5"; }
    grep -q '^| box | path-tracer | 0.0001 | 5e-05 | 5e-05 |$' "$out/report.md" ||
        { cat "$out/report.md"; fail "path tracer check row: noise 1e-4, predicted and measured 5e-5"; }
    ;;
*)
    fail "unknown case $case_name"
    ;;
esac
echo "PASS: $case_name"
