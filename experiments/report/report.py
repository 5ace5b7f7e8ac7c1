"""bundlelab report RESULTS_DIR: plots, one self-contained HTML report and a Markdown summary.

The HTML embeds everything (plots as PNG, images as float16 data for the viewer), so it can be
mailed or archived alone.
"""

import base64
import html
import io
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plots  # noqa: E402
from results import load, loglog_interpolate, read_pfm, downsample, time_to_reach  # noqa: E402

ERROR_LEVELS = [1e-1, 1e-2, 1e-3]  # relMSE levels for "time to reach"
VIEWER_MAX_SIDE = 256              # viewer images are box-downsampled to this


def fmt(v, digits=3):
    if v is None:
        return "—"
    if v == 0 or (1e-3 <= abs(v) < 1e4):
        return f"{v:.{digits}g}"
    return f"{v:.{digits}e}"


def summary_rows(tasks):
    """Per scene and group: final error, time to reach error levels, error at equal time, speed-up."""
    rows = []
    for scene in sorted({t.scene for t in tasks}):
        st = [t for t in tasks if t.scene == scene]
        equal_time = min((t.wall for t in st if t.wall > 0), default=None)
        for t in st:
            # Speed-up only against a path tracer judged against the same reference image.
            refs = [r for r in st if r.mode == "reference" and r.reference_image == t.reference_image]
            xs, ys = t.series("relmse")
            reach = [time_to_reach(xs, ys, level) if len(xs) else None for level in ERROR_LEVELS]
            at_equal = loglog_interpolate(xs, ys, equal_time) if equal_time and len(xs) else None
            final = t.final("relmse")
            speedup = None
            if refs and final and t.mode != "reference" and t.wall > 0:
                rxs, rys = refs[0].series("relmse")
                t_ref = time_to_reach(rxs, rys, final) if len(rxs) else None
                speedup = t_ref / t.wall if t_ref else None
            rows.append(dict(scene=scene, group=t.group, seed=t.seed, iterations=t.iterations, wall=t.wall,
                             final=final, noise=t.reference_noise, reach=reach, equal_time=equal_time,
                             at_equal=at_equal, speedup=speedup, id=t.id))
    return rows


def image_payload(root, tasks):
    images, seen = [], set()
    def add(path, name, scene):
        if not path or not os.path.exists(path) or path in seen:
            return
        seen.add(path)
        img = downsample(read_pfm(path), VIEWER_MAX_SIDE)
        img = np.nan_to_num(img, nan=0.0, posinf=65504.0, neginf=0.0).clip(0, 65504)
        images.append(dict(name=name, scene=scene, width=img.shape[1], height=img.shape[0],
                           data=base64.b64encode(img.astype("<f2").tobytes()).decode("ascii")))
    for t in tasks:
        if t.reference_image:
            add(os.path.splitext(t.reference_image)[0] + ".pfm", "reference " + os.path.basename(t.reference_image),
                t.scene)
    for t in tasks:
        add(os.path.join(t.dir, "final.pfm"), t.group + f" (seed {t.seed}, {t.iterations} it.)", t.scene)
    return images


def embed_png(path):
    with open(path, "rb") as f:
        return "data:image/png;base64," + base64.b64encode(f.read()).decode("ascii")


def pass_table(tasks):
    names = sorted({p["pass"] for t in tasks for p in t.passes})
    head = "".join(f"<th>{html.escape(n)}</th>" for n in names)
    body = ""
    for t in tasks:
        per = {p["pass"]: float(p["total_ms"]) / max(t.iterations, 1) for p in t.passes}
        cells = "".join(f"<td>{fmt(per.get(n))}</td>" for n in names)
        body += f"<tr><td>{html.escape(t.scene)}</td><td>{html.escape(t.group)}</td><td>{t.iterations}</td>{cells}</tr>"
    return f"<table><tr><th>scene</th><th>method</th><th>iterations</th>{head}</tr>{body}</table>"


def write_report(root):
    tasks, env = load(root)
    made = plots.convergence_plots(root) + [p for p in [plots.timing_plot(root)] if p]
    rows = summary_rows(tasks)
    name = env.get("experiment", os.path.basename(os.path.abspath(root)))

    level_head = "".join(f"<th>time to relMSE {l:g} (s)</th>" for l in ERROR_LEVELS)
    summary = ""
    for r in rows:
        reach = "".join(f"<td>{fmt(x)}</td>" for x in r["reach"])
        summary += (f"<tr><td>{html.escape(r['scene'])}</td><td>{html.escape(r['group'])}</td><td>{r['seed']}</td>"
                    f"<td>{r['iterations']}</td><td>{fmt(r['wall'])}</td><td>{fmt(r['final'])}</td>"
                    f"<td>{fmt(r['noise'])}</td>{reach}<td>{fmt(r['at_equal'])}</td><td>{fmt(r['speedup'])}</td></tr>")
    plots_html = "".join(f'<figure><img src="{embed_png(p)}" alt="{html.escape(os.path.basename(p))}">'
                         f"<figcaption>{html.escape(os.path.basename(p))}</figcaption></figure>" for p in made)
    env_html = "".join(f"<tr><th>{html.escape(k)}</th><td>{html.escape(str(v))}</td></tr>" for k, v in env.items())
    payload = json.dumps({"images": image_payload(root, tasks)})
    viewer_js = open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "viewer.js")).read()

    page = f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>bundlelab report: {html.escape(name)}</title>
