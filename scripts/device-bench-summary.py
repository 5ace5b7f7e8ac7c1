#!/usr/bin/env python3
"""Summary of a scripts/device-bench.sh run: OUTDIR/summary.md (tables) and OUTDIR/summary.json.

Standard library only (the machine the kit runs on may have no matplotlib). Exit status 1 when a step
failed (a render or benchmark exited non-zero); steps skipped for the budget are listed, not failures.
"""
import csv
import json
import os
import sys

from reference_noise import noise_corrected, reference_spp


def read(path, default=""):
    try:
        with open(path) as f:
            return f.read().strip()
    except OSError:
        return default


def load(path):
    """A JSON file, or None when it is missing or cut short (a run stopped mid-write)."""
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def is_wall(name):
    """A host wall-clock span around GPU passes (base/WallSpan.h, PassTime.h isWallTime)."""
    return name.endswith(" (wall)")


def per_pass(out):
    """Per configuration, from the pass totals after iterations 1 + 2F, 1 + 3F and 1 + 5F (T1, T2, T3;
    each checkpoint resolves once): per iteration = ((T3 - T2) - (T2 - T1)) / F, per resolve =
    (T2 - T1) - F x that. The checkpoint after the first iteration gives its wall time and the passes
    that ran then only; the iterations between it and T1 are a warm-up (the GPU's clocks ramp up).
    A run of an older kit (checkpoints after 1 and 1 + F, end after 1 + 3F) reads with T1 the first."""
    rows = []
    base = os.path.join(out, "passes")
    for config in sorted(os.listdir(base)) if os.path.isdir(base) else []:
        d = os.path.join(base, config)
        checkpoints = sorted(int(f.split(".")[1]) for f in os.listdir(d) if f.count(".") == 2 and f.endswith(".json"))
        runs = [load(os.path.join(d, f"run.{n}.json")) for n in checkpoints] + [load(os.path.join(d, "run.json"))]
        if len(runs) not in (3, 4) or any(r is None for r in runs):
            rows.append({"config": config, "error": "the run did not finish (see its log)"})
            continue
        first = runs[0]
        runs = runs[-3:]
        a, b, c = runs
        n1, n2, n3 = a["iterations"], b["iterations"], c["iterations"]
        frames = n2 - n1
        if frames <= 0 or n3 - n2 != 2 * frames:
            rows.append({"config": config, "error": f"unexpected iterations {n1}, {n2}, {n3}"})
            continue
        total = [{p["name"]: p for p in r["passes"]} for r in runs]
        first_passes = {p["name"]: p for p in first["passes"]}
        passes, per_resolve, first_only = {}, {}, {}
        for name, p in total[2].items():
            t1, t2, t3 = (total[i][name]["total_ms"] if name in total[i] else 0.0 for i in range(3))
            if name in first_passes and first_passes[name]["count"] == p["count"]:
                first_only[name] = p["total_ms"]  # e.g. the lights' shadow maps of a static scene
                continue
            it = ((t3 - t2) - (t2 - t1)) / frames
            passes[name] = it
            resolve = (t2 - t1) - frames * it
            if abs(resolve) > 1e-3 and not is_wall(name):
                per_resolve[name] = resolve
        rows.append({
            "config": config, "mode": c["mode"], "scene": os.path.basename(c["scene"]),
            "width": c["width"], "height": c["height"], "iterations": [n1, n2, n3],
            "settings": c.get("settings", {}), "setup_seconds": c["setup_seconds"],
            # Wall time counts iterate() only (no resolve): the last 3F iterations.
            "wall_ms_per_iteration": (c["wall_seconds"] - a["wall_seconds"]) * 1000.0 / (n3 - n1),
            "first_iteration_wall_ms": first["wall_seconds"] * 1000.0,
            "gpu_ms_per_iteration": sum(v for k, v in passes.items() if not is_wall(k)),
            "passes_ms_per_iteration": passes, "resolve_ms": per_resolve,
            "first_iteration_only_ms": first_only,
            "device": c["environment"]["device"],
        })
    return rows


def bundles(out):
    rows = []
    base = os.path.join(out, "bundles")
    for f in sorted(os.listdir(base)) if os.path.isdir(base) else []:
        if f.endswith(".json"):
            j = load(os.path.join(base, f))
            for r in (j or {}).get("results", []):
                rows.append({"scene": os.path.basename(j["scene"]), "triangles": j["triangles"], "backend": j["backend"],
                             "directions": j["directions"], **r})
    return rows


