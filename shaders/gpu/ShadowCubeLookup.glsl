// Visibility from cube shadow maps (core/gpu/ShadowCubePass.h): 4x4 PCF with a receiver-plane depth
// test, and the crease rule that keeps a closed room dark (blShadowCreaseOverrules). Define BL_SHADOW_SET and BL_SHADOW_BINDING (where the maps are bound) before including;
// a shader that reads a second cube image of another resolution (e.g. lights' cubes and VPLs'
// cubes) also defines BL_SHADOW_BINDING_2 and passes map 1 to blShadowVisibilityIn, and a third
// (bidir: lights, VPLs and emitter points) BL_SHADOW_BINDING_3, map 2.
// A cube occupies six consecutive layers (CubeFaces.h order) starting at `firstLayer`: 6 l for
// light l, or any cube ShadowCubePass::record(cmd, position, cube, ...) rendered (e.g. a VPL).
#ifndef BL_GPU_SHADOW_CUBE_LOOKUP_GLSL
#define BL_GPU_SHADOW_CUBE_LOOKUP_GLSL
#include "gpu/ShadowTexel.glsl"
#include "shared/CubeFaces.h"

layout(set = BL_SHADOW_SET, binding = BL_SHADOW_BINDING, rgba16ui) uniform readonly uimage2DArray blShadowMaps;
#ifdef BL_SHADOW_BINDING_2
layout(set = BL_SHADOW_SET, binding = BL_SHADOW_BINDING_2, rgba16ui) uniform readonly uimage2DArray blShadowMaps2;
#endif
#ifdef BL_SHADOW_BINDING_3
layout(set = BL_SHADOW_SET, binding = BL_SHADOW_BINDING_3, rgba16ui) uniform readonly uimage2DArray blShadowMaps3;
#endif

// Relative tolerance of the shadow test (receiver-plane depth against the stored distance). The
// receiver's own distance is reproduced to float precision (~1e-6) for planar receivers; 1e-3
// also covers curved receivers over a 4x4-texel PCF footprint, and, being relative, holds at any
// scene scale.
const float kShadowRelativeBias = 1e-3;
// A tap whose centre ray meets the receiver plane at a cosine below this (in magnitude) runs
// parallel to it: it cannot hit the receiver, so it counts as lit.
const float kShadowParallelCosine = 1e-6;
const int kShadowPcfTaps = 4; // per side
// The crease rule ignores a surface seen within this cosine of its own plane from the light (the
// tangent cap of the bundle tests, kBundleMaxOwnSurfaceTangent = 12): its plane crosses a texel's
// whole depth range and says little about where the surface is.
const float kShadowCreaseMinCosine = 1.0 / 12.0;
// x within this distance (relative to the light's) of a surface's plane lies on it, at the crease
// itself (a few times the float precision of a G-buffer position), where which side x's own surface
// extends to cannot be told from the map: a closed room lit from outside and a room lit from inside
// show the same taps there. Such x keep the lit room's answer.
const float kShadowOnPlane = 1e-5;
// A lit tap sees something other than x's plane when its stored distance differs from the
// receiver's by more than this (relative): x's own planar surface is reproduced to ~1e-6, and to
// some 1e-5 where a cube sees it at grazing angles (a VPL's cube looking along the ceiling it sits
// on), which should not run the rule.
const float kShadowPastPlane = 1e-4;
// The distinct candidate planes the rule keeps (a crease has one; a corner two or three).
const int kShadowCreasePlanes = 4;
const uint kShadowCubeFaces = 6u; // layers per cube

// Projects direction d (from the cube's centre) onto its cube face: continuous texel coordinates.
vec2 blShadowFaceTexel(vec3 d, uint face, float resolution) {
    vec3 r, u, f;
    blCubeFaceBasis(face, r, u, f);
    float z = dot(d, f);
    vec2 xy = vec2(dot(d, r), dot(d, u)) / z;
    return vec2(xy.x + 1.0, 1.0 - xy.y) * (0.5 * resolution);
}

