#!/usr/bin/python3
"""Writes the stress scenes of issue 19 item 7 (scenes, meshes) into a directory.

    data/stress/generate.py OUT [--big]     write every scene into OUT (--big: also the large meshes)
    data/stress/generate.py --check DIR     exit 1 if DIR differs from what the generator writes

Every scene is self-contained in OUT (it refers to OUT/meshes only), so the same bytes come out
wherever OUT is: data/stress/scenes/ is this script's output without --big, committed so a user
can render a case by hand, and the stress experiment (experiments/stress/run.py) writes a fresh
copy with --big into its output directory, so it never runs a stale or missing file.

Each case is written beside its unperturbed twin (the case list with the twins is in
experiments/stress/cases.py). The base is the point-lit Cornell box (data/cornell-box/cornell-point.toml,
millimetres); `-sky` scenes are the same geometry under a constant unit sky and no point light, for
skylight, which renders environment light only. Meshes whose normals matter carry explicit `vn`;
the rest are flat-faced (quads, boxes), where generated smooth normals (45-degree crease) and flat
shading agree, so the cases do not depend on how a file without normals is shaded.

Standard library only (/usr/bin/python3).
"""
import filecmp
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
CORNELL = os.path.join(HERE, "..", "cornell-box", "meshes")

# The point-lit Cornell box: (mesh, material) and its light, as in data/cornell-box/cornell-point.toml.
CORNELL_MESHES = [("floor", "white"), ("ceiling", "white"), ("backwall", "white"), ("leftwall", "red"),
                  ("rightwall", "green"), ("shortblock", "white"), ("tallblock", "white")]
CORNELL_MATERIALS = [("white", [0.725, 0.71, 0.68]), ("red", [0.63, 0.065, 0.05]), ("green", [0.14, 0.45, 0.091])]
CORNELL_LIGHT = (278.0, 500.0, 279.5)
# The area-lit Cornell box (data/cornell-box/cornell.toml): its light, 0.1 mm below the ceiling, emits radiance.
CORNELL_EMITTER = ("light", [0.78, 0.78, 0.78], [17.0, 12.0, 4.0])
CORNELL_INTENSITY = 50000.0
CORNELL_SIZE = 548.8  # room height (mm): "1e-4 of the room" above the floor is 1e-4 of it
CORNELL_CAMERA = {"position": (278.0, 273.0, -800.0), "target": (278.0, 273.0, 0.0), "fov": 39.3077}

SLIVER_ASPECTS = {"1e4": 10000, "1e5": 100000}
SCALES = {"1e-6": 1e-6, "1e-3": 1e-3, "1e3": 1e3, "1e6": 1e6}
OFFSETS = {"1e2": 1e2, "1e4": 1e4, "1e6": 1e6}
WALLS = {"1e-2": 1e-2, "1e-3": 1e-3, "1e-4": 1e-4, "1e-5": 1e-5}
EXPONENTS = {"1": 1.0, "1e2": 1e2, "1e4": 1e4, "1e6": 1e6}
MILLION_SIDE = 708  # 2 * 708^2 = 1,002,528 triangles

# Meshes above this many triangles are written only with --big (not committed).
BIG_TRIANGLES = 1000


def g(x):
    """A number as TOML/OBJ text: shortest round-trip form, so coordinates keep double precision."""
    return repr(float(x)) if x != int(x) or abs(x) >= 1e15 else str(int(x)) + ".0"


def vec(v):
    return "[" + ", ".join(g(x) for x in v) + "]"


def read_obj(name):
    """Positions and faces (1-based index lists) of one of the Cornell box meshes."""
    vs, fs = [], []
    with open(os.path.join(CORNELL, name + ".obj")) as f:
        for line in f:
            p = line.split()
            if p and p[0] == "v":
                vs.append(tuple(float(x) for x in p[1:4]))
            elif p and p[0] == "f":
                fs.append([int(x.split("/")[0]) for x in p[1:]])
    return vs, fs


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def face_normal(vs, face):
    """Newell's normal of a planar polygon (1-based indices), unit length."""
    n = [0.0, 0.0, 0.0]
    for i in range(len(face)):
        a, b = vs[face[i] - 1], vs[face[(i + 1) % len(face)] - 1]
        n[0] += (a[1] - b[1]) * (a[2] + b[2])
        n[1] += (a[2] - b[2]) * (a[0] + b[0])
        n[2] += (a[0] - b[0]) * (a[1] + b[1])
    length = sum(x * x for x in n) ** 0.5
    return tuple(x / length for x in n)


