// Glossy artifact suppression of mode bidir ([TO12 Eq. 9]-[TO12 Eq. 14–17], papers/EQUATIONS.md):
// the glossy lobe's distribution D is read as a density kernel whose peak may not exceed the
// local directional sample density over m neighbours, max D <= d(y_i) / m (Eq. 9).
//   none       the BRDF as it is (unbiased, spiky where samples are sparse)
//   clamp      D truncated at d / m: f times min(1, (d / m) / D(theta)) (energy lost)
//   roughness  the exponent lowered until max D = d / m (Eq. 10 Phong with m of the widened lobe:
//              n <= 2 pi d / (m' s cos) - 2, Eq. 11-12 per axis for Ashikhmin-Shirley): the lobe
//              widens, its albedo stays
// with Phong D = (a + 1) / (2 pi) cos^a and Ashikhmin-Shirley D = sqrt((a_x + 1)(a_y + 1)) / (2 pi)
// cos^(...) (their peaks (a + 1) / (2 pi) and sqrt((a_x + 1)(a_y + 1)) / (2 pi)), and
// m = m' f (n . w_i) / D (the text after Eq. 17; m' = `suppression_neighbours`, 16 in the paper).
// The densities d come from the caller (evaluate.comp.glsl, Eq. 13-17). Host and GLSL, like Brdf.h.
#ifndef BL_BIDIR_SUPPRESSION_H
#define BL_BIDIR_SUPPRESSION_H
#include "../../shared/Brdf.h"

BL_NAMESPACE_BEGIN

BL_CONST uint kBidirSuppressionNone = 0u;
BL_CONST uint kBidirSuppressionClamp = 1u;
BL_CONST uint kBidirSuppressionRoughness = 2u;

// Eq. 10 / 12: the exponent whose distribution peaks at `peak` (samples per steradian / m),
// never above the material's.
BL_INLINE float blBidirClampedExponent(float exponent, float peak) {
    return max(0.0f, min(exponent, 2.0f * kPi * peak - 1.0f));
}

// The BRDF of material m at a path vertex whose directional sample density is `density`
// (samples per steradian, Eq. 13), with suppression `mode` and m' = `neighbours`. n, wi, wo as in
// blEvalBrdf (wi toward the light end of the path). density <= 0 or >= 1e30: no suppression.
BL_INLINE vec3 blBidirEvalBrdf(GpuMaterial m, vec3 albedo, vec3 n, vec3 wi, vec3 wo, float density, uint mode,
                              float neighbours) {
    if (mode == kBidirSuppressionNone || !(m.specular.x + m.specular.y + m.specular.z > 0.0f) ||
        !(density > 0.0f && density < 1e30f)) {
        return blEvalBrdf(m, albedo, n, wi, wo);
    }
    float cosI = max(dot(n, wi), 0.0f);
    vec3 t;
    vec3 b;
    blOrthonormalBasis(n, t, b);
    const bool anisotropic = blIsAnisotropic(m);
    vec3 lobe = anisotropic ? blAshikhminShirleyLobe(m.specular, m.exponentU, m.exponentV, n, t, b, wi, wo)
                            : blPhongLobe(m.specular, m.exponentU, n, wi, wo);
    // f / D of the lobe (D cancelled), as a scalar weight: Phong specular (a + 2) / (a + 1);
    // Ashikhmin-Shirley F / (4 (wi.h) max(cos_i, cos_o)) with F at its normal-incidence value.
    float ks = max(m.specular.x, max(m.specular.y, m.specular.z));
    float ratio;
    float peak; // max D of the material's own lobe
    if (anisotropic) {
        vec3 h = normalize(wi + wo);
        float kh = max(dot(wi, h), 1e-6f);
        ratio = ks / (4.0f * kh * max(max(cosI, dot(n, wo)), 1e-6f));
        peak = sqrt((m.exponentU + 1.0f) * (m.exponentV + 1.0f)) * (0.5f * kInvPi);
    } else {
        ratio = ks * (m.exponentU + 2.0f) / (m.exponentU + 1.0f);
        peak = (m.exponentU + 1.0f) * (0.5f * kInvPi);
    }
    float neighbourCount = neighbours * ratio * cosI; // m of Eq. 9
    if (!(neighbourCount > 0.0f)) {
        return blEvalBrdf(m, albedo, n, wi, wo);
    }
    float allowed = density / neighbourCount; // the largest D Eq. 9 allows
    if (peak <= allowed) {
        return blLambert(albedo) + lobe;
    }
    if (mode == kBidirSuppressionClamp) {
        // D(theta) of the lobe from its value: lobe = ratio-like factor * D, per the model.
        float d;
        if (anisotropic) {
            vec3 h = normalize(wi + wo);
            d = peak * blCosinePower(n, h, blAshikhminShirleyExponent(m.exponentU, m.exponentV, t, b, h));
        } else {
            vec3 r = 2.0f * dot(n, wi) * n - wi;
            d = peak * blCosinePower(r, wo, m.exponentU);
        }
        return blLambert(albedo) + (d > allowed ? lobe * (allowed / d) : lobe);
    }
    if (anisotropic) {
        return blLambert(albedo) + blAshikhminShirleyLobe(m.specular, blBidirClampedExponent(m.exponentU, allowed),
                                                          blBidirClampedExponent(m.exponentV, allowed), n, t, b, wi, wo);
    }
    // Phong: D cancels from Eq. 9 (m = m' f cos / D), which bounds the lobe itself,
    // m' cos_i s (n' + 2) / (2 pi) <= d, so n' = 2 pi d / (m' s cos_i) - 2 (CONVENTIONS.md). Eq. 10
    // with the original exponent's m (allowed) would leave the widened lobe's peak above the bound
    // (by a factor up to (a + 2) / (a + 1)): d / (m' s cos_i) = allowed (a + 2) / (a + 1).
    float lobePeak = allowed * (m.exponentU + 2.0f) / (m.exponentU + 1.0f);
    return blLambert(albedo) +
           blPhongLobe(m.specular, max(0.0f, min(m.exponentU, 2.0f * kPi * lobePeak - 2.0f)), n, wi, wo);
}

BL_NAMESPACE_END
#endif
