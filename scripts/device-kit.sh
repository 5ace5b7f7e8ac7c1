#!/usr/bin/env bash
# Packs the one-call GPU benchmark kit: the Release `bundlelab`, the shared libraries it needs beyond
# the C and C++ runtimes (Embree, TBB, OpenEXR, OpenMesh, toml++, stb, the Vulkan loader, ...), the
# benchmark scenes (data/ and the files of ../shared/data they name) and scripts/device-bench.sh,
# into one .tar.gz of at most 60 MiB (checked: a bigger kit is an error, not a surprise on the
# other machine). On any x86-64 Linux with a Vulkan 1.3 driver and a C/C++ runtime at least as new as
# the build machine's (Debian 12: glibc 2.36, GCC 12's libstdc++):
#   tar xzf bundlelab-kit.tar.gz && bundlelab-kit/bundlelab/scripts/device-bench.sh OUTDIR
#
#   scripts/device-kit.sh [ARCHIVE] [BUILD_DIR]     (default: build/bundlelab-kit.tar.gz, build/)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
archive=${1:-$root/build/bundlelab-kit.tar.gz}
build=${2:-$root/build}
shared=$root/../shared/data
limit_mib=60

binary=$build/bundlelab
[[ -x "$binary" ]] || { echo "device-kit: $binary not found (run scripts/build.sh first)" >&2; exit 1; }
grep -q 'CMAKE_BUILD_TYPE:STRING=Release' "$build/CMakeCache.txt" ||
    { echo "device-kit: $build is not a Release build (benchmarks of a Debug binary mislead)" >&2; exit 1; }
for f in sponza-dabrovic bunny/mcguire/bunny.obj envmap; do
    [[ -e "$shared/$f" ]] || { echo "device-kit: $shared/$f not found (the benchmark scenes need ../shared/data)" >&2; exit 1; }
done

stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
kit=$stage/bundlelab-kit/bundlelab
mkdir -p "$kit/bin" "$kit/lib" "$kit/scripts" "$stage/bundlelab-kit/shared/data/bunny/mcguire"
cp "$binary" "$kit/bin/"
# Every library the binary loads except the C and C++ runtimes and the dynamic loader, which the
# target machine has (a newer glibc / libstdc++ runs a binary built against Debian 12's).
ldd "$binary" | awk '$2 == "=>" && $3 ~ /^\// {print $1, $3}' | while read -r name path; do
    case $name in
        libc.so.*|libm.so.*|libstdc++.so.*|libgcc_s.so.*|libpthread.so.*|libdl.so.*|librt.so.*|ld-linux*) ;;
        *) cp -L "$path" "$kit/lib/$name" ;;
    esac
done
cp "$root/scripts/device-bench.sh" "$root/scripts/device-bench-summary.py" "$root/scripts/reference_noise.py" "$kit/scripts/"
cp -r "$root/data" "$kit/"
cp -r "$shared/sponza-dabrovic" "$stage/bundlelab-kit/shared/data/"
cp "$shared/bunny/mcguire/bunny.obj" "$stage/bundlelab-kit/shared/data/bunny/mcguire/"
cp -r "$shared/envmap" "$stage/bundlelab-kit/shared/data/"
git -C "$root" rev-parse --short=12 HEAD >"$kit/REVISION" 2>/dev/null || echo unknown >"$kit/REVISION"

mkdir -p "$(dirname "$archive")"
tar -C "$stage" -czf "$archive.tmp" bundlelab-kit
bytes=$(stat -c %s "$archive.tmp")
if ((bytes > limit_mib * 1024 * 1024)); then
    rm -f "$archive.tmp"
    echo "device-kit: the kit is $((bytes / 1024 / 1024)) MiB, over its $limit_mib MiB limit" >&2
    exit 1
fi
mv "$archive.tmp" "$archive"
echo "wrote $archive ($((bytes / 1024 / 1024)) MiB; $(ls "$kit/lib" | wc -l) libraries, revision $(cat "$kit/REVISION"))"