def obj_text(comment, vs, fs, normals=None):
    """OBJ text; normals: one per face (written as `f v//n`), or None for a file without vn."""
    out = ["# " + line for line in comment.split("\n")]
    out += ["v %s %s %s" % tuple(g(x) for x in v) for v in vs]
    if normals is None:
        out += ["f " + " ".join(str(i) for i in f) for f in fs]
    else:
        unique = sorted(set(normals))
        index = {n: i + 1 for i, n in enumerate(unique)}
        out += ["vn %s %s %s" % tuple(g(x) for x in n) for n in unique]
        out += ["f " + " ".join("%d//%d" % (i, index[n]) for i in f) for f, n in zip(fs, normals)]
    return "\n".join(out) + "\n"


class Writer:
    def __init__(self, out, big):
        self.out, self.big = out, big
        os.makedirs(os.path.join(out, "meshes"), exist_ok=True)

    def write(self, rel, text):
        with open(os.path.join(self.out, rel), "w") as f:
            f.write(text)

    def mesh(self, name, comment, vs, fs, normals=None):
        """Writes meshes/NAME.obj unless it is big and --big is off; returns whether it exists now."""
        if sum(len(f) - 2 for f in fs) > BIG_TRIANGLES and not self.big:
            return False
        self.write("meshes/%s.obj" % name, obj_text(comment, vs, fs, normals))
        return True


def camera_block(position, target, fov, up=(0.0, 1.0, 0.0)):
    return ("[camera]\nposition   = %s\ntarget     = %s\nup         = %s\nfov        = %s\n"
            "fov_axis   = \"x\"\nresolution = [64, 64]\n" % (vec(position), vec(target), vec(up), g(fov)))


def materials_block(materials):
    out = ""
    for name, albedo, *glossy in materials:
        out += "\n[[material]]\nname   = \"%s\"\nalbedo = %s\n" % (name, vec(albedo))
        if glossy:
            out += "specular = %s\nexponent = %s\n" % (vec(glossy[0]), g(glossy[1]))
    return out


def mesh_block(file, material, scale=None, translate=None, emission=None):
    out = "\n[[mesh]]\nfile     = \"meshes/%s.obj\"\nmaterial = \"%s\"\n" % (file, material)
    if emission is not None:
        out += "emission = %s\n" % vec(emission)
    if scale is not None:
        out += "scale    = %s\n" % g(scale)
    if translate is not None:
        out += "translate = %s\n" % vec(translate)
    return out


def light_block(position, intensity):
    return "\n[[light]]\ntype      = \"point\"\nposition  = %s\nintensity = %s\n" % (
        vec(position), vec([intensity] * 3))


SKY_BLOCK = "\n[environment]\nradiance = [1.0, 1.0, 1.0]\n"


def cornell(w, name, comment, meshes=None, extra=(), scale=1.0, offset=0.0, light=CORNELL_LIGHT, sky=True,
            floor="white", area=False):
    """The Cornell box scene NAME.toml (and NAME-sky.toml): `meshes` maps a Cornell mesh to the file
    that replaces it, `extra` adds (file, material) meshes; scale s and offset d move everything as
    x -> s x + d (lights' intensity times s^2, so the image stays the same). area: lit by the box's
    area emitter (radiance, unchanged by s) instead of the point light, and no sky twin."""
    meshes = meshes or {}
    t = lambda p: tuple(scale * x + offset for x in p)  # noqa: E731
    cam = camera_block(t(CORNELL_CAMERA["position"]), t(CORNELL_CAMERA["target"]), CORNELL_CAMERA["fov"])
    body = materials_block([(n, a) for n, a in CORNELL_MATERIALS] + ([(floor, [0.0] * 3)] if floor != "white" else []) +
                           ([CORNELL_EMITTER[:2]] if area else []))
    transform = dict(scale=scale if scale != 1.0 else None, translate=(offset,) * 3 if offset else None)
    for mesh, material in CORNELL_MESHES:
        body += mesh_block(meshes.get(mesh, "cornell-" + mesh), floor if mesh == "floor" else material, **transform)
    for file, material in extra:
        body += mesh_block(file, material, **transform)
    head = "".join("# " + line + "\n" for line in comment.split("\n")) + "\n"
    if area:
        # The emitter is never flipped: emission is one-sided, so its winding is part of the scene.
        name_, albedo, emission = CORNELL_EMITTER
        w.write(name + ".toml", head + cam + body + mesh_block("cornell-light", name_, emission=emission, **transform))
        return
    w.write(name + ".toml", head + cam + body + light_block(t(light), CORNELL_INTENSITY * scale * scale))
    if sky:
        w.write(name + "-sky.toml", head + "# Under a constant unit sky, no point light (for skylight).\n\n" +
                cam + body + SKY_BLOCK)


