// blTriangleBarycentrics (shaders/shared/Barycentrics.h), which locates every bundle hit and
// G-buffer sample in its triangle, on slivers and at extreme scales (issue 19: a floor of aspect-1e4
// slivers multiplied the atlas's indirect light because the Gram determinant cancelled to noise).
#include <shared/Barycentrics.h>

#include <gtest/gtest.h>

using namespace bl;

namespace {

// Largest error of the recovered (b1, b2) over a grid of points inside the triangle (p0, p0 + e1,
// p0 + e2), each built as p0 + b1 e1 + b2 e2 in float, as a rasterizer's hit point is.
float worstError(glm::vec3 p0, glm::vec3 e1, glm::vec3 e2) {
    float worst = 0.0f;
    for (int i = 1; i < 10; ++i) {
        for (int j = 1; i + j < 10; ++j) {
            const glm::vec2 b(float(i) / 10.0f, float(j) / 10.0f);
            const glm::vec3 p = p0 + b.x * e1 + b.y * e2;
            const glm::vec2 got = shader::blTriangleBarycentrics(p - p0, e1, e2);
            worst = std::max(worst, std::max(std::abs(got.x - b.x), std::abs(got.y - b.y)));
        }
    }
    return worst;
}

} // namespace

TEST(Barycentrics, WellShapedTrianglesAreExactToRounding) {
    EXPECT_LT(worstError({1, 2, 3}, {1, 0, 0}, {0.3f, 1, 0.2f}), 1e-6f);
}

TEST(Barycentrics, SliversKeepTheirPointsWithinTheirRoundingError) {
    // The floor strips: 559.2 mm long, 0.055 mm wide (aspect 1e4), 100-550 mm from the
    // origin. A hit point rounded to float moves by ~|p| eps = 550 * 6e-8 = 3.3e-5 mm, 6e-4 of the
    // width; b moves by that much (times a small constant of the triangle's shape): 4x is the bound.
    const float bound = 4.0f * 550.0f * 6e-8f / 0.055f;
    for (float x : {100.0f, 300.0f, 550.0f}) {
        const glm::vec3 p(x, 0.0f, 0.0f), q(x * 549.6f / 552.8f, 0.0f, 559.2f);
        const glm::vec3 next = q + glm::vec3(0.055f, 0.0f, 0.0f);
        EXPECT_LT(worstError(p, q - p, next - p), bound) << "x = " << x;
        // Aspect 1e5 (issue 19's stress range): still within its own rounding bound.
        EXPECT_LT(worstError(p, q - p, q + glm::vec3(0.0055f, 0, 0) - p), 10.0f * bound) << "x = " << x;
    }
}

TEST(Barycentrics, HugeAndTinyTrianglesNeitherOverflowNorUnderflow) {
    // (e1.e1)(e2.e2) overflows float at edges of ~1e10 and underflows at ~1e-10.
    for (float scale : {1e-15f, 1e-9f, 1e12f, 1e18f}) {
        EXPECT_LT(worstError(glm::vec3(0.0f), glm::vec3(scale, 0, 0), glm::vec3(0.2f, 1, 0.1f) * scale), 1e-5f) << scale;
    }
}
