// Visibility from cube shadow maps (core/gpu/ShadowCubePass.h): 4x4 PCF with a receiver-plane depth
// test. Define BL_SHADOW_SET and BL_SHADOW_BINDING (where the maps are bound) before including;
// a shader that reads a second cube image of another resolution (e.g. lights' cubes and VPLs'
// cubes) also defines BL_SHADOW_BINDING_2 and passes map 1 to blShadowVisibilityIn, and a third
// (bidir: lights, VPLs and emitter points) BL_SHADOW_BINDING_3, map 2.
// A cube occupies six consecutive layers (CubeFaces.h order) starting at `firstLayer`: 6 l for
// light l, or any cube ShadowCubePass::record(cmd, position, cube, ...) rendered (e.g. a VPL).
#ifndef BL_GPU_SHADOW_CUBE_LOOKUP_GLSL
#define BL_GPU_SHADOW_CUBE_LOOKUP_GLSL
#include "shared/CubeFaces.h"

layout(set = BL_SHADOW_SET, binding = BL_SHADOW_BINDING, r32f) uniform readonly image2DArray blShadowMaps;
#ifdef BL_SHADOW_BINDING_2
layout(set = BL_SHADOW_SET, binding = BL_SHADOW_BINDING_2, r32f) uniform readonly image2DArray blShadowMaps2;
#endif
#ifdef BL_SHADOW_BINDING_3
layout(set = BL_SHADOW_SET, binding = BL_SHADOW_BINDING_3, r32f) uniform readonly image2DArray blShadowMaps3;
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
const uint kShadowCubeFaces = 6u; // layers per cube

// Projects direction d (from the cube's centre) onto its cube face: continuous texel coordinates.
vec2 blShadowFaceTexel(vec3 d, uint face, float resolution) {
    vec3 r, u, f;
    blCubeFaceBasis(face, r, u, f);
    float z = dot(d, f);
    vec2 xy = vec2(dot(d, r), dot(d, u)) / z;
    return vec2(xy.x + 1.0, 1.0 - xy.y) * (0.5 * resolution);
}

// The stored distance of texel `texel` of layer `layer` of map 0 (BL_SHADOW_BINDING) or map 1
// (BL_SHADOW_BINDING_2). A branch, not an image array: arrays of storage images indexed by a
// non-constant need shaderStorageImageArrayDynamicIndexing, which lavapipe lacks.
float blShadowStored(uint map, ivec2 texel, uint layer) {
#ifdef BL_SHADOW_BINDING_3
    if (map == 2u) {
        return imageLoad(blShadowMaps3, ivec3(texel, int(layer))).r;
    }
#endif
#ifdef BL_SHADOW_BINDING_2
    if (map != 0u) {
        return imageLoad(blShadowMaps2, ivec3(texel, int(layer))).r;
    }
#endif
    return imageLoad(blShadowMaps, ivec3(texel, int(layer))).r;
}

// One PCF tap: 1 when texel `texel` of the face with basis (r, u, f), at layer `layer` of map
// `map`, sees the cube's centre from the receiver plane through p (relative to the centre) with
// normal n, else 0. The tap compares the stored distance along its texel's centre ray with the
// distance at which that same ray meets the receiver's tangent plane, so a planar receiver never
// shadows itself and no scale-dependent bias is needed.
float blShadowTap(uint map, uint layer, ivec2 texel, vec3 r, vec3 u, vec3 f, float res, vec3 p, vec3 n) {
    vec2 c = (vec2(texel) + 0.5) / res * 2.0 - 1.0;
    vec3 centreRay = normalize(f + c.x * r - c.y * u);
    float denom = dot(centreRay, n);
    if (denom >= -kShadowParallelCosine) {
        return 1.0; // the tap's ray runs parallel to or behind the receiver plane
    }
    float receiver = dot(p, n) / denom;
    float stored = blShadowStored(map, texel, layer);
    return stored >= receiver * (1.0 - kShadowRelativeBias) ? 1.0 : 0.0;
}

// Fraction of the taps x taps PCF taps (1 to 4 a side; a constant, so the loops unroll) of map
// `map` that see the cube's centre from receiver point p (relative to the centre) with normal n
// (blShadowTap).
float blShadowVisibilityTaps(uint map, uint firstLayer, uint resolution, vec3 p, vec3 n, const int taps) {
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
    for (int j = 0; j < taps; ++j) {
        for (int i = 0; i < taps; ++i) {
            vec2 tap = st + vec2(float(i) - centre, float(j) - centre);
            if (all(greaterThanEqual(tap, vec2(1.0))) && all(lessThan(tap, vec2(res - 1.0)))) {
                lit += blShadowTap(map, firstLayer + face, ivec2(floor(tap)), r, u, f, res, p, n);
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
        vec2 xy = vec2(tap.x / res * 2.0 - 1.0, 1.0 - tap.y / res * 2.0);
        vec3 dir = f + xy.x * r + xy.y * u;
        uint tapFace = blCubeFaceOf(dir);
        vec2 tapSt = tapFace == face ? tap : blShadowFaceTexel(dir, tapFace, res);
        ivec2 texel = clamp(ivec2(floor(tapSt)), ivec2(0), ivec2(int(resolution) - 1));
        vec3 tr, tu, tf;
        blCubeFaceBasis(tapFace, tr, tu, tf);
        lit += blShadowTap(map, firstLayer + tapFace, texel, tr, tu, tf, res, p, n);
    }
    return lit / float(taps * taps);
}

float blShadowVisibilityIn(uint map, uint firstLayer, uint resolution, vec3 p, vec3 n) {
    return blShadowVisibilityTaps(map, firstLayer, resolution, p, n, kShadowPcfTaps);
}

// The same on map 0 (the only one unless BL_SHADOW_BINDING_2 is defined).
float blShadowVisibility(uint firstLayer, uint resolution, vec3 p, vec3 n) {
    return blShadowVisibilityIn(0u, firstLayer, resolution, p, n);
}

#endif
