// Irradiance of one point or spot light at a receiver, visibility from the light's cube shadow map
// (ShadowCubeLookup.glsl, included; define BL_SHADOW_SET and BL_SHADOW_BINDING first). Shared by
// the modes that light surfaces by shadow cubes (atlas's direct pass; raster's and multibounce's
// loops do the same and can call it).
#ifndef BL_GPU_SHADOWED_LIGHT_GLSL
#define BL_GPU_SHADOWED_LIGHT_GLSL
#include "gpu/ShadowCubeLookup.glsl"
#include "shared/Lights.h"

// Light `light` (cube `cube` of the maps, `resolution` texels a side) at point p with unit normal n:
// the direction toward the light `wi` and the irradiance I profile visibility cos / r^2 on the
// plane of n. False (irradiance 0) when p is behind n, outside a spot's cone, at the light, or
// in shadow.
bool blShadowedLight(GpuLight light, uint cube, uint resolution, vec3 p, vec3 n, out vec3 wi, out vec3 irradiance) {
    irradiance = vec3(0.0);
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
    irradiance = light.intensity * (profile * visibility * cosine / r2);
    return true;
}

#endif
