// Powers of cosines near 1, for sharp lobes (Phong and Ashikhmin-Shirley exponents to 1e6 and
// beyond), shared by the reference and every GPU mode.
//
// pow(dot(a, b), e) loses such a lobe twice in float. A lobe of exponent e lives where
// 1 - cos ~ 1 / e (1e-6 at e = 1e6), but dot(a, b) near 1 is rounded to float's spacing there
// (6e-8), which alone moves cos^e by a factor up to exp(e 6e-8) (6% at 1e6); and a GPU's pow is
// exp2(e log2 c), whose log2 near 1 has an absolute, not a relative, error (lavapipe's image of the
// 1e6 lobe under a point light read 3.7% below the CPU's). Here 1 - cos = |a - b|^2 / 2, exact
// for unit a and b with no rounding near 1, and log(1 - x) is summed as its series where 1 - x
// would round; the samplers' inverse CDFs get 1 - cos the same way (blOneMinusCosineSample).
#ifndef BL_SHARED_COSINE_POWER_H
#define BL_SHARED_COSINE_POWER_H
#include "Prelude.h"

BL_NAMESPACE_BEGIN

// Below this the series are used: truncated after the fifth power, their relative error is below
// x^5 / 6 = 4e-9 here, under float's 6e-8.
BL_CONST float kCosinePowerSeriesBelow = 0.03f;

// log(1 - x) for x in [0, 1).
BL_INLINE float blLogOneMinus(float x) {
    if (x < kCosinePowerSeriesBelow) {
        return -x * (1.0f + x * (0.5f + x * (1.0f / 3.0f + x * (0.25f + x * 0.2f))));
    }
    return log(1.0f - x);
}

// exp(y) - 1.
BL_INLINE float blExpMinusOne(float y) {
    if (abs(y) < kCosinePowerSeriesBelow) {
        return y * (1.0f + y * (0.5f + y * (1.0f / 6.0f + y * (1.0f / 24.0f + y * (1.0f / 120.0f)))));
    }
    return exp(y) - 1.0f;
}

// max(0, cos)^e of the angle between unit vectors a and b; e >= 0 (1 where e = 0 and cos > 0).
BL_INLINE float blCosinePower(vec3 a, vec3 b, float e) {
    vec3 d = a - b;
    float x = 0.5f * dot(d, d); // 1 - cos
    if (!(x < 1.0f)) {
        return 0.0f;
    }
    return exp(e * blLogOneMinus(x));
}

// 1 - cos of a direction drawn with density proportional to cos^e about an axis, from a uniform u
// in [0, 1): the inverse CDF cos = (1 - u)^(1 / (e + 1)), kept accurate where cos is near 1.
BL_INLINE float blOneMinusCosineSample(float u, float e) {
    return max(0.0f, -blExpMinusOne(log(1.0f - u) / (e + 1.0f)));
}

BL_NAMESPACE_END

#endif
