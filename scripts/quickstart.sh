#!/usr/bin/env bash
# Quick start, step 1: install what is missing, build, and run the main job on the built-in
# default: the quickstart experiment (Cornell box and an environment-lit scene; the reference path
# tracer, raster and skylight against a cached reference), then its report.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
scripts/install-deps.sh
scripts/build.sh
# `import bundlelab` for /usr/bin/python3: a .pth file in its site-packages naming build/python.
site=$(/usr/bin/python3 -c 'import site; print(site.getsitepackages()[0])')
if ! { mkdir -p "$site" && echo "$root/build/python" >"$site/bundlelab.pth"; } 2>/dev/null; then
    site=$(/usr/bin/python3 -m site --user-site)
    mkdir -p "$site" && echo "$root/build/python" >"$site/bundlelab.pth"
fi
out=results/quickstart
build/bundlelab run experiments/quickstart.toml --out "$out"
build/bundlelab report "$out"
echo
echo "quickstart: open $root/$out/report.html (summary: $out/report.md, data: $out/results.csv)"
