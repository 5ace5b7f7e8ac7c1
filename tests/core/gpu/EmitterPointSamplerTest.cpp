// The emitter points' host sampler (core/gpu/EmitterPointSampler.h) against the density it states:
// triangles by power, points uniform on them, p_A = mean(L_e) / Phi, at the scene's time.
#include "base/Error.h"
#include "gpu/EmitterPointSampler.h"
#include "support/AnalyticScenes.h"

#include <gtest/gtest.h>

#include <limits>

using namespace bl;

namespace {

// Two emitters of different radiance and area: A is 1 x 1 at y = 1 (mean radiance 1), B is 1 x 2
// at y = 2 (mean radiance 3), both facing down: Phi = 1 + 6 = 7, so B holds 6/7 of the power.
Scene twoEmitters() {
    Scene s;
    s.materials.push_back(Material{});
    Mesh a = test::makeRectangle({0.0f, 0.0f}, {1.0f, 1.0f}, 1.0f, true, 0);
    a.emission = glm::vec3(1.0f);
    Mesh b = test::makeRectangle({0.0f, 0.0f}, {1.0f, 2.0f}, 2.0f, true, 0);
    b.emission = glm::vec3(1.0f, 2.0f, 6.0f);
    s.meshes = {a, b};
    return s;
}

} // namespace

TEST(EmitterPointSampler, DrawsByPowerWithTheDensityItStates) {
    const Scene s = twoEmitters();
    const gpu::EmitterPointSampler sampler(s);
    ASSERT_FALSE(sampler.empty());
    EXPECT_NEAR(sampler.inversePower(), 1.0 / 7.0, 1e-7);
    // Stratified in the power CDF: of M points, B's share is 6/7 to within one point.
    constexpr std::uint32_t kCount = 7000;
    const std::vector<shader::GpuEmitterPoint> points = sampler.sample(kCount, 3, 0, 0.0, 0.0f);
    ASSERT_EQ(points.size(), kCount);
    std::uint32_t onB = 0;
    glm::dvec3 meanA(0.0), meanB(0.0);
    for (const shader::GpuEmitterPoint& p : points) {
        const bool b = p.position.y == 2.0f;
        ASSERT_TRUE(b || p.position.y == 1.0f) << p.position.y;
        onB += b ? 1u : 0u;
        (b ? meanB : meanA) += glm::dvec3(p.position);
        // p_A = mean(L_e) / Phi: 3/7 on B, 1/7 on A; the front normal faces down.
        EXPECT_NEAR(p.areaPdf, b ? 3.0 / 7.0 : 1.0 / 7.0, 1e-6);
        EXPECT_EQ(p.normal, glm::vec3(0.0f, -1.0f, 0.0f));
        EXPECT_EQ(p.emission, b ? glm::vec3(1.0f, 2.0f, 6.0f) : glm::vec3(1.0f));
        EXPECT_EQ(p.cubeCentre, p.position);
        ASSERT_TRUE(p.position.x >= 0.0f && p.position.x <= 1.0f && p.position.z >= 0.0f &&
                    p.position.z <= (b ? 2.0f : 1.0f));
    }
    EXPECT_NEAR(double(onB), kCount * 6.0 / 7.0, 1.0);
    // Uniform on each rectangle: the mean point is its centre (standard error of a coordinate
    // uniform on [0, w]: w / sqrt(12 n); 5 of them allowed).
    meanA /= double(kCount - onB);
    meanB /= double(onB);
    EXPECT_NEAR(meanA.x, 0.5, 5.0 / std::sqrt(12.0 * (kCount - onB)));
    EXPECT_NEAR(meanA.z, 0.5, 5.0 / std::sqrt(12.0 * (kCount - onB)));
    EXPECT_NEAR(meanB.x, 0.5, 5.0 / std::sqrt(12.0 * onB));
    EXPECT_NEAR(meanB.z, 1.0, 10.0 / std::sqrt(12.0 * onB));
    // The lift moves the cube centre along the front normal, never the point.
    for (const shader::GpuEmitterPoint& p : sampler.sample(8, 3, 0, 0.0, 0.25f)) {
        EXPECT_EQ(p.cubeCentre, p.position + glm::vec3(0.0f, -0.25f, 0.0f));
    }
    // Deterministic per (seed, iteration); other iterations draw other points.
    EXPECT_EQ(sampler.sample(4, 3, 5, 0.0, 0.0f)[2].position, sampler.sample(4, 3, 5, 0.0, 0.0f)[2].position);
    EXPECT_NE(sampler.sample(4, 3, 5, 0.0, 0.0f)[2].position, sampler.sample(4, 3, 6, 0.0, 0.0f)[2].position);
}

TEST(EmitterPointSampler, PointsFollowAKeyframedEmitter) {
    Scene s = twoEmitters();
    s.meshes[0].animation.addKey({0.0, glm::vec3(0.0f)});
    s.meshes[0].animation.addKey({1.0, glm::vec3(0.0f, -0.5f, 0.0f)});
    const gpu::EmitterPointSampler sampler(s);
    for (const shader::GpuEmitterPoint& p : sampler.sample(64, 1, 0, 1.0, 0.0f)) {
        EXPECT_TRUE(p.position.y == 0.5f || p.position.y == 2.0f) << p.position.y;
    }
}

TEST(EmitterPointSampler, PowerAFloatCannotHoldIsRefusedAndInfiniteRadianceIsCounted) {
    Scene s = twoEmitters();
    s.meshes[1].emission = glm::vec3(3e38f); // finite, but 3e38 x area 2 overflows a float
    try {
        gpu::EmitterPointSampler sampler(s);
        ADD_FAILURE() << "an unrepresentable power was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("beyond what a float represents"), std::string::npos) << e.what();
    }
    // Infinite radiance cannot come from a file (the loaders refuse it); set in memory it is drawn
    // by area and its samples reach the modes' lost-work count instead of a throw.
    s.meshes[1].emission = glm::vec3(std::numeric_limits<float>::infinity());
    EXPECT_NO_THROW(gpu::EmitterPointSampler{s});
}