// Texel `texel` of layer `layer` of map 0 (BL_SHADOW_BINDING), 1 (BL_SHADOW_BINDING_2) or 2
// (BL_SHADOW_BINDING_3), packed (ShadowTexel.glsl). A branch, not an image array: arrays of storage
// images indexed by a non-constant need shaderStorageImageArrayDynamicIndexing, which lavapipe lacks.
uvec4 blShadowTexel(uint map, ivec2 texel, uint layer) {
#ifdef BL_SHADOW_BINDING_3
    if (map == 2u) {
        return imageLoad(blShadowMaps3, ivec3(texel, int(layer)));
    }
#endif
#ifdef BL_SHADOW_BINDING_2
    if (map != 0u) {
        return imageLoad(blShadowMaps2, ivec3(texel, int(layer)));
    }
#endif
    return imageLoad(blShadowMaps, ivec3(texel, int(layer)));
}

// The texel's centre ray (unit, from the cube's centre) on the face with basis (r, u, f).
vec3 blShadowCentreRay(ivec2 texel, vec3 r, vec3 u, vec3 f, float res) {
    vec2 c = (vec2(texel) + 0.5) / res * 2.0 - 1.0;
    return normalize(f + c.x * r - c.y * u);
}

// One PCF tap: 1 when texel `texel` of the face with basis (r, u, f), at layer `layer` of map
// `map`, sees the cube's centre from the receiver plane through p (relative to the centre) with
// normal n, else 0. `pastPlane` is set where the tap is lit by something other than the receiver
// plane itself (a surface beyond it, nothing, or one within the tolerance before it): the only lit
// taps the crease rule below can overrule. The tap compares the stored distance along its texel's centre ray with the
// distance at which that same ray meets the receiver's tangent plane, so a planar receiver never
// shadows itself and no scale-dependent bias is needed.
float blShadowTap(uint map, uint layer, ivec2 texel, vec3 r, vec3 u, vec3 f, float res, vec3 p, vec3 n,
                  inout bool pastPlane) {
    vec3 centreRay = blShadowCentreRay(texel, r, u, f, res);
    float denom = dot(centreRay, n);
    if (denom >= -kShadowParallelCosine) {
        return 1.0; // the tap's ray runs parallel to or behind the receiver plane
    }
    float receiver = dot(p, n) / denom;
    float stored = blShadowTexelDistance(blShadowTexel(map, texel, layer));
    bool lit = stored >= receiver * (1.0 - kShadowRelativeBias);
    pastPlane = pastPlane || (lit && abs(stored - receiver) > receiver * kShadowPastPlane);
    return lit ? 1.0 : 0.0;
}

// Tap `tap` (continuous texel coordinates on face `face`, basis (r, u, f)), which may lie beyond the
// face's edge: the face it continues on, its basis and its texel.
void blShadowTapTexel(vec2 tap, uint face, vec3 r, vec3 u, vec3 f, uint resolution, out uint tapFace, out vec3 tr,
                      out vec3 tu, out vec3 tf, out ivec2 texel) {
    float res = float(resolution);
    vec2 xy = vec2(tap.x / res * 2.0 - 1.0, 1.0 - tap.y / res * 2.0);
    vec3 dir = f + xy.x * r + xy.y * u;
    tapFace = blCubeFaceOf(dir);
    vec2 tapSt = tapFace == face ? tap : blShadowFaceTexel(dir, tapFace, res);
    texel = clamp(ivec2(floor(tapSt)), ivec2(0), ivec2(int(resolution) - 1));
    blCubeFaceBasis(tapFace, tr, tu, tf);
}

