#!/usr/bin/env bash
# Issue 13's "works on every scene": renders every scene toml of data/ and ../shared/data with mode
# multibounce, perfect and imperfect bundles, at a tiny resolution and few iterations; checks the exit
# code, the JSON record's non-finite sample count and `bundlelab stats` (no NaN/Inf in any layer),
# and prints one table row per run with the wall time and the passes' ms.
# Usage: experiments/multibounce/every-scene.sh BUILD_DIR [OUT_DIR] [extra --set key=value ...]
# DEFAULTS=1 in the environment keeps the mode's default bundle settings (64 bundles of 128^2, 16384
# points) instead of the small ones (8 bundles of 64^2, 4096 points).
set -uo pipefail
build=${1:?build dir}
out=${2:-/tmp/multibounce-every-scene}
shift $(( $# >= 2 ? 2 : 1 ))
root=$(cd "$(dirname "$0")/../.." && pwd)
bin="$build/bundlelab"
mkdir -p "$out"
scenes=$(cd "$root" && { find data -name '*.toml'; find ../shared/data -name '*.toml' 2>/dev/null; } | sort)
failures=0
printf '| scene | bundles | exit | non-finite | wall s | build ms | paths ms | note |\n|---|---|---|---|---|---|---|---|\n'
for scene in $scenes; do
    for kind in perfect imperfect; do
        name=$(echo "$scene" | tr '/.' '__')-$kind
        log="$out/$name.log"
        small=(--set bundle_count=8 --set bundle_resolution=64 --set points=4096)
        [[ "${DEFAULTS:-0}" == 1 ]] && small=()
        (cd "$root" && timeout 300 "$bin" render "$scene" -m multibounce --width 32 --height 24 --iterations 2 \
            "${small[@]}" --set bundles=$kind "$@" -o "$out/$name.exr") >"$log" 2>&1
        rc=$?
        nonfinite=-; wall=-; build_ms=-; paths_ms=-; note=""
        if [[ $rc -eq 0 ]]; then
            nonfinite=$(/usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['non_finite_samples'])" "$out/$name.json")
            wall=$(/usr/bin/python3 -c "import json,sys; print('%.2f' % json.load(open(sys.argv[1]))['wall_seconds'])" "$out/$name.json")
            build_ms=$(awk '/^bundle build/ {print $3}' "$log")
            paths_ms=$(awk '/^paths/ {print $2}' "$log")
            stats=$("$bin" stats "$out/$name.exr" 2>&1)
            if echo "$stats" | grep -Eiq 'nan|inf|non-finite [1-9]'; then
                note="stats: $(echo "$stats" | grep -Ei 'nan|inf|non-finite' | head -1)"
                failures=$((failures + 1))
            fi
            [[ "$nonfinite" != 0 ]] && failures=$((failures + 1))
        else
            note=$(grep -i 'error' "$log" | head -1 | cut -c1-160)
            failures=$((failures + 1))
        fi
        printf '| %s | %s | %s | %s | %s | %s | %s | %s |\n' "$scene" "$kind" "$rc" "$nonfinite" "$wall" "$build_ms" "$paths_ms" "$note"
    done
done
echo "failures: $failures"
[[ $failures -eq 0 ]]
