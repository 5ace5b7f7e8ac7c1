#!/usr/bin/env python3
"""Medians over repeated scripts/device-bench.sh runs: DIR/summary*.json -> DIR/medians.md.

    experiments/gpu/medians.py DIR
Every figure is the median over the repeats, the repeats' range beside it (same machine, same kit).
"""
import glob
import importlib.util
import json
import os
import statistics
import sys

# The kit's summary holds the noise correction; runs summarized before it had it get it here.
_scripts = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts")
sys.path.insert(0, _scripts)  # its own import of reference_noise
_spec = importlib.util.spec_from_file_location("device_bench_summary", os.path.join(_scripts, "device-bench-summary.py"))
device_bench_summary = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(device_bench_summary)


def with_noise_correction(run):
    """Fills noise_corrected_over_path_tracer where a run's summary predates it."""
    if any("noise_corrected_over_path_tracer" not in r for r in run.get("equal_time", [])):
        device_bench_summary.with_noise_correction(run["equal_time"])
    return run


def med(values, spec):
    values = [v for v in values if v is not None]
    if not values:
        return "—"
    m = statistics.median(values)
    return f"{m:{spec}} ({min(values):{spec}}–{max(values):{spec}})" if len(values) > 1 else f"{m:{spec}}"


def matching(runs, section, key, row):
    """The row of each run with the same key (runs that skipped or failed it are left out)."""
    out = []
    for run in runs:
        r = next((r for r in run[section] if "error" not in r and key(r) == key(row)), None)
        if r is not None:
            out.append(r)
    return out


def main(d):
    runs = [with_noise_correction(json.load(open(f))) for f in sorted(glob.glob(os.path.join(d, "summary*.json")))]
    if not runs:
        sys.exit(f"{d}: no summary*.json")
    first = runs[0]
    md = [f"# Device benchmark, medians over {len(runs)} runs", "",
          f"- device: {'; '.join(first['devices'])}", f"- cpu: {first['machine'].get('cpu', '?')}",
          f"- revision: {first['machine'].get('revision', '?')}; kit: `scripts/device-kit.sh`, run: "
          "`scripts/device-bench.sh OUT`", "",
          "## Milliseconds per iteration", "",
          "| mode | scene | size | set-up s | wall ms/it | GPU ms/it | largest passes (ms/it) |", "|---|---|---|---|---|---|---|"]
    for row in first["passes"]:
        if "error" in row:
            continue
        same = matching(runs, "passes", lambda r: r["config"], row)
        names = sorted(row["passes_ms_per_iteration"], key=lambda k: -row["passes_ms_per_iteration"][k])[:4]
        passes = ", ".join(f"{k} {med([s['passes_ms_per_iteration'].get(k) for s in same], '.2f')}" for k in names)
        md.append(f"| {row['mode']} | {row['scene']} | {row['width']}×{row['height']} | "
                  f"{med([s['setup_seconds'] for s in same], '.2f')} | "
                  f"{med([s['wall_ms_per_iteration'] for s in same], '.2f')} | "
                  f"{med([s['gpu_ms_per_iteration'] for s in same], '.2f')} | {passes} |")
    md += ["", "## Bundles against the floor", "",
           "| scene | backend | resolution | floor ms | build ms | walk ms | (build+walk)/floor |", "|---|---|---|---|---|---|---|"]
    for row in first["bundles"]:
        same = matching(runs, "bundles", lambda r: (r["scene"], r["backend"], r["resolution"]), row)
        md.append(f"| {row['scene']} | {row['backend']} | {row['resolution']}² | {med([s['floor_ms_median'] for s in same], '.3f')} | "
                  f"{med([s['build_ms_median'] for s in same], '.3f')} | {med([s['traverse_ms_median'] for s in same], '.3f')} | "
                  f"{med([s['ratio_to_floor'] for s in same], '.2f')} |")
    md += ["", "## Equal time against the path tracer (equal-time.toml of each run: seconds, size, seed)", "",
           "| scene | mode | iterations | relMSE | relMSE / path tracer | noise-corrected | image mean / reference (g) |",
           "|---|---|---|---|---|---|---|"]
    for row in first["equal_time"]:
        same = matching(runs, "equal_time", lambda r: (r["scene"], r["label"]), row)
        md.append(f"| {row['scene']} | {row['label']} | {med([s['iterations'] for s in same], '.0f')} | "
                  f"{med([s['relmse'] for s in same], '.3g')} | {med([s['relmse_over_path_tracer'] for s in same], '.3g')} | "
                  f"{med([s['noise_corrected_over_path_tracer'] for s in same], '.3g')} | "
                  f"{med([s['mean_ratio'][1] if s['mean_ratio'] else None for s in same], '.4f')} |")
    if first.get("texels"):
        md += ["", "## The atlas in texel space (point-lit Cornell box; seconds and relMSE)", "",
               "| method | budget | seconds | texel relMSE | image relMSE |", "|---|---|---|---|---|"]
        for row in first["texels"]:
            same = matching(runs, "texels", lambda r: (r["method"], r["budget"]), row)
            md.append(f"| {row['method']} | {row['budget']} | {med([s['seconds'] for s in same], '.3g')} | "
                      f"{med([s['texel_relmse'] for s in same], '.3g')} | {med([s['image_relmse'] for s in same], '.3g')} |")
    open(os.path.join(d, "medians.md"), "w").write("\n".join(md) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".")
