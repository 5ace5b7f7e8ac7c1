#!/usr/bin/env bash
# record-cornell-animated.sh [OUTDIR] [BUNDLELAB]: the animated Cornell box (camera dolly, turning
# block) played in `bundlelab view` with bidir's real-time settings (temporal interleaving on, so
# the caches are reprojected as the camera moves), headless under xvfb-run: 24 frames at 12 fps of
# scene time, 4 iterations each, each frame's window (overlay included) and estimate as PNG, and
# every frame's times in frames.csv. The committed run is experiments/viewer/cornell-animated/.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
out=${1:-$root/experiments/viewer/cornell-animated}
bl=${2:-$root/build/bundlelab}
mkdir -p "$out"
script=$(mktemp)
for f in $(seq 0 23); do
    printf 'frames 1\nscreenshot %s/frame%02d.exr\n' "$out" "$f" >>"$script"
done
cd "$root"
xvfb-run -a -s "-screen 0 640x480x24" "$bl" view data/cornell-box/cornell-animated.toml --mode bidir \
    --set temporal=on --width 160 --height 160 --play --fps 12 --frame-iterations 4 --script "$script" \
    --frame-log "$out/frames.csv" --validation | grep -v "^wrote "
rm -f "$script" "$out"/frame*.exr "$out"/frame*.json "$out"/frame??.png # the window pictures stay
# The frame log: one row per refresh; the median iteration time over the played frames.
/usr/bin/python3 - "$out/frames.csv" <<'PY'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
per_iteration = [float(r["iterate_ms"]) / int(r["iterations"]) for r in rows[1:]]  # frame 0 compiles shaders
shown = [float(r["iterate_ms"]) + float(r["resolve_ms"]) + float(r["present_ms"]) for r in rows[1:]]
print(f"{len(rows)} frames; median {statistics.median(per_iteration):.1f} ms per bidir iteration, "
      f"median {statistics.median(shown):.1f} ms per shown frame (4 iterations, resolve, present)")
PY
