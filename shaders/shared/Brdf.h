// The BRDFs, defined once for the CPU reference and every GPU mode (CONVENTIONS.md).
// Directions point away from the surface: wi toward the light, wo toward the viewer; n is the
// shading normal already turned toward the side being lit and seen.
#ifndef BL_SHARED_BRDF_H
#define BL_SHARED_BRDF_H
#include "GpuTypes.h"
#include "Frame.h"
#include "CosinePower.h"

// A shader pass may define these (before its first include of this file) as specialization
// constants saying whether some material has a glossy lobe, an anisotropic one
// (gpu/MaterialSpecialization.glsl): where not, the lobes compile out. The results are the same;
// lavapipe, which runs both sides of every branch under a lane mask, stops paying for lobes no
// material has. The CPU reference keeps them.
#ifndef BL_GLOSSY_LOBES
#define BL_GLOSSY_LOBES true
#endif
#ifndef BL_ANISOTROPIC_LOBES
#define BL_ANISOTROPIC_LOBES true
#endif

BL_NAMESPACE_BEGIN

BL_INLINE vec3 blLambert(vec3 albedo) { return albedo * kInvPi; }

// Normalized Phong lobe about the mirror direction r of wi:
// f = specular (e + 2) / (2 pi) max(0, r.wo)^e. Its directional albedo is <= specular.
BL_INLINE vec3 blPhongLobe(vec3 specular, float exponent, vec3 n, vec3 wi, vec3 wo) {
    vec3 r = 2.0f * dot(n, wi) * n - wi;
    return specular * ((exponent + 2.0f) * (0.5f * kInvPi) * blCosinePower(r, wo, exponent));
}

// The exponent of Ashikhmin-Shirley's (n.h)^e at unit half vector h: (nu (t.h)^2 + nv (b.h)^2) /
// (1 - (n.h)^2), the denominator taken as (t.h)^2 + (b.h)^2, equal for unit h and without the
// rounding of 1 - (n.h)^2 near the lobe's axis.
BL_INLINE float blAshikhminShirleyExponent(float nu, float nv, vec3 t, vec3 b, vec3 h) {
    float th = dot(t, h);
    float bh = dot(b, h);
    return (nu * th * th + nv * bh * bh) / max(th * th + bh * bh, 1e-30f);
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
    float e = blAshikhminShirleyExponent(nu, nv, t, b, h);
    float kh = max(dot(wi, h), 1e-6f);
    vec3 fresnel = specular + (vec3(1.0f) - specular) * pow(1.0f - kh, 5.0f);
    float d = sqrt((nu + 1.0f) * (nv + 1.0f)) * (0.125f * kInvPi) * blCosinePower(n, h, e);
    return fresnel * (d / (kh * max(cosI, cosO)));
}

BL_INLINE bool blIsAnisotropic(GpuMaterial m) { return m.exponentU != m.exponentV; }

BL_INLINE bool blHasGlossyLobe(GpuMaterial m) { return m.specular.x + m.specular.y + m.specular.z > 0.0f; }

// The glossy lobe of a material alone (zero without specular); symmetric in wi and wo.
BL_INLINE vec3 blGlossyBrdf(GpuMaterial m, vec3 n, vec3 wi, vec3 wo) {
    if (!BL_GLOSSY_LOBES || !blHasGlossyLobe(m)) {
        return vec3(0.0f);
    }
    if (BL_ANISOTROPIC_LOBES && blIsAnisotropic(m)) {
        vec3 t;
        vec3 b;
        blOrthonormalBasis(n, t, b);
        return blAshikhminShirleyLobe(m.specular, m.exponentU, m.exponentV, n, t, b, wi, wo);
    }
    return blPhongLobe(m.specular, m.exponentU, n, wi, wo);
}

// Full BRDF of a material: Lambert + glossy lobe. `albedo` may come from a texture.
BL_INLINE vec3 blEvalBrdf(GpuMaterial m, vec3 albedo, vec3 n, vec3 wi, vec3 wo) {
    return blLambert(albedo) + blGlossyBrdf(m, n, wi, wo);
}

BL_NAMESPACE_END
#endif
