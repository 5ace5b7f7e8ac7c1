#!/usr/bin/env bash
# Quick start, step 1: install what is missing, build, and run the main job on the built-in
# default: the quickstart experiment (Cornell box and an environment-lit scene; the reference path
# tracer, raster and skylight against a cached reference), then its report.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
scripts/install-deps.sh
scripts/build.sh
# `import bundlelab`: a .pth file naming build/python in the site-packages of /usr/bin/python3 (the
# module is built for it) and of the `python3` on PATH where that is another interpreter of the
# same version (a pyenv or venv build of 3.11 loads the same module).
version=$(/usr/bin/python3 -c 'import sys; print("%d.%d" % sys.version_info[:2])')
for py in /usr/bin/python3 $(command -v python3 || true); do
    [[ "$($py -c 'import sys; print("%d.%d" % sys.version_info[:2])' 2>/dev/null)" == "$version" ]] || continue
    site=$($py -c 'import site; print(site.getsitepackages()[0])')
    if ! { mkdir -p "$site" && echo "$root/build/python" >"$site/bundlelab.pth"; } 2>/dev/null; then
        site=$($py -m site --user-site)
        mkdir -p "$site" && echo "$root/build/python" >"$site/bundlelab.pth"
    fi
done
out=results/quickstart
build/bundlelab run experiments/quickstart.toml --out "$out"
build/bundlelab report "$out"
echo
echo "quickstart: open $root/$out/report.html (summary: $out/report.md, data: $out/results.csv)"
