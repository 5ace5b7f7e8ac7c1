"""Reading a results directory written by `bundlelab run` (results.csv, tasks/*/metrics.csv, ...)."""

import csv
import json
import math
import os

import numpy as np

METRICS = ["mse", "rmse", "relmse", "smape", "mae", "block_ratio_rms"]


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def number(value):
    try:
        v = float(value)
        return v if math.isfinite(v) else None
    except (TypeError, ValueError):
        return None


class Task:
    """One finished task: its row of results.csv, its convergence curve and pass timings."""

    def __init__(self, root, row):
        self.row = row
        self.dir = os.path.join(root, row["dir"])
        self.id = row["id"]
        self.scene = row["scene"]
        self.mode = row["mode"]
        self.label = row["label"]
        self.params = row["params"]
        self.seed = row["seed"]
        self.group = self.label + (" " + self.params if self.params else "")
        self.curve = read_csv(os.path.join(self.dir, "metrics.csv"))
        passes = os.path.join(self.dir, "passes.csv")
        self.passes = read_csv(passes) if os.path.exists(passes) else []
        self.iterations = int(row["iterations"])
        self.wall = number(row["wall_seconds"]) or 0.0
        self.reference_noise = number(row.get("reference_noise_relmse"))
        ref = os.path.join(self.dir, "reference.txt")
        self.reference_image = None
        if os.path.exists(ref):
            with open(ref) as f:
                rel = f.read().strip()
            self.reference_image = os.path.normpath(os.path.join(self.dir, rel))

    def series(self, metric, x="wall_seconds"):
        xs, ys = [], []
        for r in self.curve:
            xv, yv = number(r.get(x)), number(r.get(metric))
            if xv is not None and yv is not None and xv > 0 and yv > 0:
                xs.append(xv)
                ys.append(yv)
        return np.array(xs), np.array(ys)

    def final(self, metric):
        return number(self.row.get(metric))


def load(root):
    rows = read_csv(os.path.join(root, "results.csv"))
    tasks = [Task(root, r) for r in rows]
    env_path = os.path.join(root, "environment.json")
    env = json.load(open(env_path)) if os.path.exists(env_path) else {}
    return tasks, env


def loglog_interpolate(xs, ys, x):
    """y at x on the log-log polyline through (xs, ys); None outside its range."""
    if len(xs) == 0 or x < xs[0] or x > xs[-1]:
        return None
    lx, ly = np.log(xs), np.log(ys)
    return float(np.exp(np.interp(math.log(x), lx, ly)))


def time_to_reach(xs, ys, level):
    """First time at which the curve reaches `level` (log-log interpolation); None if never."""
    for i in range(len(ys)):
        if ys[i] <= level:
            if i == 0:
                return float(xs[0])
            # Between points i-1 and i, in log-log.
            a, b = math.log(ys[i - 1]), math.log(ys[i])
            t = (math.log(level) - a) / (b - a) if b != a else 1.0
            return float(math.exp(math.log(xs[i - 1]) + t * (math.log(xs[i]) - math.log(xs[i - 1]))))
    return None


def read_pfm(path):
    """An RGB float32 PFM (bottom row first) as an array of shape (height, width, 3), top row first."""
    with open(path, "rb") as f:
        if f.readline().strip() != b"PF":
            raise ValueError(path + ": not an RGB PFM")
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(height, width, 3)[::-1].astype(np.float32)


def downsample(image, max_side):
    """Box-downsample by the smallest integer factor that fits max_side."""
    h, w, _ = image.shape
    f = max(1, math.ceil(max(h, w) / max_side))
    h2, w2 = h // f, w // f
    return image[: h2 * f, : w2 * f].reshape(h2, f, w2, f, 3).mean(axis=(1, 3))
