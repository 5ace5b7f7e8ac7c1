// Mode bidir: direct environment light at a camera point by this frame's environment bundles
// ([TO12] section 3, Eq. 1-2; shaders/gpu/BundleEnvironmentLight.glsl): with E bundles along
// directions omega_e drawn by Eq. 2's importance q, a point x with normal n uses d = +-omega_e on
// its side, unoccluded when its bundle pixel's list has no surface beyond x along d (x's own
// surface never counts, whatever its winding, and a closed room's creases keep the sky out:
// bundle/Traversal.glsl, blBundleSurfaceNearestAcrossCreases):
//   (1 / E) sum_e L_e(d) f(x, d, w_o) (n.d) V(x, d) / p_r(d),  p_r(d) = q(d) + q(-d).
// Needs push.pool (BidirPush), the Traversal helpers and bidirSurfaceNearest (evaluate.comp.glsl); a point outside an environment bundle's
// frame sets gOutsideBundle (its sample is dropped, as for the pairs' bundles).
#include "modes/bidir/BidirEnvironment.h"
#include "gpu/BundleEnvironmentLight.glsl"

layout(set = kBidirSet, binding = kBidirBindingEnvironment) readonly buffer EnvironmentBlock {
    BidirEnvironmentHeader environmentHeader;
    BidirEnvironmentBundle environmentBundles[];
};

vec3 bidirEnvironmentDirect(vec3 x, vec3 n, GpuMaterial m, vec3 albedo, vec3 wo) {
    uint count = environmentHeader.count;
    vec3 sum = vec3(0.0);
    for (uint e = 0u; e < count; ++e) {
        uint slot = environmentHeader.firstSlot + e;
        BundleFrame frame = blBundlePoolFrame(push.pool, slot);
        BidirEnvironmentBundle b = environmentBundles[e];
        BlBundleLight light = BlBundleLight(b.radianceForward, b.pdfForward, b.radianceBackward, b.pdfBackward, false);
        BlBundleLightSample s = blBundleLightSample(frame, light, n);
        if (!s.usable) {
            continue;
        }
        ivec2 bundlePixel;
        float depth;
        if (!blBundlePixel(frame, x, bundlePixel, depth)) {
            gOutsideBundle = true;
            continue;
        }
        float unusedCrossing;
        ivec2 unusedHitPixel;
        if (bidirSurfaceNearest(BundleNodes(push.pool.nodes), slot, frame, bundlePixel, x, depth, n, s.side,
                                unusedCrossing, unusedHitPixel) == kBundleNil) {
            sum += blBundleLightContribution(s, m, albedo, n, wo);
        }
    }
    return count > 0u ? sum / float(count) : vec3(0.0);
}
