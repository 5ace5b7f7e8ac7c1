// Emission profiles of point and spot lights, shared by every renderer.
#ifndef BL_SHARED_LIGHTS_H
#define BL_SHARED_LIGHTS_H
#include "GpuTypes.h"

BL_NAMESPACE_BEGIN

// Fraction of the light's intensity emitted along unit direction d (from the light outward).
// Point lights: 1. Spot lights: 1 inside the inner cone, 0 outside the outer cone, smoothstep in
// between (as pbrt-v4's SpotLight).
BL_INLINE float blLightProfile(GpuLight light, vec3 d) {
    if (light.type != kLightSpot) {
        return 1.0f;
    }
    float c = dot(d, light.direction);
    if (c <= light.cosOuter) {
        return 0.0f;
    }
    if (c >= light.cosInner) {
        return 1.0f;
    }
    float x = (c - light.cosOuter) / (light.cosInner - light.cosOuter);
    return x * x * (3.0f - 2.0f * x);
}

BL_NAMESPACE_END
#endif