// ---- The crease rule ----
// The receiver-plane test extends x's plane over the PCF footprint. Where x lies within two texels
// of a crease of a closed room that lies on the room's outline seen from an outside light, the
// extension leaves the room: the taps beyond the crease pass outside it, find nothing in front of
// x's plane and count as lit, and light leaks in along every such crease (data/stress dark-box).
// The rule: a surface another tap found in shadow (point q, stored normal m of either sign) is a
// crease candidate when
//   (a) it lies in front of x's plane (toward the light) beyond the shadow test's tolerance,
//   (b) it is not seen within kShadowCreaseMinCosine of its own plane, and
//   (c) its plane and x's meet along a line that passes, in the light's view, within the
//       footprint of both x and q (blShadowCreaseNearBoth): x's surface may end there.
// A lit tap, with receiver point r (where its centre ray meets x's plane), is overruled (counted in
// shadow) when a candidate's plane parts r from x (r lies beyond the crease, on no surface x's
// plane continues to) or parts r from the light (the tap's ray passed the candidate's outline and
// reached x's plane behind it); and, where r lies on the candidate's plane (the tap saw the crease
// itself), when x lies behind that plane from the light. A lit room's crease keeps every lit tap on
// x's side of the other wall (its taps beyond the wall were in shadow already) and on the light's
// side, a convex edge has no candidate (the other face lies behind x's plane), and an occluder far
// from x fails (c): open scenes keep the filter's answer. Only footprints with taps both lit and in
// shadow (penumbrae) run it. A filter of one tap (emitter points, vpl_shadow_taps = 1) has none:
// its crease leak stays (rooms lit from outside by area lights; the test counts it). Judging its
// tap with the surfaces of x's 2x2 footprint closes it, but cost every such lookup four probes on
// a SIMD CPU driver: raster's shade pass x1.6 on the area-lit Cornell box. Emitter points' cubes
// therefore store no normal (ShadowCubePass::forPositions); VPL cubes store it whatever their taps.
// It runs only where a lit tap sees something other than x's plane (kShadowPastPlane: a leak's taps
// pass outside the room; a lit tap that sees x's own planar surface, as nearly all do, needs no
// rule), which keeps its cost to the few such footprints on a GPU. A SIMD CPU driver (lavapipe)
// runs the body under a lane mask whether or not a lane needs it: there every lookup pays it
// (measured on the Cornell box with a point light, with the cubes' normals: raster's shade pass
// x1.18, bidir's evaluate x1.22, multibounce's paths x1.11).
// What stays open (tests/core/gpu/ShadowCubeCreaseTest.cpp counts it): a crease whose other face no
// tap can show (the light sees neither of its sides: a third face hides it), x on the crease
// itself (kShadowOnPlane), and a footprint whose lit taps all see x's plane within kShadowPastPlane:
// a texel centre ray through the crease line itself, where the two faces tie in depth and the one
// kept may be x's own (a crease that runs exactly through a row of texel centres).

// The distance, across the unit ray `ray`, from a point to the line through it + v along `line`:
// where the two lie in the light's view.
float blShadowAcrossRay(vec3 v, vec3 line, vec3 ray) {
    vec3 pv = v - dot(v, ray) * ray;
    vec3 pl = line - dot(line, ray) * ray;
    float l2 = dot(pl, pl);
    return length(l2 > 1.0e-8 ? pv - dot(pv, pl) / l2 * pl : pv);
}

// (c): whether the planes through p (normal n) and q (normal m, seen along the unit ray `ray` from
// the cube's centre) meet along a line that passes, in the light's view, within the footprint of
// both: 2 sqrt(2) texels, the reach of the 4 x 4 taps' texel centres from x's own direction (a face
// texel spans at most 2 / res of the distance). Parallel planes never meet.
bool blShadowCreaseNearBoth(vec3 p, vec3 n, vec3 q, vec3 m, vec3 ray, float res) {
    vec3 line = cross(n, m);
    float sine = length(line);
    if (sine < 1.0e-4) {
        return false;
    }
    line /= sine;
    // From each point to the line's nearest point within its own plane.
    vec3 pIn = cross(line, n);
    vec3 qIn = cross(line, m);
    vec3 pToLine = dot(q - p, m) / dot(pIn, m) * pIn;
    vec3 qToLine = dot(p - q, n) / dot(qIn, n) * qIn;
    float limit = 2.0 * 1.41421356 * 2.0 / res;
    return blShadowAcrossRay(qToLine, line, ray) <= limit * length(q) &&
           blShadowAcrossRay(pToLine, line, p / length(p)) <= limit * length(p);
}

