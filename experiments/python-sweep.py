#!/usr/bin/python3
"""A parameter sweep from Python (the `bundlelab` module): multibounce's bundle_count on the
point-lit Cornell box, each at several time budgets, relMSE against a reference rendered once;
error against time, one line per setting, into python-sweep.png (and .csv) in the output folder.

    PYTHONPATH=build/python experiments/python-sweep.py [--out results/python-sweep] [--size 64]
(after scripts/quickstart.sh, `import bundlelab` works without PYTHONPATH)."""
import argparse
import csv
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import bundlelab  # noqa: E402

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", default=os.path.join(ROOT, "results", "python-sweep"))
    p.add_argument("--size", type=int, default=64)
    p.add_argument("--scene", default=os.path.join(ROOT, "data", "cornell-box", "cornell-point.toml"))
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    scene = bundlelab.load_scene(a.scene)
    scene.resolution = (a.size, a.size)
    reference = bundlelab.render(scene, "reference", iterations=1024)["radiance"]
    rows = []
    for k in [4, 16, 64]:
        for seconds in [0.5, 1.0, 2.0, 4.0]:
            r = bundlelab.render(scene, "multibounce", settings={"bundle_count": k}, seconds=seconds, seed=1)
            e = bundlelab.compare(r["radiance"], reference)
            rows.append({"bundle_count": k, "seconds": r["seconds"], "iterations": r["iterations"], "relmse": e["relmse"]})
            print("bundle_count %3d  %.2f s  %4d iterations  relMSE %.4g" % (k, r["seconds"], r["iterations"], e["relmse"]))
    with open(os.path.join(a.out, "python-sweep.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    for k in sorted({r["bundle_count"] for r in rows}):
        pts = [r for r in rows if r["bundle_count"] == k]
        plt.loglog([r["seconds"] for r in pts], [r["relmse"] for r in pts], "o-", label="bundle_count %d" % k)
    plt.xlabel("seconds (iterate only)")
    plt.ylabel("relMSE against the reference (1024 spp)")
    plt.title("multibounce on %s, %dx%d" % (os.path.basename(a.scene), a.size, a.size))
    plt.legend()
    plt.savefig(os.path.join(a.out, "python-sweep.png"), dpi=120)
    print("wrote", os.path.join(a.out, "python-sweep.png"))


if __name__ == "__main__":
    main()