<style>
body {{ font-family: sans-serif; margin: 1.5em; color: #222; }}
table {{ border-collapse: collapse; margin: 0.5em 0 1.5em; font-size: 0.85em; }}
th, td {{ border: 1px solid #ccc; padding: 0.25em 0.5em; text-align: right; }}
th {{ background: #f3f3f3; }} td:first-child, td:nth-child(2) {{ text-align: left; }}
figure {{ display: inline-block; margin: 0.5em; }} figure img {{ max-width: 560px; }}
#bl-viewer {{ border: 1px solid #ccc; padding: 0.8em; display: inline-block; }}
#bl-canvas {{ image-rendering: pixelated; border: 1px solid #888; cursor: crosshair; display: block; margin-top: 0.5em; }}
.controls label {{ margin-right: 1em; }}
</style></head><body>
<h1>bundlelab report: {html.escape(name)}</h1>
<p>Errors are against each scene's reference (relMSE with ε = 0.01); the reference's own noise is
the floor no method can be judged below. "At equal time" interpolates every method's curve at the
shortest run's wall time; speed-up is the time the reference path tracer needs to reach the
method's final error, divided by the method's time.</p>
<h2>Summary</h2>
<table><tr><th>scene</th><th>method</th><th>seed</th><th>iterations</th><th>wall (s)</th><th>final relMSE</th>
<th>reference noise</th>{level_head}<th>relMSE at equal time</th><th>speed-up vs reference</th></tr>{summary}</table>
<h2>Convergence and timing</h2>{plots_html}
<h2>Images</h2>
<div id="bl-viewer"><div class="controls">
<label>A <select id="bl-a"></select></label><label>B <select id="bl-b"></select></label>
<label>view <select id="bl-mode"><option value="split">side by side (move the mouse)</option><option value="a">A</option>
<option value="b">B</option><option value="flip">flip (button or key f)</option><option value="error">false-colour error</option></select></label>
<button id="bl-flip">flip</button><br>
<label>exposure <input id="bl-exposure" type="range" min="-8" max="8" step="0.5" value="0"></label>
<label>zoom <select id="bl-zoom"><option>1</option><option>2</option><option>4</option><option>8</option></select> (drag to pan)</label>
<label>error scale <select id="bl-error-scale"><option>0.01</option><option selected>0.1</option><option>1</option></select></label>
</div><canvas id="bl-canvas"></canvas><div id="bl-caption"></div></div>
<div id="bl-status" data-status="loading">loading</div>
<h2>Time per pass (ms per iteration)</h2>{pass_table(tasks)}
<h2>Environment</h2><table>{env_html}</table>
<script type="application/json" id="bl-images">{payload}</script>
<script>{viewer_js}</script>
</body></html>
"""
    out = os.path.join(root, "report.html")
    with open(out + ".tmp", "w") as f:
        f.write(page)
    os.replace(out + ".tmp", out)

    md = [f"# bundlelab report: {name}", "",
          "| scene | method | seed | iterations | wall (s) | final relMSE | reference noise | "
          + " | ".join(f"time to {l:g} (s)" for l in ERROR_LEVELS) + " | relMSE at equal time | speed-up |",
          "|" + "---|" * (9 + len(ERROR_LEVELS))]
    for r in rows:
        md.append(f"| {r['scene']} | {r['group']} | {r['seed']} | {r['iterations']} | {fmt(r['wall'])} | "
                  f"{fmt(r['final'])} | {fmt(r['noise'])} | " + " | ".join(fmt(x) for x in r["reach"])
                  + f" | {fmt(r['at_equal'])} | {fmt(r['speedup'])} |")
    md += ["", "Plots: " + ", ".join(os.path.relpath(p, root) for p in made), "",
           "Environment: " + ", ".join(f"{k}: {v}" for k, v in env.items())]
    with open(os.path.join(root, "report.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print("report: " + out)
    print("summary: " + os.path.join(root, "report.md"))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: report.py RESULTS_DIR")
    write_report(sys.argv[1])
