#!/usr/bin/env python3
"""Splits `bundlelab bench bundles` JSON into per-bundle and per-fragment costs (least squares of
ms against fragments over the resolutions), for the floor, the build and the walk; prints a
Markdown table per scene and the share of build + walk that is above the floor, per fragment."""
import json
import sys


def fit(xs, ys):
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else 0.0
    return my - slope * mx, slope


for path in sys.argv[1:]:
    d = json.load(open(path))
    rows = d["results"]
    frags = [r["fragments_median"] for r in rows]
    print(f"\n### {d['scene'].split('/')[-1]} ({d['triangles']} triangles), {d.get('backend', 'raster')} build, "
          f"{d['directions']} directions, {d['device']}\n")
    print("| resolution | fragments | floor ms | build ms | walk ms | (b+w)/floor | build-floor ns/fragment | walk ns/node |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        f, b, w = r["floor_ms_median"], r["build_ms_median"], r["traverse_ms_median"]
        fr = r["fragments_median"]
        print(f"| {r['resolution']} | {fr:.0f} | {f:.2f} | {b:.2f} | {w:.2f} | {r['ratio_to_floor']:.2f} | "
              f"{(b - f) / fr * 1e6 if fr else 0:.1f} | {w / fr * 1e6 if fr else 0:.1f} |")
    print("\n| pass | per bundle ms (intercept) | per fragment ns (slope) |")
    print("|---|---|---|")
    for key, name in (("floor_ms_median", "floor (count only)"), ("build_ms_median", "build"),
                      ("traverse_ms_median", "walk")):
        a, s = fit(frags, [r[key] for r in rows])
        print(f"| {name} | {a:.2f} | {s * 1e6:.1f} |")
