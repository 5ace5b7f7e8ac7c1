#!/usr/bin/env python3
"""Bias against noise of mode atlas, from a run of experiments/atlas-discretization.toml (or any run
with two seeds per contender and a rendered reference): at every checkpoint, per contender,

  relMSE        mean over pixels and channels of e_s^2, e_s = (I_s - R) / sqrt(R^2 + 0.01) (the
                project's relMSE, core/image/Metrics.cpp), averaged over the two seeds;
  noise         mean((e_1 - e_2)^2) / 2: the seeds' noise is independent, so this is the variance part;
  bias^2        mean(e_1 e_2): the product of two independent errors keeps only what they share, the
                squared bias (plus the reference's own noise, which both seeds share; printed apart);
  mean ratio    image mean / reference mean (green), per seed and of the two seeds' average image;
  block ratios  8 x 8 block means / the reference's (blocks darker than 1e-3 of the image mean
                skipped, as Metrics.cpp): RMS of (ratio - 1) per seed, and the shared part
                sqrt(mean((r_1 - 1)(r_2 - 1))) (the block ratios' bias), and the largest |ratio - 1|
                of the two seeds' average image.

Common random numbers: the same seed gives the same directions and bundle jitter at every atlas
and bundle resolution, so two contenders at one seed share most of their noise. Their difference,
relMSE(A_s, B_s) with B as the reference of the scale, stays put over directions where it is a
difference in bias (discretization) and falls as 1/n where it is noise; printed per pair and
checkpoint (mean over the seeds), with the ratio of their image means and their 8 x 8 block ratios A / B (RMS and largest deviation).

    experiments/atlas-discretization.py RESULTS_DIR > table.md

Reads the runner's iter-N.exr (ZIP-compressed float scanlines, as core/image/ImageIO.cpp writes
them) with zlib and numpy only.
"""
import json
import struct
import sys
import zlib
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent / "report"))
from results import read_pfm  # noqa: E402  (experiments/report/results.py)

EPS = 0.01
BLOCK = 8


def read_exr_rgb(path):
    """The main R, G, B float channels of an uncompressed or ZIP-compressed scanline EXR."""
    d = open(path, "rb").read()
    i, header = 8, {}
    while d[i] != 0:
        name = d[i:d.index(b"\0", i)]
        i += len(name) + 1
        kind = d[i:d.index(b"\0", i)]
        i += len(kind) + 1
        size = struct.unpack_from("<i", d, i)[0]
        i += 4
        header[name.decode()] = d[i:i + size]
        i += size
    i += 1
    channels, c = [], header["channels"]
    j = 0
    while c[j] != 0:
        name = c[j:c.index(b"\0", j)].decode()
        j += len(name) + 1
        ptype = struct.unpack_from("<i", c, j)[0]
        j += 16
        channels.append((name, ptype))
    compression = header["compression"][0]
    x0, y0, x1, y1 = struct.unpack("<4i", header["dataWindow"])
    w, h = x1 - x0 + 1, y1 - y0 + 1
    lines = {0: 1, 3: 16, 2: 1}[compression]
    chunks = (h + lines - 1) // lines
    offsets = struct.unpack_from(f"<{chunks}Q", d, i)
    sizes = {0: 2, 1: 4, 2: 4}
    out = {name: np.zeros((h, w), np.float32) for name, _ in channels}
    for off in offsets:
        y, n = struct.unpack_from("<2i", d, off)
        raw = d[off + 8:off + 8 + n]
        rows = min(lines, y1 + 1 - y)
        expected = rows * w * sum(sizes[t] for _, t in channels)
        if compression != 0 and n < expected:
            b = np.frombuffer(zlib.decompress(raw), np.uint8).astype(np.int32)
            b = np.cumsum(np.concatenate([b[:1], b[1:] - 128])) & 0xFF  # undo the predictor
            b = b.astype(np.uint8)
            half = (len(b) + 1) // 2
            raw = np.empty(len(b), np.uint8)
            raw[0::2], raw[1::2] = b[:half], b[half:]  # undo the interleave
            raw = raw.tobytes()
        p = 0
        for r in range(rows):
            for name, t in channels:
                dtype = {0: "<u4", 1: "<f2", 2: "<f4"}[t]
                out[name][y - y0 + r] = np.frombuffer(raw, dtype, w, p).astype(np.float32)
                p += w * sizes[t]
    return np.stack([out["R"], out["G"], out["B"]], axis=-1).astype(np.float64)


