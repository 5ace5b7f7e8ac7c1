// Host/device definitions of mode multibounce (modes/multibounce/MultibounceMode.h): the path
// pass's set 1, push constants and emitter table. Set 0 is the camera set (core/gpu/CameraPass.h).
#ifndef BL_MULTIBOUNCE_SHARED_H
#define BL_MULTIBOUNCE_SHARED_H
#include "../../shared/Accumulation.h"
#include "../../shared/BundleTypes.h"

BL_NAMESPACE_BEGIN

// Path pass, set 1.
BL_CONST uint kMultibounceSet = 1u;
BL_CONST uint kMultibounceBindingLights = 0u;     // storage GpuLight[]
BL_CONST uint kMultibounceBindingShadowMaps = 1u; // storage image 2D array (r32f), 6 layers per light
BL_CONST uint kMultibounceBindingEmitters = 2u;   // storage MultibounceEmitter[] (one per draw)

// Emission of the triangles of one draw: triangle id t belongs to the last entry with
// firstTriangle <= t (entries in GpuScene draw order, so firstTriangle ascends). Radiance of the
// front face.
struct MultibounceEmitter {
    vec3 emission;
    uint firstTriangle;
};
BL_STATIC_ASSERT(sizeof(MultibounceEmitter) == 16, "MultibounceEmitter layout");

struct MultibouncePush {
    BundlePoolView pool;       // the K resident, sorted bundles of this iteration
    uint width;                // camera image
    uint height;
    uint seed;                 // run seed
    uint iteration;            // iteration index: decorrelates iterations
    uint lightCount;
    uint shadowResolution;     // texels per cube-face side
    uint emitterCount;
    uint environmentPresent;
    float environmentRotation; // radians about +y
    uint maxSegments;          // at most this many segments per path (1 = emitters only)
    uint rrSegments;           // segments before Russian roulette starts
    float hemispherePdf;       // p_r(d) of a bundle direction on a point's hemisphere: 1 / (2 pi)
    vec2 samplePosition;       // sub-pixel position of this iteration's camera sample, in [0, 1)^2
    uint pathsPerPixel;        // camera paths per pixel through this iteration's bundles
    uint pad0;
};
BL_STATIC_ASSERT(sizeof(MultibouncePush) == 128, "MultibouncePush layout");

BL_CONST uint kMultibounceGroupSize = 8u;

// Russian roulette never keeps a path with probability above this: a path whose throughput stays
// near 1 (white furnace) still ends, at the cost of 5% more variance per surviving segment.
BL_CONST float kMultibounceMaxSurvival = 0.95f;

// Every layer of the reference: emitted, direct, indirect1, indirect2, rest.
BL_CONST uint kMultibounceAccumLayers = kAllPathLayers;

BL_NAMESPACE_END
#endif
