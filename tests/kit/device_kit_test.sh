#!/usr/bin/env bash
# device_kit_test.sh BUILD_DIR OUTDIR: the GPU benchmark kit on lavapipe, as it runs on a GPU machine.
# Packs the kit from BUILD_DIR, unpacks it elsewhere, checks that it carries its own libraries (not
# the C/C++ runtimes), runs scripts/device-bench.sh --quick from the unpacked kit and checks that
# every section of its summary holds rows and that a failed step fails the summary.
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=$1
out=$2/device-kit
rm -rf "$out" && mkdir -p "$out/unpacked"
fail() { echo "FAIL: $*"; exit 1; }
# What device-kit.sh refuses by design is a skip here, not a failure: it packs Release builds only
# (benchmarks of another build mislead) and needs the benchmark scenes of ../shared/data.
grep -q 'CMAKE_BUILD_TYPE:STRING=Release' "$build/CMakeCache.txt" || { echo "SKIP: $build is not a Release build"; exit 77; }
[[ -d "$root/../shared/data/sponza-dabrovic" ]] || { echo "SKIP: no ../shared/data"; exit 77; }

"$root/scripts/device-kit.sh" "$out/kit.tar.gz" "$build" || fail "device-kit.sh failed"
tar -C "$out/unpacked" -xzf "$out/kit.tar.gz" || fail "the kit does not unpack"
kit=$out/unpacked/bundlelab-kit/bundlelab
for f in bin/bundlelab lib/libembree3.so.3 lib/libvulkan.so.1 lib/libOpenEXR-3_1.so.30 scripts/device-bench.sh \
         data/external/sponza-point.toml ../shared/data/sponza-dabrovic/sponza.obj ../shared/data/bunny/mcguire/bunny.obj; do
    [[ -e "$kit/$f" ]] || fail "the kit lacks $f"
done
for runtime in libc.so libstdc++.so libm.so ld-linux; do
    ! ls "$kit/lib" | grep -q "^$runtime" || fail "the kit carries the runtime $runtime"
done
# Every library beyond the runtimes resolves inside the kit.
LD_LIBRARY_PATH=$kit/lib ldd "$kit/bin/bundlelab" >"$out/ldd.txt"
grep -E 'embree|OpenEXR|OpenMesh|tbb|toml|vulkan' "$out/ldd.txt" | grep -v "$kit/lib" && fail "a library resolves outside the kit"

"$kit/scripts/device-bench.sh" "$out/bench" --quick --budget 300 || fail "device-bench.sh --quick failed"
md=$out/bench/summary.md
cat "$md"
for mode in raster bidir multibounce atlas skylight; do
    grep -qE "^\| $mode \| [a-z-]+\.toml \| 64×36 \| 1 \| [0-9.]+ \|" "$md" || fail "no per-pass row for $mode"
done
[[ $(grep -cE '^\| cornell\.toml \| 32 \| (raster|compute) \|' "$md") == 4 ]] || fail "bundles: want 2 backends x 2 resolutions"
for label in path-tracer multibounce bidir atlas path-tracer-2 raster; do
    grep -qE "^\| cornell-point \| $label \| [0-9]+ \| [0-9.]+ \| [0-9.]+ \| [0-9.e+-]+ \| [0-9.e+-]+ \|" "$md" \
        || fail "no equal-time row for $label"
done
grep -qE "^\| atlas \| 8 directions \| [0-9.]+ \| [0-9.e+-]+ \|" "$md" || fail "no texel-space row for the atlas"
grep -qE "^\| baker \| 4 spp \|" "$md" || fail "no texel-space row for the baker"
/usr/bin/python3 -c "import json,sys; j=json.load(open(sys.argv[1])); assert j['passes'] and j['bundles'] and j['equal_time']" \
    "$out/bench/summary.json" || fail "summary.json incomplete"
# The noise correction reads the quick run's 16-spp references (not the full runs' 1024) and rates
# every row against its own path tracer.
/usr/bin/python3 -c "import json,sys; e=json.load(open(sys.argv[1]))['equal_time']
assert all(r['reference_spp'] == 16 for r in e), [r['reference_spp'] for r in e]
assert all(r['noise_corrected_over_path_tracer'] is not None for r in e), e" \
    "$out/bench/summary.json" || fail "summary.json: noise correction missing or at the wrong spp"
# --only runs the steps named and no other.
"$kit/scripts/device-bench.sh" "$out/only" --quick --only texels >"$out/only.log" 2>&1 || fail "device-bench.sh --only texels failed"
[[ $(cat "$out/only/steps.txt") == "texels cornell-point ok" ]] || fail "--only texels ran: $(tr '\n' ';' <"$out/only/steps.txt")"
"$kit/scripts/device-bench.sh" "$out/only" --only bogus 2>/dev/null && fail "--only bogus was accepted"
# A step that failed fails the summary and is named in it.
echo "passes planted-failure failed (exit 3)" >>"$out/bench/steps.txt"
/usr/bin/python3 "$kit/scripts/device-bench-summary.py" "$out/bench" >"$out/failed.txt" && fail "a failed step did not fail the summary"
grep -q "Failed: passes planted-failure" "$out/failed.txt" || fail "the failed step is not named"
echo "PASS: device kit"