def with_noise_correction(rows):
    """Each equal-time row's noise-corrected ratio against the path tracer judged by the same
    reference (scripts/reference_noise.py); rows of summaries written before it had it carry no
    reference_spp: every such run of the kit used 1024-spp references."""
    tracers = {(r["scene"], r.get("reference")): r for r in rows if r.get("mode") == "reference"}
    for r in rows:
        tracer = tracers.get((r["scene"], r.get("reference")))
        r["noise_corrected_over_path_tracer"] = noise_corrected(
            r.get("relmse"), r.get("reference_noise_relmse"), tracer and tracer.get("reference_noise_relmse"),
            r["reference_spp"] if "reference_spp" in r else 1024, tracer and tracer.get("iterations")) if tracer else None
    return rows


def equal_time(out):
    path = os.path.join(out, "equal-time", "results.csv")
    if not os.path.exists(path):
        return []
    rows = list(csv.DictReader(open(path)))
    # A mode is compared with the path tracer judged against the same reference image (bidir's
    # reference keeps paths of up to four segments, like bidir).
    def reference_of(r):
        return r["scene"], read(os.path.join(out, "equal-time", r["dir"], "reference.txt"))
    pt = {reference_of(r): float(r["relmse"]) for r in rows if r["mode"] == "reference" and r["relmse"]}
    result = []
    for r in rows:
        rel = float(r["relmse"]) if r["relmse"] else None
        result.append({
            "scene": r["scene"], "mode": r["mode"], "label": r["label"], "iterations": int(r["iterations"]),
            "wall_seconds": float(r["wall_seconds"]), "setup_seconds": float(r["setup_seconds"]),
            "gpu_ms": float(r["gpu_ms"]) if r["gpu_ms"] else None, "relmse": rel,
            "relmse_over_path_tracer": rel / pt[reference_of(r)] if rel is not None and pt.get(reference_of(r)) else None,
            "reference": reference_of(r)[1],
            "reference_spp": reference_spp(os.path.join(out, "equal-time", r["dir"])),
            "mean_ratio": [float(r[k]) for k in ("mean_ratio_r", "mean_ratio_g", "mean_ratio_b") if r[k]],
            "reference_noise_relmse": float(r["reference_noise_relmse"]) if r["reference_noise_relmse"] else None,
        })
    with_noise_correction(result)
    return result


def texel_rows(out):
    """bench texels' CSV (method, budget, seconds, texel and image relMSE; nan where a method has none)."""
    path = os.path.join(out, "texels", "cornell-point.csv")
    if not os.path.exists(path):
        return []
    def num(v):
        x = float(v)
        return None if x != x else x  # nan -> null in JSON
    return [{"method": r["method"], "budget": int(float(r["budget"])), "seconds": float(r["seconds"]),
             "texel_relmse": num(r["texel_relmse"]), "image_relmse": num(r["image_relmse"])}
            for r in csv.DictReader(open(path))]


def fmt(v, spec=".3g"):
    return "—" if v is None else format(v, spec)


