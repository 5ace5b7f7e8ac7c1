// Direct light from the environment along one bundle direction ([TO12] section 3): for a point with
// normal n, the bundle's direction d in {omega, -omega} on n's side, and its estimate
//   L_e(d) f(x, d, w_o) (n.d) / p(d)
// once visibility is known. Shared by every mode that lights points from bundle directions
// (skylight, and the gathering steps of bidir, multibounce and atlas).
#ifndef BL_GPU_BUNDLE_ENVIRONMENT_LIGHT_GLSL
#define BL_GPU_BUNDLE_ENVIRONMENT_LIGHT_GLSL
#include "bundle/Traversal.glsl"
#include "shared/Brdf.h"

// The environment's light along one bundle direction, both ways.
struct BlBundleLight {
    vec3 radianceForward;  // L_e(omega)
    float pdfForward;      // density omega was drawn with (p_r, or q for one-sided use)
    vec3 radianceBackward; // L_e(-omega)
    float pdfBackward;
    bool forwardOnly;      // -omega unusable (a depth map answers omega only)
};

// One point's use of a bundle direction.
struct BlBundleLightSample {
    vec3 direction; // d: omega or -omega, toward the light
    float side;     // +1 for omega, -1 for -omega
    vec3 radiance;  // L_e(d)
    float pdf;
    float cosine;     // |n . omega| (the own-surface tolerance: blBundleSurfaceEpsilon)
    bool usable;      // false: nothing to add (wrong side, zero pdf or black)
};

BlBundleLightSample blBundleLightSample(BundleFrame frame, BlBundleLight light, vec3 n) {
    BlBundleLightSample s;
    float c = dot(n, frame.direction);
    s.side = c >= 0.0 ? 1.0 : -1.0; // use omega or -omega, whichever is on n's side
    s.direction = s.side * frame.direction;
    s.radiance = s.side > 0.0 ? light.radianceForward : light.radianceBackward;
    s.pdf = s.side > 0.0 ? light.pdfForward : light.pdfBackward;
    s.cosine = abs(c);
    s.usable = (!light.forwardOnly || s.side > 0.0) && s.cosine > 0.0 && s.pdf > 0.0 &&
               dot(s.radiance, s.radiance) > 0.0;
    return s;
}

// The estimate of an unoccluded, usable sample.
vec3 blBundleLightContribution(BlBundleLightSample s, GpuMaterial m, vec3 albedo, vec3 n, vec3 wo) {
    return s.radiance * blEvalBrdf(m, albedo, n, s.direction, wo) * (s.cosine / s.pdf);
}

#endif
