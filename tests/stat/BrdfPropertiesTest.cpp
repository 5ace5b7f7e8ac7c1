// Physical properties of the shared BRDFs: reciprocity and energy conservation (directional
// albedo <= 1) over sweeps of exponents and incident angles.
#include <gtest/gtest.h>
#include <shared/BrdfSampling.h>
#include <shared/Random.h>

using namespace bl::shader;

namespace {
GpuMaterial lobe(float nu, float nv) {
    GpuMaterial m{};
    m.specular = glm::vec3(1.0f);
    m.exponentU = nu;
    m.exponentV = nv;
    return m;
}

} // namespace

TEST(BrdfProperties, Reciprocity) {
    const glm::vec3 n(0, 0, 1);
    for (glm::vec2 e : {glm::vec2(1, 1), glm::vec2(20, 20), glm::vec2(300, 300), glm::vec2(5, 80)}) {
        GpuMaterial m = lobe(e.x, e.y);
        m.albedo = glm::vec3(0.2f);
        m.specular = glm::vec3(0.6f);
        for (std::uint32_t i = 0; i < 500; ++i) {
            glm::vec3 a = blSampleCosineHemisphere(glm::vec2(blHashRandom(1u, 4 * i), blHashRandom(1u, 4 * i + 1)));
            glm::vec3 b = blSampleCosineHemisphere(glm::vec2(blHashRandom(1u, 4 * i + 2), blHashRandom(1u, 4 * i + 3)));
            glm::vec3 fab = blEvalBrdf(m, m.albedo, n, a, b), fba = blEvalBrdf(m, m.albedo, n, b, a);
            ASSERT_NEAR(fab.x, fba.x, 1e-4f * std::max(1.0f, fab.x)) << e.x << " " << e.y;
        }
    }
}

// Directional albedo rho(wi) = integral of f cos over the hemisphere, estimated by sampling the
// lobe itself (low variance), must stay <= 1 for a lobe of unit specular reflectance.
TEST(BrdfProperties, DirectionalAlbedoAtMostOne) {
    const glm::vec3 n(0, 0, 1);
    const int samples = 20000;
    for (glm::vec2 e : {glm::vec2(1, 1), glm::vec2(2, 2), glm::vec2(10, 10), glm::vec2(100, 100),
                        glm::vec2(1000, 1000), glm::vec2(10, 100), glm::vec2(1, 1000)}) {
        GpuMaterial m = lobe(e.x, e.y);
        for (float degrees : {0.0f, 30.0f, 60.0f, 80.0f, 89.0f}) {
            const float a = glm::radians(degrees);
            const glm::vec3 wi(std::sin(a), 0.0f, std::cos(a));
            double sum = 0.0, sumSq = 0.0;
            for (int i = 0; i < samples; ++i) {
                const auto k = static_cast<std::uint32_t>(3 * i);
                glm::vec3 u(blHashRandom(9u, k), blHashRandom(9u, k + 1), blHashRandom(9u, k + 2));
                glm::vec3 wo = blSampleBrdf(m, m.albedo, n, wi, u);
                float pdf = blBrdfPdf(m, m.albedo, n, wi, wo);
                double v = pdf > 0.0f ? blEvalBrdf(m, m.albedo, n, wi, wo).x * wo.z / pdf : 0.0;
                sum += v;
                sumSq += v * v;
            }
            double mean = sum / samples;
            double stderrMean = std::sqrt(std::max(0.0, sumSq / samples - mean * mean) / samples);
            EXPECT_LE(mean, 1.0 + 4.0 * stderrMean + 1e-3) << "exponents " << e.x << "," << e.y << " at " << degrees;
            EXPECT_GT(mean, 0.0);
        }
    }
}