def main(out):
    steps = [line.split(" ", 2) for line in read(os.path.join(out, "steps.txt")).splitlines() if line.strip()]
    failed = [s for s in steps if len(s) == 3 and s[2].startswith("failed")]
    skipped = [s for s in steps if len(s) == 3 and s[2].startswith("skipped")]
    summary = {
        "machine": dict(line.split(": ", 1) for line in read(os.path.join(out, "machine.txt")).splitlines() if ": " in line),
        "devices": read(os.path.join(out, "devices.txt")).splitlines(),
        "passes": per_pass(out), "bundles": bundles(out), "equal_time": equal_time(out),
        "texels": texel_rows(out), "failed": [" ".join(s) for s in failed], "skipped": [" ".join(s) for s in skipped],
    }
    m = summary["machine"]
    md = ["# bundlelab device benchmark", "",
          f"- device(s): {'; '.join(summary['devices']) or 'none found'}",
          *(f"- {k}: {v}" for k, v in m.items()), ""]
    if failed or skipped:
        md += ["Failed: " + (", ".join(" ".join(s[:2]) for s in failed) or "none") + "; skipped (budget): "
               + (", ".join(" ".join(s[:2]) for s in skipped) or "none"), ""]

    md += ["## Milliseconds per pass and iteration", "",
           "From the modes' GPU timestamps in one process after iterations 1 + 2F, 1 + 3F and 1 + 5F (T1, T2, T3; each "
           "checkpoint resolves the image once): per iteration ((T3 − T2) − (T2 − T1)) / F, per resolve what is left of "
           "T2 − T1; set-up (scene upload, BVH, atlas, pipelines), the first iteration's shader compilation and the "
           "GPU's clock ramp (the 2F warm-up iterations) fall out. Wall = the mode's "
           "iterate() calls (host work and waits included; \"(wall)\" passes are host spans around GPU passes). Passes "
           "that ran in the first iteration only (the lights' shadow maps of a static scene) are listed apart.", "",
           "| mode | scene | size | F | set-up s | first iteration wall ms | wall ms/it | GPU ms/it | passes (ms/it) | per resolve (ms) | first iteration only (ms) |",
           "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in summary["passes"]:
        if "error" in r:
            md.append(f"| {r['config']} | — | — | — | — | — | — | — | {r['error']} | — | — |")
            continue
        passes = ", ".join(f"{k} {v:.2f}" for k, v in sorted(r["passes_ms_per_iteration"].items(), key=lambda kv: -kv[1]))
        md.append(f"| {r['mode']} | {r['scene']} | {r['width']}×{r['height']} | {r['iterations'][1] - r['iterations'][0]} | "
                  f"{r['setup_seconds']:.2f} | {r['first_iteration_wall_ms']:.1f} | {r['wall_ms_per_iteration']:.2f} | "
                  f"{r['gpu_ms_per_iteration']:.2f} | {passes} | "
                  f"{', '.join(f'{k} {v:.2f}' for k, v in r['resolve_ms'].items()) or '—'} | "
                  f"{', '.join(f'{k} {v:.2f}' for k, v in r['first_iteration_only_ms'].items()) or '—'} |")

    md += ["", "## Bundles against the rasterization floor", "",
           "Medians over the directions (after a warm-up) of `bundlelab bench bundles`; floor = rasterizing the scene once "
           "at the bundle's resolution.", "",
           "| scene | triangles | backend | resolution | fragments | floor ms | build ms | walk ms | (build+walk)/floor |",
           "|---|---|---|---|---|---|---|---|---|"]
    for r in summary["bundles"]:
        md.append(f"| {r['scene']} | {r['triangles']} | {r['backend']} | {r['resolution']}² | {r['fragments_median']:.0f} | "
                  f"{r['floor_ms_median']:.3f} | {r['build_ms_median']:.3f} | {r['traverse_ms_median']:.3f} | "
                  f"{r['ratio_to_floor']:.2f} |")

    md += ["", "## Every mode against the path tracer at equal time", "",
           "`bundlelab run` of OUTDIR/equal-time.toml: the same wall seconds of each mode's own work, relMSE against the "
           "runner's reference (the path tracer at higher spp, another seed); ratio = relMSE / the path tracer's at the same "
           "time (below 1: the mode wins). Noise-corrected: the reference's own noise taken off the mode's relMSE, over "
           "the path tracer's own relMSE predicted as that noise * reference spp / its samples (on the path tracer's "
           "row: its measured relMSE less the noise over that prediction, about 1). The measured ratio understates "
           "the gap wherever the path tracer's relMSE is mostly the reference's noise.", "",
           "| scene | mode | iterations | wall s | set-up s | relMSE | relMSE / path tracer | noise-corrected | "
           "image mean / reference (r, g, b) | reference |",
           "|---|---|---|---|---|---|---|---|---|---|"]
    for r in summary["equal_time"]:
        md.append(f"| {r['scene']} | {r['label']} | {r['iterations']} | {r['wall_seconds']:.2f} | {r['setup_seconds']:.2f} | "
                  f"{fmt(r['relmse'])} | {fmt(r['relmse_over_path_tracer'])} | "
                  f"{fmt(r['noise_corrected_over_path_tracer'])} | "
                  f"{', '.join(format(x, '.4f') for x in r['mean_ratio']) or '—'} | {os.path.basename(r['reference'])} |")
    md += ["", "## The atlas in texel space", "",
           "`bundlelab bench texels` on the point-lit Cornell box: the atlas's error over every texel side against the "
           "path tracer baking the same texels, and through the camera against the path tracer for V views "
           "(experiments/atlas-texels/README.md explains the columns).", ""]
    texels = read(os.path.join(out, "texels", "cornell-point.log"))
    kept = []  # the tables and their captions, each caption and table apart (a table ends at a blank line)
    for line in texels.splitlines():
        if line.startswith("|"):
            kept.append(line)
        elif line.startswith(("Time to", "atlas ")):
            kept += ["", line, ""]
    texel_step = [s for s in steps if len(s) == 3 and s[0] == "texels"]
    md += kept or ["(" + (texel_step[0][2] if texel_step else "not run") + ")"]
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=2)
    print("\n".join(md))
    return 1 if failed else 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: device-bench-summary.py OUTDIR")
    sys.exit(main(sys.argv[1]))
