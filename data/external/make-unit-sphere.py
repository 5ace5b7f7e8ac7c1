#!/usr/bin/python3
"""Writes meshes/unit-sphere-64x32.obj: the unit sphere as Mitsuba scenes are imported (64 segments
around the z axis, 32 rings, the seam's vertices repeated, smooth normals, counter-clockwise from
outside), for TOML twins of Mitsuba scenes with spheres (veach-mis.toml places it by scale and
translate). Written from the parametrization, not from the importer's code."""
import math
import os

AROUND, RINGS = 64, 32
out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "meshes", "unit-sphere-64x32.obj")
lines = ["# unit sphere, 64 x 32, written by make-unit-sphere.py"]
for r in range(RINGS + 1):
    theta = math.pi * r / RINGS
    for a in range(AROUND + 1):
        phi = 2.0 * math.pi * a / AROUND
        n = (math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta))
        lines.append("v %.9g %.9g %.9g" % n)
        lines.append("vn %.9g %.9g %.9g" % n)
for r in range(RINGS):
    for a in range(AROUND):
        i = r * (AROUND + 1) + a + 1  # OBJ indices start at 1
        j = i + AROUND + 1
        if r > 0:
            lines.append(f"f {i}//{i} {j}//{j} {i + 1}//{i + 1}")
        if r + 1 < RINGS:
            lines.append(f"f {i + 1}//{i + 1} {j}//{j} {j + 1}//{j + 1}")
open(out, "w").write("\n".join(lines) + "\n")
print("wrote", out)
