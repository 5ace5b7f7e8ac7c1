// The BRDFs, defined once for the CPU reference and every GPU mode (CONVENTIONS.md).
// Directions point away from the surface: wi toward the light, wo toward the viewer; n is the
// shading normal already turned toward the side being lit and seen.
#ifndef BL_SHARED_BRDF_H
#define BL_SHARED_BRDF_H
#include "GpuTypes.h"
#include "Frame.h"

BL_NAMESPACE_BEGIN

BL_INLINE vec3 blLambert(vec3 albedo) { return albedo * kInvPi; }

// Normalized Phong lobe about the mirror direction r of wi:
// f = specular (e + 2) / (2 pi) max(0, r.wo)^e. Its directional albedo is <= specular.
BL_INLINE vec3 blPhongLobe(vec3 specular, float exponent, vec3 n, vec3 wi, vec3 wo) {
    vec3 r = 2.0f * dot(n, wi) * n - wi;
    float c = max(0.0f, dot(r, wo));
    return specular * ((exponent + 2.0f) * (0.5f * kInvPi) * pow(c, exponent));
}

// Ashikhmin-Shirley (2000) anisotropic specular lobe with Schlick Fresnel of reflectance
// `specular`, exponents nu along the tangent t and nv along the bitangent b.
BL_INLINE vec3 blAshikhminShirleyLobe(vec3 specular, float nu, float nv, vec3 n, vec3 t, vec3 b,
                                      vec3 wi, vec3 wo) {
    float cosI = dot(n, wi);
    float cosO = dot(n, wo);
    if (cosI <= 0.0f || cosO <= 0.0f) {
        return vec3(0.0f);
    }
    vec3 h = normalize(wi + wo);
    float nh = max(dot(n, h), 0.0f);
    float th = dot(t, h);
    float bh = dot(b, h);
    float sin2 = max(1.0f - nh * nh, 1e-12f);
    float e = (nu * th * th + nv * bh * bh) / sin2;
    float kh = max(dot(wi, h), 1e-6f);
    vec3 fresnel = specular + (vec3(1.0f) - specular) * pow(1.0f - kh, 5.0f);
    float d = sqrt((nu + 1.0f) * (nv + 1.0f)) * (0.125f * kInvPi) * pow(nh, e);
    return fresnel * (d / (kh * max(cosI, cosO)));
}

BL_INLINE bool blIsAnisotropic(GpuMaterial m) { return m.exponentU != m.exponentV; }

// Full BRDF of a material: Lambert + glossy lobe. `albedo` may come from a texture.
BL_INLINE vec3 blEvalBrdf(GpuMaterial m, vec3 albedo, vec3 n, vec3 wi, vec3 wo) {
    vec3 f = blLambert(albedo);
    if (m.specular.x + m.specular.y + m.specular.z > 0.0f) {
        if (blIsAnisotropic(m)) {
            vec3 t;
            vec3 b;
            blOrthonormalBasis(n, t, b);
            f += blAshikhminShirleyLobe(m.specular, m.exponentU, m.exponentV, n, t, b, wi, wo);
        } else {
            f += blPhongLobe(m.specular, m.exponentU, n, wi, wo);
        }
    }
    return f;
}

BL_NAMESPACE_END
#endif