// Tap t of the filter's taps x taps around st: its centre ray and packed texel; false where its ray
// runs parallel to or behind x's plane (lit without a receiver point).
bool blShadowCreaseProbe(uint map, uint firstLayer, uint resolution, uint face, vec3 r, vec3 u, vec3 f, vec2 st,
                         vec3 n, int taps, int t, out vec3 ray, out uvec4 packed) {
    float centre = 0.5 * float(taps - 1);
    vec2 tap = st + vec2(float(t % taps) - centre, float(t / taps) - centre);
    uint tapFace;
    vec3 tr, tu, tf;
    ivec2 texel;
    blShadowTapTexel(tap, face, r, u, f, resolution, tapFace, tr, tu, tf, texel);
    ray = blShadowCentreRay(texel, tr, tu, tf, float(resolution));
    packed = blShadowTexel(map, texel, firstLayer + tapFace);
    return dot(ray, n) < -kShadowParallelCosine;
}

// The overrule for the lit taps of a mixed filter of taps x taps (2 to 4) of map `map` around st
// on face `face` (basis r, u, f): how many of its lit taps the crease rule puts in shadow. p: the
// receiver relative to the cube's centre; n: its normal toward the light.
int blShadowCreaseOverrules(uint map, uint firstLayer, uint resolution, uint face, vec3 r, vec3 u, vec3 f, vec2 st,
                            vec3 p, vec3 n, const int taps) {
    const int count = taps * taps;
    float res = float(resolution);
    float epsilon = kShadowRelativeBias * length(p);
    float onPlaneTolerance = kShadowOnPlane * length(p);
    // First the candidates: distinct planes of surfaces found in shadow that pass (a) to (c).
    vec3 planePoint[kShadowCreasePlanes];
    vec3 planeNormal[kShadowCreasePlanes];
    int planes = 0;
    for (int t = 0; t < count; ++t) {
        vec3 ray;
        uvec4 packed;
        if (!blShadowCreaseProbe(map, firstLayer, resolution, face, r, u, f, st, n, taps, t, ray, packed)) {
            continue;
        }
        float stored = blShadowTexelDistance(packed);
        vec3 m;
        vec3 q = stored * ray;
        if (stored >= dot(p, n) / dot(ray, n) * (1.0 - kShadowRelativeBias) || planes == kShadowCreasePlanes ||
            !blShadowTexelNormal(packed, m) || !(dot(q - p, n) > epsilon) ||
            abs(dot(m, ray)) < kShadowCreaseMinCosine) {
            continue; // lit, full, or not a candidate
        }
        bool known = false; // the plane of a candidate already kept (one face seen by several taps)
        for (int k = 0; k < planes; ++k) {
            known = known || (abs(dot(m, planeNormal[k])) > 0.9999 && abs(dot(q - planePoint[k], planeNormal[k])) <= epsilon);
        }
        if (!known && blShadowCreaseNearBoth(p, n, q, m, ray, res)) {
            planePoint[planes] = q;
            planeNormal[planes] = m;
            ++planes;
        }
    }
    if (planes == 0) {
        return 0;
    }
    // Then the lit taps of the filter against them.
    int overruled = 0;
    for (int t = 0; t < count; ++t) {
        vec3 ray;
        uvec4 packed;
        if (!blShadowCreaseProbe(map, firstLayer, resolution, face, r, u, f, st, n, taps, t, ray, packed)) {
            continue;
        }
        float receiver = dot(p, n) / dot(ray, n);
        if (blShadowTexelDistance(packed) < receiver * (1.0 - kShadowRelativeBias)) {
            continue; // in shadow already
        }
        vec3 rPoint = receiver * ray;
        for (int k = 0; k < planes; ++k) {
            float sr = dot(rPoint - planePoint[k], planeNormal[k]);
            float sx = dot(p - planePoint[k], planeNormal[k]);
            float sl = -dot(planePoint[k], planeNormal[k]); // the light's side
            // x on the plane (the crease itself, within float precision): which side its surface
            // extends to cannot be told, and the lit room's answer is kept.
            sx = abs(sx) <= onPlaneTolerance ? 0.0 : sx;
            bool across = abs(sr) > epsilon ? sr * sx < 0.0 || sr * sl < 0.0
                                            : sx * sl < 0.0 && abs(sx) > epsilon && abs(sl) > epsilon;
            if (across) {
                ++overruled;
                break;
            }
        }
    }
    return overruled;
}

