// Importance sampling of the BRDFs of Brdf.h, and the matching densities (solid angle). The full
// BRDF is sampled as a mixture: the Lambert term with probability proportional to the albedo's
// luminance, the glossy lobe with probability proportional to the specular's; the pdf of a
// direction is the mixture's, whichever component produced it (one-sample MIS).
#ifndef BL_SHARED_BRDF_SAMPLING_H
#define BL_SHARED_BRDF_SAMPLING_H
#include "Brdf.h"
#include "Sampling.h"

BL_NAMESPACE_BEGIN

// Normalized Phong lobe: directions about the mirror direction r with pdf (e + 1) / (2 pi) cos^e.
BL_INLINE vec3 blSamplePhongLobe(float exponent, vec3 r, vec2 u) {
    float oneMinusCos = blOneMinusCosineSample(u.x, exponent);
    float cosA = 1.0f - oneMinusCos;
    float sinA = sqrt(max(0.0f, oneMinusCos * (2.0f - oneMinusCos)));
    float phi = kTwoPi * u.y;
    return blToWorld(vec3(sinA * cos(phi), sinA * sin(phi), cosA), r);
}

BL_INLINE float blPhongLobePdf(float exponent, vec3 r, vec3 wo) {
    return (exponent + 1.0f) * (0.5f * kInvPi) * blCosinePower(r, wo, exponent);
}

// Ashikhmin-Shirley (2000) half-vector sampling, exponents nu along t and nv along b.
BL_INLINE vec3 blSampleAshikhminShirley(float nu, float nv, vec3 n, vec3 t, vec3 b, vec3 wi, vec2 u) {
    // phi in the first quadrant, then mirrored into the quadrant u.x selects.
    float x = 4.0f * u.x;
    float quadrant = floor(x);
    float v = x - quadrant;
    float phi = atan(sqrt((nu + 1.0f) / (nv + 1.0f)) * tan(0.5f * kPi * v));
    if (quadrant == 1.0f) {
        phi = kPi - phi;
    } else if (quadrant == 2.0f) {
        phi = kPi + phi;
    } else if (quadrant == 3.0f) {
        phi = kTwoPi - phi;
    }
    float c = cos(phi);
    float s = sin(phi);
    float e = nu * c * c + nv * s * s;
    float oneMinusCos = blOneMinusCosineSample(u.y, e);
    float cosH = 1.0f - oneMinusCos;
    float sinH = sqrt(max(0.0f, oneMinusCos * (2.0f - oneMinusCos)));
    vec3 h = sinH * c * t + sinH * s * b + cosH * n;
    return 2.0f * dot(wi, h) * h - wi;
}

BL_INLINE float blAshikhminShirleyPdf(float nu, float nv, vec3 n, vec3 t, vec3 b, vec3 wi, vec3 wo) {
    vec3 h = normalize(wi + wo);
    float nh = dot(n, h);
    float kh = dot(wi, h);
    if (nh <= 0.0f || kh <= 0.0f) {
        return 0.0f;
    }
    float e = blAshikhminShirleyExponent(nu, nv, t, b, h);
    float pdfH = sqrt((nu + 1.0f) * (nv + 1.0f)) * (0.5f * kInvPi) * blCosinePower(n, h, e);
    return pdfH / (4.0f * kh);
}

// The glossy lobe's own sampling: wo about wi's mirror direction (Phong) or by half vector
// (Ashikhmin-Shirley), and its density over the whole sphere (a direction below the surface has
// density but a zero lobe).
BL_INLINE vec3 blSampleGlossyLobe(GpuMaterial m, vec3 n, vec3 wi, vec2 v) {
    if (blIsAnisotropic(m)) {
        vec3 t;
        vec3 b;
        blOrthonormalBasis(n, t, b);
        return blSampleAshikhminShirley(m.exponentU, m.exponentV, n, t, b, wi, v);
    }
    return blSamplePhongLobe(m.exponentU, 2.0f * dot(n, wi) * n - wi, v);
}

BL_INLINE float blGlossyLobePdf(GpuMaterial m, vec3 n, vec3 wi, vec3 wo) {
    if (blIsAnisotropic(m)) {
        vec3 t;
        vec3 b;
        blOrthonormalBasis(n, t, b);
        return blAshikhminShirleyPdf(m.exponentU, m.exponentV, n, t, b, wi, wo);
    }
    return blPhongLobePdf(m.exponentU, 2.0f * dot(n, wi) * n - wi, wo);
}

// Probability of choosing the glossy lobe in the mixture.
BL_INLINE float blGlossyProbability(GpuMaterial m, vec3 albedo) {
    float d = blLuminance(albedo);
    float s = blLuminance(m.specular);
    return d + s > 0.0f ? s / (d + s) : 0.0f;
}

BL_INLINE float blBrdfPdf(GpuMaterial m, vec3 albedo, vec3 n, vec3 wi, vec3 wo) {
    float cosO = dot(n, wo);
    if (cosO <= 0.0f) {
        return 0.0f;
    }
    float pg = blGlossyProbability(m, albedo);
    float pdf = (1.0f - pg) * cosO * kInvPi;
    if (pg > 0.0f) {
        pdf += pg * blGlossyLobePdf(m, n, wi, wo);
    }
    return pdf;
}

// Samples wo given wi (both away from the surface, n facing wi). u.x picks the component and is
// reused (rescaled) so three numbers suffice. Returns a direction that may lie below the surface;
// its pdf is then 0 and the caller ends the path.
BL_INLINE vec3 blSampleBrdf(GpuMaterial m, vec3 albedo, vec3 n, vec3 wi, vec3 u) {
    float pg = blGlossyProbability(m, albedo);
    if (u.x < pg) {
        return blSampleGlossyLobe(m, n, wi, vec2(u.y, u.z));
    }
    return blToWorld(blSampleCosineHemisphere(vec2(u.y, u.z)), n);
}

BL_NAMESPACE_END
#endif
