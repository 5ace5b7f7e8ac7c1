// The shared GLSL/C++ functions, evaluated on the host: conventions of CONVENTIONS.md.
#include <gtest/gtest.h>
#include <shared/Brdf.h>
#include <shared/CubeFaces.h>
#include <shared/EnvMap.h>
#include <shared/Lights.h>

using namespace bl::shader;

TEST(EnvMap, OrientationFollowsConventions) {
    auto uv = [](glm::vec3 d) { return blEnvDirectionToUv(glm::normalize(d), 0.0f); };
    EXPECT_NEAR(uv({0, 1, 0}).y, 0.0f, 1e-6f);       // +y: top row
    EXPECT_NEAR(uv({0, -1, 0}).y, 1.0f, 1e-6f);      // -y: bottom row
    EXPECT_NEAR(uv({1, 0, 0}).x, 0.5f, 1e-6f);       // +x: middle column
    EXPECT_NEAR(uv({0, 0, 1}).x, 0.75f, 1e-6f);      // +z: three quarters across
    EXPECT_NEAR(uv({0, 0, -1}).x, 0.25f, 1e-6f);     // -z: one quarter across
    EXPECT_NEAR(std::abs(uv({-1, 0, 0}).x - 0.5f), 0.5f, 1e-6f); // -x: the edges
    EXPECT_NEAR(uv({1, 0, 0}).y, 0.5f, 1e-6f);
    for (glm::vec2 p : {glm::vec2(0.1f, 0.2f), glm::vec2(0.7f, 0.9f), glm::vec2(0.45f, 0.5f)}) {
        for (float rot : {0.0f, 1.0f, -2.5f}) {
            glm::vec3 d = blEnvUvToDirection(p, rot);
            glm::vec2 back = blEnvDirectionToUv(d, rot);
            EXPECT_NEAR(back.x, p.x, 1e-5f);
            EXPECT_NEAR(back.y, p.y, 1e-5f);
        }
    }
    // Rotating the map by +90 degrees about +y moves what was at +x to -z (right-handed).
    glm::vec2 moved = blEnvDirectionToUv(glm::vec3(0, 0, -1), glm::radians(90.0f));
    EXPECT_NEAR(moved.x, 0.5f, 1e-5f);
}

TEST(CubeFaces, BasesAreRightHandedAndSelectTheirFace) {
    for (uint face = 0; face < 6; ++face) {
        glm::vec3 r, u, f;
        blCubeFaceBasis(face, r, u, f);
        EXPECT_NEAR(glm::dot(glm::cross(r, u), -f), 1.0f, 1e-6f) << face; // view space: r x u = -f
        EXPECT_EQ(blCubeFaceOf(f + 0.3f * r - 0.9f * u), face);
    }
}

TEST(Lights, SpotProfile) {
    GpuLight spot{};
    spot.type = kLightSpot;
    spot.direction = glm::vec3(0, -1, 0);
    spot.cosOuter = std::cos(glm::radians(30.0f));
    spot.cosInner = std::cos(glm::radians(20.0f));
    EXPECT_FLOAT_EQ(blLightProfile(spot, {0, -1, 0}), 1.0f);
    EXPECT_FLOAT_EQ(blLightProfile(spot, glm::normalize(glm::vec3(1, -1, 0))), 0.0f); // 45 degrees
    float mid = blLightProfile(spot, glm::vec3(std::sin(glm::radians(25.0f)), -std::cos(glm::radians(25.0f)), 0));
    EXPECT_GT(mid, 0.0f);
    EXPECT_LT(mid, 1.0f);
    GpuLight point{};
    EXPECT_FLOAT_EQ(blLightProfile(point, {1, 0, 0}), 1.0f);
}

TEST(Brdf, LambertPhongAndReciprocity) {
    glm::vec3 n(0, 0, 1);
    EXPECT_NEAR(blLambert(glm::vec3(0.5f)).x, 0.5f / kPi, 1e-7f);
    glm::vec3 wi = glm::normalize(glm::vec3(0.3f, 0.1f, 1.0f));
    glm::vec3 mirror = 2.0f * glm::dot(n, wi) * n - wi;
    // At the mirror direction the normalized lobe peaks at specular (e+2)/(2 pi).
    EXPECT_NEAR(blPhongLobe(glm::vec3(1), 20.0f, n, wi, mirror).x, 22.0f / (2.0f * kPi), 1e-4f);
    GpuMaterial m{};
    m.albedo = glm::vec3(0.3f);
    m.specular = glm::vec3(0.5f);
    m.exponentU = 30.0f;
    m.exponentV = 30.0f;
    glm::vec3 wo = glm::normalize(glm::vec3(-0.5f, 0.2f, 0.8f));
    EXPECT_NEAR(blEvalBrdf(m, m.albedo, n, wi, wo).x, blEvalBrdf(m, m.albedo, n, wo, wi).x, 1e-6f);
    m.exponentV = 300.0f; // Ashikhmin-Shirley
    EXPECT_NEAR(blEvalBrdf(m, m.albedo, n, wi, wo).x, blEvalBrdf(m, m.albedo, n, wo, wi).x, 1e-6f);
    EXPECT_TRUE(std::isfinite(blEvalBrdf(m, m.albedo, n, n, n).x));
}