def blocks(img):
    h, w = img.shape[0] // BLOCK * BLOCK, img.shape[1] // BLOCK * BLOCK
    s = img[:h, :w].sum(axis=2)
    return s.reshape(h // BLOCK, BLOCK, w // BLOCK, BLOCK).sum(axis=(1, 3))


root = Path(sys.argv[1])
ref_file = next((root / "references").glob("*.pfm"))
ref = read_pfm(str(ref_file)).astype(np.float64)
ref_noise = json.load(open(ref_file.with_suffix(".json"))) if ref_file.with_suffix(".json").exists() else {}
scale = np.sqrt(ref ** 2 + EPS)
ref_blocks = blocks(ref)
keep = ref_blocks / BLOCK ** 2 > 1e-3 * ref.mean(axis=(0, 1)).sum()

runs = {}
for task in sorted((root / "tasks").iterdir()):
    if not (task / "done.json").exists():
        continue
    info = json.load(open(task / "task.json"))
    s = info.get("settings", {})
    name = f"{info.get('label')} atlas {s.get('atlas_resolution')}^2, bundles {s.get('bundle_resolution')}^2"
    runs.setdefault(name, []).append(task)

print(f"reference: {ref_file.name}, {ref.shape[1]}x{ref.shape[0]}, mean {ref.mean(axis=(0, 1)).round(5).tolist()}"
      f"{', noise ' + json.dumps(ref_noise) if ref_noise else ''}\n")
print("| contender | directions | relMSE (seeds) | noise | bias^2 | mean ratio g (seeds; average) | "
      "block ratio RMS (seeds) | block bias RMS | max block dev (average) |")
print("|---|---|---|---|---|---|---|---|---|")
biased = []
for name, tasks in runs.items():
    a, b = tasks[0], tasks[1] if len(tasks) > 1 else None
    its = sorted(int(p.stem.split("-")[1]) for p in a.glob("iter-*.exr"))
    for n in (k for k in its if k >= 32):
        ia = read_exr_rgb(a / f"iter-{n}.exr")
        ea = (ia - ref) / scale
        ra = blocks(ia)[keep] / ref_blocks[keep] - 1
        if b is None or not (b / f"iter-{n}.exr").exists():
            print(f"| {name} | {n} | {float((ea ** 2).mean()):.4g} (seed 1) | - | - | "
                  f"{ia[..., 1].mean() / ref[..., 1].mean():.4f} | {float(np.sqrt((ra ** 2).mean())):.4f} | - | "
                  f"{float(np.abs(ra).max()):.4f} |")
            continue
        ib = read_exr_rgb(b / f"iter-{n}.exr")
        eb = (ib - ref) / scale
        rel = [float((ea ** 2).mean()), float((eb ** 2).mean())]
        noise = float(((ea - eb) ** 2).mean() / 2)
        bias2 = float((ea * eb).mean())
        avg = (ia + ib) / 2
        ratio = [float(x[..., 1].mean() / ref[..., 1].mean()) for x in (ia, ib, avg)]
        rb, rv = (blocks(x)[keep] / ref_blocks[keep] - 1 for x in (ib, avg))
        rms = [float(np.sqrt((r ** 2).mean())) for r in (ra, rb)]
        shared = float((ra * rb).mean())
        shared_rms = np.sqrt(shared) if shared > 0 else 0.0
        print(f"| {name} | {n} | {rel[0]:.4g} / {rel[1]:.4g} | {noise:.3g} | {bias2:.3g} | "
              f"{ratio[0]:.4f} / {ratio[1]:.4f}; {ratio[2]:.4f} | {rms[0]:.4f} / {rms[1]:.4f} | "
              f"{shared_rms:.4f}{'' if shared > 0 else ' (<0)'} | {float(np.abs(rv).max()):.4f} |")
        if n == its[-1]:
            # blocks both seeds put off the same way: the candidates for a bias (row, column of the block)
            prod = ra * rb
            where = np.argwhere(keep)
            worst = np.argsort(-prod)[:4]
            biased.append(f"{name}, {n} directions: " + ", ".join(
                f"block ({where[k][0]}, {where[k][1]}) {1 + ra[k]:.2f} / {1 + rb[k]:.2f}" for k in worst))

print("\nBlocks off the same way in both seeds (the largest products (r_1 - 1)(r_2 - 1); block (row, column) "
      f"of {BLOCK} x {BLOCK} pixels, row 0 at the top):\n")
for line in biased:
    print(f"- {line}")
print("\nSame seed, two contenders (common random numbers): relMSE of A against B (B's scale), "
      "mean over seeds (image mean A / B, green; 8 x 8 block ratios A / B: RMS of (ratio - 1), largest |ratio - 1|)\n")
print("| A | B | " + " | ".join(f"{n} directions" for n in (32, 64, 128, 256, 512)) + " |")
print("|---|---|" + "---|" * 5)
names = list(runs)
for i, na in enumerate(names):
    for nb in names[i + 1:]:
        cells = []
        for n in (32, 64, 128, 256, 512):
            rel, ratio, block = [], [], []
            for ta, tb in zip(runs[na], runs[nb]):
                fa, fb = ta / f"iter-{n}.exr", tb / f"iter-{n}.exr"
                if not (fa.exists() and fb.exists()):
                    continue
                ia, ib = read_exr_rgb(fa), read_exr_rgb(fb)
                rel.append(float((((ia - ib) / np.sqrt(ib ** 2 + EPS)) ** 2).mean()))
                ratio.append(float(ia[..., 1].mean() / ib[..., 1].mean()))
                br = blocks(ia)[keep] / blocks(ib)[keep] - 1
                block.append((float(np.sqrt((br ** 2).mean())), float(np.abs(br).max())))
            cells.append(f"{np.mean(rel):.3g} ({np.mean(ratio):.4f}; {np.mean([b[0] for b in block]):.4f}, "
                         f"{max(b[1] for b in block):.3f})" if rel else "-")
        print(f"| {na} | {nb} | " + " | ".join(cells) + " |")