// Fraction of the taps x taps PCF taps (1 to 4 a side; a constant, so the loops unroll) of map
// `map` that see the cube's centre from receiver point p (relative to the centre) with normal n
// (blShadowTap), after the crease rule where `creaseRule` (the tests turn it off to show what it
// does).
float blShadowFilter(uint map, uint firstLayer, uint resolution, vec3 p, vec3 n, const int taps, bool creaseRule) {
    const float res = float(resolution);
    uint face = blCubeFaceOf(p);
    vec3 r, u, f;
    blCubeFaceBasis(face, r, u, f);
    vec2 st = blShadowFaceTexel(p, face, res);
    float centre = 0.5 * float(taps - 1);
    float lit = 0.0;
    // A tap a texel or more inside the face (most of them): its centre direction f + x r + y u has
    // |x|, |y| < 1, so the face lookup below would choose this face and this texel; it is read
    // directly. The others are marked (bit j * taps + i) for the general path.
    uint nearEdge = 0u;
    bool pastPlane = false;
    for (int j = 0; j < taps; ++j) {
        for (int i = 0; i < taps; ++i) {
            vec2 tap = st + vec2(float(i) - centre, float(j) - centre);
            if (all(greaterThanEqual(tap, vec2(1.0))) && all(lessThan(tap, vec2(res - 1.0)))) {
                lit += blShadowTap(map, firstLayer + face, ivec2(floor(tap)), r, u, f, res, p, n, pastPlane);
            } else {
                nearEdge |= 1u << uint(j * taps + i);
            }
        }
    }
    // Taps near or beyond the face's edge; those beyond it continue on the neighbouring face. A loop
    // over the marked taps only: SIMD CPU drivers (lavapipe) run both sides of a branch under a lane
    // mask, but a loop only as often as its busiest lane needs.
    for (; nearEdge != 0u; nearEdge &= nearEdge - 1u) {
        int t = findLSB(nearEdge);
        vec2 tap = st + vec2(float(t % taps) - centre, float(t / taps) - centre);
        uint tapFace;
        vec3 tr, tu, tf;
        ivec2 texel;
        blShadowTapTexel(tap, face, r, u, f, resolution, tapFace, tr, tu, tf, texel);
        lit += blShadowTap(map, firstLayer + tapFace, texel, tr, tu, tf, res, p, n, pastPlane);
    }
    if (creaseRule && taps > 1 && pastPlane && lit > 0.0 && lit < float(taps * taps)) {
        // Clamped: the rule overrules lit taps only, but a float sum must not go below zero.
        lit = max(lit - float(blShadowCreaseOverrules(map, firstLayer, resolution, face, r, u, f, st, p, n, taps)), 0.0);
    }
    return lit / float(taps * taps);
}

// blShadowFilter with the crease rule.
float blShadowVisibilityTaps(uint map, uint firstLayer, uint resolution, vec3 p, vec3 n, const int taps) {
    return blShadowFilter(map, firstLayer, resolution, p, n, taps, true);
}

float blShadowVisibilityIn(uint map, uint firstLayer, uint resolution, vec3 p, vec3 n) {
    return blShadowVisibilityTaps(map, firstLayer, resolution, p, n, kShadowPcfTaps);
}

// The same on map 0 (the only one unless BL_SHADOW_BINDING_2 is defined).
float blShadowVisibility(uint firstLayer, uint resolution, vec3 p, vec3 n) {
    return blShadowVisibilityIn(0u, firstLayer, resolution, p, n);
}

#endif
