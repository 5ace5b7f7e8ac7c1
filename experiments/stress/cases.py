"""The stress suite of issue 19 item 7: every mode x every case, each with how it is judged.

Scenes are data/stress/generate.py's (the runner writes them, with the large meshes, into its output
directory). A case is judged by one of these kinds (verdicts in verdicts.py):

  twin       the image against the unperturbed twin's at the same seeds (common random numbers):
             ratio of image means and 8 x 8 block means, within the seeds' spread
  leak       light behind a thin wall or into a closed box: image mean / the lit twin's <= 1% (the
             bound the issue sets for data/analytic/light-leak.toml), judged on its upper confidence
             limit; exactly black passes outright
  reference  the image against the reference path tracer's of the same scene (Phong lobes)
  unlit      the scene has only lights this mode cannot render: it must refuse or warn, not write a
             black image silently

skylight renders environment light only: it runs each case's `-sky` twin (the same geometry under a
constant sky, no point light) where the case means something under a sky, and n/a where the case is
about a point light.
"""
import collections

MODES = ["raster", "reference", "skylight", "multibounce", "bidir", "atlas"]

# Budget per mode at 32 x 32: small enough for the whole suite in under 30 minutes on 2 shared cores,
# and cheaper than the defaults where the default cost is in the number of samples only (bundle_count,
# pairs_per_frame); atlas' bundle and atlas resolution are lowered to 128 (its light leak falls as
# 1 / atlas resolution, so this is the harder setting for the thin walls). Everything else: defaults.
SETTINGS = {
    "raster": (4, []),
    "reference": (64, []),
    "skylight": (32, []),
    "multibounce": (4, ["bundle_count=8"]),
    "bidir": (2, ["pairs_per_frame=4"]),
    "atlas": (32, ["bundle_resolution=128", "atlas_resolution=128"]),
}
REFERENCE_SPP = 256  # the reference's budget where it is the truth (kind reference)
SIZE = 32
SEEDS = [0, 1, 2]
# bidir's paired ratios spread most (its VPLs follow the geometry, so case and twin share less of
# their noise): six seeds, so that t se can resolve 2% (verdicts.RESOLUTION).
MODE_SEEDS = {"bidir": [0, 1, 2, 3, 4, 5]}
# skylight against the reference (unpaired): each seed is a Cranley-Patterson shift of the same 32
# Halton directions, whose error on the diffuse part spreads about +-0.6 % between shifts, and three
# shifts can agree by chance (seeds 0-2 all read +0.8 % on phong-*-sky, seed 3 -0.5 %): eight seeds,
# so the spread is seen. Against its twin the shifts are paired and three seeds do.
KIND_SEEDS = {("skylight", "reference"): [0, 1, 2, 3, 4, 5, 6, 7]}
# The 1M-triangle case loads a 50 MB OBJ per render (about 15 s here): two seeds.
CASE_SEEDS = {"mesh-1m": [0, 1]}

# Where the twin is not the same scene to float precision, the bound on how far its image may differ
# (replacing verdicts.FLOAT_FLOOR). light-on-floor: moving a point light by h changes the irradiance of
# a point at distance r by at most about 2h/r (1/r^2) + h/r (the cosine), and moves shadow edges by
# about h/d of their distance: 3h/d with d = 11.91 mm, the nearest surface to the light but the floor
# (the tall block's face; measured from the meshes), h = 0.05488 mm.
CASE_FLOOR = {"light-on-floor": 3 * 0.05488 / 11.91}


def seeds(mode, case):
    return CASE_SEEDS.get(case.name, KIND_SEEDS.get((mode, case.kind), MODE_SEEDS.get(mode, SEEDS)))

Case = collections.namedtuple("Case", "name kind scene twin sky note")
_SKY_NA = "n/a: a point- or area-light case (skylight renders environment light only)"


def _cases():
    c = [
        Case("flip-flat", "twin", "flip-flat", "base", True, "every face wound the other way, no vn"),
        Case("flip-vn", "twin", "flip-vn", "base", True, "every face wound the other way, original normals as vn"),
    ]
    for k in ["1e-2", "1e-3", "1e-4", "1e-5"]:
        c.append(Case("wall-" + k, "leak", "wall-" + k, "wall-lit", False, "thin wall %s of the room" % k))
    for k in ["1e4", "1e5"]:
        c.append(Case("slivers-" + k, "twin", "slivers-" + k, "base", True, "floor of slivers, aspect " + k))
    c += [
        Case("coincident", "twin", "coincident", "base", True, "overlapping coplanar floor"),
        Case("reversed-duplicate", "twin", "reversed-duplicate", "base", True, "reversed duplicate floor"),
        Case("light-on-floor", "twin", "light-on-floor", "light-above-floor", False,
             "point light on the floor vs 1e-4 of the room above it"),
    ]
    for k in ["1e-6", "1e-3", "1e3", "1e6"]:
        c.append(Case("scale-" + k, "twin", "scale-" + k, "base", True, "scaled by %s, intensity by its square" % k))
    for k in ["1e2", "1e4", "1e6"]:
        c.append(Case("offset-" + k, "twin", "offset-" + k, "base", True, "moved by %s mm on every axis" % k))
    for k in ["1", "1e2", "1e4", "1e6"]:
        c.append(Case("phong-" + k, "reference", "phong-" + k, "phong-" + k, True, "Phong exponent " + k))
    # Area-lit (the emitter points every GPU mode lights area emitters by): no sky twin (n/a for skylight).
    c.append(Case("area-flip-flat", "twin", "area-flip-flat", "area-base", False,
                  "area light; every reflecting face wound the other way"))
    for k in ["1e-6", "1e6"]:
        c.append(Case("area-scale-" + k, "twin", "area-scale-" + k, "area-base", False, "area light; scaled by " + k))
    c.append(Case("area-offset-1e6", "twin", "area-offset-1e6", "area-base", False, "area light; moved by 1e6 mm"))
    c += [
        Case("mesh-1m", "twin", "mesh-1m", "base", True, "floor as 1,002,528 triangles"),
        Case("dark-box", "leak", "dark-box", "dark-box-lit", True, "closed box, the light outside"),
        Case("point-lit", "unlit", "base", None, False, "a scene lit by a point light only"),
        Case("area-lit", "unlit", "area-base", None, False, "a scene lit by an area emitter only"),
    ]
    return c


CASES = _cases()

# The fast subset CI runs (tests/stress): the cheapest, most telling pairs, in about a minute.
CI = [("raster", "flip-flat"), ("raster", "offset-1e6"), ("raster", "dark-box"), ("raster", "area-offset-1e6"),
      ("reference", "light-on-floor"),
      ("multibounce", "flip-flat"), ("multibounce", "wall-1e-3"), ("skylight", "point-lit")]


def applies(mode, case):
    """None if the mode runs the case, else why not (shown in the table)."""
    if case.kind == "unlit":
        return None if mode == "skylight" else "n/a"
    if case.kind == "reference" and mode == "reference":
        return "n/a: the ground truth"
    if mode == "skylight" and not case.sky:
        return _SKY_NA
    return None


def scene_for(mode, case, scene):
    """The scene file a mode renders for one of a case's scenes (skylight: its sky twin)."""
    return scene + "-sky" if mode == "skylight" and case.kind != "unlit" else scene