def sliver_floor(n):
    """The Cornell floor cut into n strips of 2 triangles each (aspect about n), same winding, vn up."""
    v1, v2, v3, v4 = read_obj("floor")[0]
    lerp = lambda a, b, u: tuple(x + (y - x) * u for x, y in zip(a, b))  # noqa: E731
    vs = []
    for i in range(n + 1):
        vs += [lerp(v1, v4, i / n), lerp(v2, v3, i / n)]  # Q_i (x = 552.8 side), P_i (x = 0 side)
    fs = []
    for i in range(n):
        q0, p0, q1, p1 = 2 * i + 1, 2 * i + 2, 2 * i + 3, 2 * i + 4
        fs += [[q0, p0, p1], [q0, p1, q1]]
    return vs, fs


def grid_floor(side):
    """The Cornell floor as a side x side grid of quads cut into triangles, same winding, vn up."""
    v1, v2, v3, v4 = read_obj("floor")[0]
    vs = []
    for i in range(side + 1):
        a = tuple(x + (y - x) * i / side for x, y in zip(v1, v4))
        b = tuple(x + (y - x) * i / side for x, y in zip(v2, v3))
        vs += [tuple(x + (y - x) * j / side for x, y in zip(a, b)) for j in range(side + 1)]
    fs = []
    for i in range(side):
        for j in range(side):
            q0, p0 = i * (side + 1) + j + 1, i * (side + 1) + j + 2
            q1, p1 = q0 + side + 1, p0 + side + 1
            fs += [[q0, p0, p1], [q0, p1, q1]]
    return vs, fs


