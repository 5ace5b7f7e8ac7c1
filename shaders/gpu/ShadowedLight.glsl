// Irradiance of one point or spot light at a receiver, visibility from the light's cube shadow map
// (ShadowCubeLookup.glsl, included; define BL_SHADOW_SET and BL_SHADOW_BINDING first). The one
// place where a point/spot light's cosine (the normal the caller passes: raster and multibounce the
// shading normal turned toward the eye, atlas the texel's side), profile and shadow test live:
// raster's and multibounce's light loops, atlas's direct and highlight passes. bidir's lightAt
// keeps its own copy of the shape: it needs the light ray's density before the shadow test (MIS).
#ifndef BL_GPU_SHADOWED_LIGHT_GLSL
#define BL_GPU_SHADOWED_LIGHT_GLSL
#include "gpu/ShadowCubeLookup.glsl"
#include "shared/Lights.h"

// Light `light` (cube `cube` of the maps, `resolution` texels a side) at point p with unit normal n:
// the direction toward the light `wi` and the factor of its intensity that reaches the plane of n,
// weight = profile visibility cos / r^2. False (weight 0) when p is behind n (lit from the side the
// caller does not see), outside a spot's cone, at the light, or in shadow.
bool blShadowedLightWeight(GpuLight light, uint cube, uint resolution, vec3 p, vec3 n, out vec3 wi, out float weight) {
    weight = 0.0;
    wi = vec3(0.0);
    vec3 d = p - light.position;
    float r2 = dot(d, d);
    if (!(r2 > 0.0)) {
        return false;
    }
    vec3 fromLight = d * inversesqrt(r2);
    wi = -fromLight;
    float cosine = dot(n, wi);
    float profile = blLightProfile(light, fromLight);
    if (cosine <= 0.0 || profile <= 0.0) {
        return false;
    }
    float visibility = blShadowVisibility(kShadowCubeFaces * cube, resolution, d, n);
    if (visibility <= 0.0) {
        return false;
    }
    weight = profile * visibility * cosine / r2;
    return true;
}

// The same as irradiance I weight on the plane of n.
bool blShadowedLight(GpuLight light, uint cube, uint resolution, vec3 p, vec3 n, out vec3 wi, out vec3 irradiance) {
    float weight;
    bool lit = blShadowedLightWeight(light, cube, resolution, p, n, wi, weight);
    irradiance = lit ? light.intensity * weight : vec3(0.0);
    return lit;
}

#endif