def box(lo, hi, inward):
    """An axis-aligned box as 6 quads, faces outward (or inward)."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    vs = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    fs = [[1, 4, 3, 2], [5, 6, 7, 8], [1, 2, 6, 5], [4, 8, 7, 3], [1, 5, 8, 4], [2, 3, 7, 6]]  # outward
    return vs, [f[::-1] for f in fs] if inward else fs


def write_cornell_cases(w):
    up = (0.0, 1.0, 0.0)
    for mesh, _ in CORNELL_MESHES:
        vs, fs = read_obj(mesh)
        normals = [face_normal(vs, f) for f in fs]
        w.mesh("cornell-" + mesh, "Cornell box %s (data/cornell-box/meshes), unchanged." % mesh, vs, fs)
        w.mesh("flipped-" + mesh, "Cornell box %s with every face wound the other way, no vn: the normals "
               "follow the winding." % mesh, vs, [f[::-1] for f in fs])
        w.mesh("flipped-vn-" + mesh, "Cornell box %s with every face wound the other way, with the original "
               "(unflipped) face normals as vn." % mesh, vs, [f[::-1] for f in fs], normals)
    cornell(w, "base", "Stress twin: the point-lit Cornell box (data/cornell-box/cornell-point.toml), unperturbed.")
    cornell(w, "flip-flat", "Every face wound the other way, no vn (normals follow the winding).",
            meshes={m: "flipped-" + m for m, _ in CORNELL_MESHES})
    cornell(w, "flip-vn", "Every face wound the other way, with the original normals as vn.",
            meshes={m: "flipped-vn-" + m for m, _ in CORNELL_MESHES})

    write_area_cases(w)

    vs, fs = read_obj("floor")
    for key, n in SLIVER_ASPECTS.items():
        svs, sfs = sliver_floor(n)
        if w.mesh("floor-slivers-" + key, "The Cornell floor as %d strips of 2 triangles (aspect about %s), "
                  "vn up." % (n, key), svs, sfs, [up] * len(sfs)):
            cornell(w, "slivers-" + key, "The floor as %d triangles of aspect about %s (twin: base, the floor "
                    "as 2 triangles)." % (2 * n, key), meshes={"floor": "floor-slivers-" + key})
    a, b, c, d = range(1, 5)
    w.mesh("floor-other-diagonal", "The Cornell floor as 2 triangles cut along the other diagonal: coplanar "
           "with the floor, overlapping it, not duplicates of its triangles.", vs, [[a, b, d], [b, c, d]])
    cornell(w, "coincident", "A second floor, cut along the other diagonal, over the floor (same material).",
            extra=[("floor-other-diagonal", "white")])
    w.mesh("floor-reversed", "The Cornell floor wound the other way (a reversed duplicate).", vs, [f[::-1] for f in fs])
    cornell(w, "reversed-duplicate", "A reversed duplicate of the floor in its own mesh (a mesh drops "
            "duplicates only within itself).", extra=[("floor-reversed", "white")])

    # The floor under the light is black in both: half a point light's flux lands within a few heights of
    # it on the floor below, so with a white floor 1e-4 above and on the floor are different scenes (the
    # first has a bright subpixel spot that lights the box); with a black one they differ by O(1e-4).
    light = CORNELL_LIGHT
    cornell(w, "light-on-floor", "The point light lying on the (black) floor (y = 0) below its usual place: it\n"
            "lights the box above the floor, as 1e-4 above it does.", light=(light[0], 0.0, light[2]), sky=False,
            floor="black")
    cornell(w, "light-above-floor", "Twin of light-on-floor: the light 1e-4 of the room (%s mm) above the black "
            "floor." % g(1e-4 * CORNELL_SIZE), light=(light[0], 1e-4 * CORNELL_SIZE, light[2]), sky=False,
            floor="black")
    for key, s in SCALES.items():
        cornell(w, "scale-" + key, "Everything scaled by %s, the light's intensity by its square: the image "
                "is the base's." % key, scale=s)
    for key, d in OFFSETS.items():
        cornell(w, "offset-" + key, "Everything moved by (%s, %s, %s) mm: the image is the base's." % (key, key, key),
                offset=d)
    gvs, gfs = grid_floor(MILLION_SIDE)
    if w.mesh("floor-1m", "The Cornell floor as a %d^2 grid: %d triangles, vn up." % (MILLION_SIDE, len(gfs)),
              gvs, gfs, [up] * len(gfs)):
        cornell(w, "mesh-1m", "The floor as %d triangles (twin: base, the floor as 2)." % len(gfs),
                meshes={"floor": "floor-1m"})


def write_area_cases(w):
    """The area-lit box (data/cornell-box/cornell.toml) flipped, scaled and moved: the emitter points that
    light it (shadow cubes from points 0.1 mm below the ceiling) must follow the scene as the point light does."""
    vs, fs = read_obj("light")
    w.mesh("cornell-light", "Cornell box light (data/cornell-box/meshes), unchanged.", vs, fs)
    cornell(w, "area-base", "Stress twin: the area-lit Cornell box (data/cornell-box/cornell.toml), unperturbed.",
            area=True)
    cornell(w, "area-flip-flat", "The area-lit box with every reflecting face wound the other way, no vn (the\n"
            "emitter is not flipped: emission is one-sided).", meshes={m: "flipped-" + m for m, _ in CORNELL_MESHES},
            area=True)
    for key in ["1e-6", "1e6"]:
        cornell(w, "area-scale-" + key, "The area-lit box scaled by %s (radiance does not scale): the image is "
                "area-base's." % key, scale=SCALES[key], area=True)
    cornell(w, "area-offset-1e6", "The area-lit box moved by (1e6, 1e6, 1e6) mm: the image is area-base's.",
            offset=OFFSETS["1e6"], area=True)


def write_room_cases(w):
    """Thin walls (light-leak.toml's room) and the closed dark box, in a unit room."""
    vs, fs = box((0, 0, 0), (1, 1, 1), inward=True)
    w.mesh("room", "Closed unit room, faces inward.", vs, fs)
    white = materials_block([("white", [0.8, 0.8, 0.8])])
    camera = camera_block((0.95, 0.5, 0.5), (0.0, 0.5, 0.5), 80.0)
    def room(name, comment, wall, light_x):
        w.write(name + ".toml", "# A unit room split by a wall (as data/analytic/light-leak.toml);\n# " + comment +
                "\n\n" + camera + white + mesh_block("room", "white") + mesh_block(wall, "white") +
                light_block((light_x, 0.5, 0.5), 1.0))

    for key, t in WALLS.items():
        wvs, wfs = box((0.5 - t / 2, 0.0, 0.0), (0.5 + t / 2, 1.0, 1.0), inward=False)
        w.mesh("wall-" + key, "A wall %s of the room thick splitting it at x = 0.5, faces outward." % key, wvs, wfs)
        room("wall-" + key, "the wall is %s of the room thick and the light on its far side: the camera sees\n"
             "# only what light reaches through the wall, so the image must be black." % key, "wall-" + key, 0.2)
    # One lit twin for every thickness: the walls' lit faces differ by at most 5e-3 of the room, which
    # moves the lit image far less than the 1% a leak is judged against.
    room("wall-lit", "twin of the wall-* scenes: the 1e-2 wall with the light mirrored to the camera's side.",
         "wall-1e-2", 0.8)
    vs, fs = box((0, 0, 0), (1, 1, 1), inward=False)
    w.mesh("dark-box", "A closed unit box, faces outward.", vs, fs)
    w.mesh("open-box", "The unit box without its top face (y = 1), faces outward.", vs, [f for f in fs if f != [4, 8, 7, 3]])
    camera = camera_block((0.5, 0.5, 0.9), (0.5, 0.5, 0.0), 80.0)
    head = ("# A closed box with the camera inside and no light inside: no light may reach what the camera\n"
            "# sees. Leaks at the creases (shadow cube texels and bundle pixels straddling the edge where an\n"
            "# outer face meets the lit one) are judged against dark-box-lit.\n")
    w.write("dark-box.toml", head + "# The point light is outside.\n\n" + camera + white +
            mesh_block("dark-box", "white") + light_block((0.5, 2.0, 0.5), 1.0))
    w.write("dark-box-sky.toml", head + "# Under a constant unit sky (for skylight).\n\n" + camera + white +
            mesh_block("dark-box", "white") + SKY_BLOCK)
    lit = "# The lit twin of dark-box.toml, what its leak is measured against: "
    w.write("dark-box-lit.toml", lit + "the same light inside the box.\n\n" + camera + white +
            mesh_block("dark-box", "white") + light_block((0.5, 0.5, 0.5), 1.0))
    w.write("dark-box-lit-sky.toml", lit + "the box open at the top under the\n# constant unit sky (for skylight).\n\n" +
            camera + white + mesh_block("open-box", "white") + SKY_BLOCK)


def write_phong_cases(w):
    """A glossy floor under a point light, the camera zoomed on the highlight so the lobe spans the image."""
    w.mesh("plane", "A 10 x 10 floor at y = 0, vn up.", [(-5, 0, -5), (-5, 0, 5), (5, 0, 5), (5, 0, -5)],
           [[1, 2, 3, 4]], [(0.0, 1.0, 0.0)])
    for key, e in EXPONENTS.items():
        # The lobe cos^e falls to 1/e at an angle of about sqrt(2/e): the view spans about 6 of those.
        fov = min(60.0, 57.29578 * 8.0 / e ** 0.5)
        head = ("# Phong exponent %s on a glossy floor, judged against the reference; the camera looks at the\n"
                "# light's mirror point (0, 0, 1) with a field of view (%s deg) that spans the lobe.\n" % (key, g(fov)))
        body = (camera_block((0.0, 1.0, 2.0), (0.0, 0.0, 1.0), fov) +
                materials_block([("glossy", [0.2, 0.2, 0.2], [0.7, 0.7, 0.7], e)]) + mesh_block("plane", "glossy"))
        w.write("phong-%s.toml" % key, head + "\n" + body + light_block((0.0, 1.0, 0.0), 1.0))
        w.write("phong-%s-sky.toml" % key, head + "# Under a constant unit sky (for skylight).\n\n" + body + SKY_BLOCK)


def generate(out, big):
    w = Writer(out, big)
    write_cornell_cases(w)
    write_room_cases(w)
    write_phong_cases(w)


def check(directory):
    """Whether DIR holds exactly what generate() writes without --big (the committed copy is fresh)."""
    with tempfile.TemporaryDirectory() as tmp:
        generate(tmp, big=False)
        bad = []
        for root, _, files in os.walk(tmp):
            for f in files:
                rel = os.path.relpath(os.path.join(root, f), tmp)
                theirs = os.path.join(directory, rel)
                if not os.path.exists(theirs) or not filecmp.cmp(os.path.join(root, f), theirs, shallow=False):
                    bad.append(rel)
        for rel in bad:
            print("stale or missing: %s (rerun data/stress/generate.py %s)" % (rel, directory), file=sys.stderr)
        return not bad


def main(argv):
    if len(argv) == 3 and argv[1] == "--check":
        return 0 if check(argv[2]) else 1
    if len(argv) in (2, 3) and (len(argv) == 2 or argv[2] == "--big"):
        generate(argv[1], big=len(argv) == 3)
        return 0
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
