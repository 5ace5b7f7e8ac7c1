// Chi-square tests of every direction sampler against its own density: the BRDF mixture
// (Lambert, normalized Phong at several exponents, Ashikhmin-Shirley) and the environment map.
// A sampler and pdf that disagree bias every MIS estimate; this catches it.
#include "image/ImageIO.h"
#include "sampling/EnvironmentLight.h"
#include "reference/SphericalTriangle.h"
#include "stat/ChiSquare.h"
#include "support/TestFiles.h"

#include <cmath>
#include <functional>
#include <gtest/gtest.h>
#include <shared/BrdfSampling.h>
#include <shared/Random.h>

using namespace bl;
using namespace bl::test;

namespace {

constexpr int kThetaBins = 12;
constexpr int kPhiBins = 24;
constexpr int kSamples = 400000;
constexpr int kSubdivisions = 24; // per bin side, to integrate the density
// Every test in this file at once stays below a 1% false-alarm rate.
constexpr double kSignificance = 0.01 / 12.0;

using Sampler = std::function<glm::vec3(glm::vec3 u)>; // returns a direction, or zero if none
using Density = std::function<double(glm::vec3 direction)>;

int binOf(glm::vec3 d) {
    float cosTheta = std::clamp(d.z, -1.0f, 1.0f);
    float phi = std::atan2(d.y, d.x);
    if (phi < 0.0f) phi += shader::kTwoPi;
    int t = std::min(static_cast<int>((1.0f - cosTheta) * 0.5f * kThetaBins), kThetaBins - 1);
    int p = std::min(static_cast<int>(phi / shader::kTwoPi * kPhiBins), kPhiBins - 1);
    return t * kPhiBins + p;
}

// Bins are equal-area on the sphere: uniform in cos(theta) and phi.
ChiSquareResult testSampler(const Sampler& sample, const Density& pdf, std::uint32_t seed) {
    std::vector<double> observed(kThetaBins * kPhiBins, 0.0), expected(kThetaBins * kPhiBins, 0.0);
    for (int i = 0; i < kSamples; ++i) {
        // Independent samples: the chi-square statistic assumes them.
        const auto k = static_cast<std::uint32_t>(3 * i);
        glm::vec3 u(shader::blHashRandom(seed, k), shader::blHashRandom(seed, k + 1), shader::blHashRandom(seed, k + 2));
        glm::vec3 d = sample(u);
        if (glm::dot(d, d) > 0.0f && pdf(d) > 0.0) {
            observed[binOf(d)] += 1.0;
        }
    }
    const double dCos = 2.0 / kThetaBins / kSubdivisions, dPhi = shader::kTwoPi / kPhiBins / kSubdivisions;
    for (int t = 0; t < kThetaBins; ++t) {
        for (int p = 0; p < kPhiBins; ++p) {
            double integral = 0.0;
            for (int j = 0; j < kSubdivisions; ++j) {
                double cosTheta = 1.0 - (t * kSubdivisions + j + 0.5) * dCos;
                double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
                for (int i = 0; i < kSubdivisions; ++i) {
                    double phi = (p * kSubdivisions + i + 0.5) * dPhi;
                    glm::vec3 d(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta);
                    integral += pdf(d);
                }
            }
            expected[t * kPhiBins + p] = integral * dCos * dPhi * kSamples;
        }
    }
    return chiSquareTest(observed, expected);
}

struct BrdfCase {
    const char* name;
    glm::vec3 albedo;
    glm::vec3 specular;
    float nu, nv;
    float incidentDegrees;
};

class BrdfChi2 : public ::testing::TestWithParam<BrdfCase> {};

} // namespace

TEST_P(BrdfChi2, SamplerMatchesDensity) {
    const BrdfCase& c = GetParam();
    shader::GpuMaterial m{};
    m.albedo = c.albedo;
    m.specular = c.specular;
    m.exponentU = c.nu;
    m.exponentV = c.nv;
    const glm::vec3 n(0, 0, 1);
    const float a = glm::radians(c.incidentDegrees);
    const glm::vec3 wi(std::sin(a), 0.0f, std::cos(a));
    ChiSquareResult r = testSampler([&](glm::vec3 u) { return shader::blSampleBrdf(m, m.albedo, n, wi, u); },
                                    [&](glm::vec3 d) { return double(shader::blBrdfPdf(m, m.albedo, n, wi, d)); }, 17);
    EXPECT_GT(r.pValue, kSignificance) << r.describe();
}

INSTANTIATE_TEST_SUITE_P(
    Materials, BrdfChi2,
    ::testing::Values(BrdfCase{"lambert", glm::vec3(0.8f), glm::vec3(0.0f), 1, 1, 30},
                      BrdfCase{"phong1", glm::vec3(0.0f), glm::vec3(0.9f), 1, 1, 20},
                      BrdfCase{"phong10", glm::vec3(0.0f), glm::vec3(0.9f), 10, 10, 50},
                      BrdfCase{"phong100_grazing", glm::vec3(0.0f), glm::vec3(0.9f), 100, 100, 75},
                      BrdfCase{"mixture", glm::vec3(0.4f), glm::vec3(0.3f), 30, 30, 40},
                      BrdfCase{"ashikhmin_shirley", glm::vec3(0.0f), glm::vec3(0.8f), 10, 100, 35},
                      BrdfCase{"as_mixture", glm::vec3(0.3f), glm::vec3(0.4f), 200, 20, 60}),
    [](const ::testing::TestParamInfo<BrdfCase>& p) { return std::string(p.param.name); });

TEST(EnvironmentChi2, LuminanceSamplingMatchesDensity) {
    BL_SKIP_WITHOUT_SHARED("data/envmap/classroom-sky.hdr");
    Environment env;
    env.present = true;
    env.map = readImage(sharedPath("data/envmap/classroom-sky.hdr"));
    env.rotationDegrees = 30.0f;
    EnvironmentLight light(env, true);
    ChiSquareResult r = testSampler(
        [&](glm::vec3 u) {
            float pdf;
            return light.sample(glm::vec2(u.x, u.y), &pdf);
        },
        [&](glm::vec3 d) { return double(light.pdf(d)); }, 23);
    EXPECT_GT(r.pValue, kSignificance) << r.describe();
}

TEST(EnvironmentChi2, SampledDensityMatchesPdfFunction) {
    BL_SKIP_WITHOUT_SHARED("data/envmap/vogl-probe.hdr");
    Environment env;
    env.present = true;
    env.map = readImage(sharedPath("data/envmap/vogl-probe.hdr"));
    EnvironmentLight light(env, true);
    for (std::uint32_t i = 0; i < 1000; ++i) {
        float pdf = 0.0f;
        glm::vec3 d = light.sample(glm::vec2(shader::blHashRandom(3u, 2 * i), shader::blHashRandom(3u, 2 * i + 1)), &pdf);
        ASSERT_NEAR(light.pdf(d), pdf, 1e-3f * pdf + 1e-6f) << i;
        ASSERT_GT(pdf, 0.0f);
    }
}

TEST(ChiSquare, DetectsAWrongDensity) {
    // A cosine sampler judged against the uniform hemisphere density must fail: the test can fail.
    ChiSquareResult r = testSampler([](glm::vec3 u) { return shader::blSampleCosineHemisphere(glm::vec2(u.x, u.y)); },
                                    [](glm::vec3 d) { return d.z > 0.0f ? 0.5 / shader::kPi : 0.0; }, 5);
    EXPECT_LT(r.pValue, 1e-6) << r.describe();
    EXPECT_NEAR(regularizedGammaQ(1.0, 2.0), std::exp(-2.0), 1e-12);
    EXPECT_NEAR(regularizedGammaQ(5.0, 3.0), 0.8152632445237722, 1e-10);
}

TEST(SphericalTriangleChi2, UniformInSolidAngle) {
    // A large, close triangle seen obliquely: area sampling would be far from uniform here.
    const glm::vec3 p(0.1f, -0.2f, 0.05f);
    const glm::vec3 a(-0.5f, -0.4f, 0.3f), b(0.9f, -0.3f, 0.5f), c(0.1f, 0.8f, 0.2f);
    const float omega = triangleSolidAngle(p, a, b, c);
    ASSERT_GT(omega, 0.5f);
    auto inside = [&](glm::vec3 d) {
        // Moeller-Trumbore: does the ray p + t d (t > 0) cross the triangle?
        glm::vec3 e1 = b - a, e2 = c - a, h = glm::cross(d, e2);
        float det = glm::dot(e1, h);
        if (std::abs(det) < 1e-12f) return false;
        glm::vec3 s = p - a;
        float u = glm::dot(s, h) / det;
        glm::vec3 q = glm::cross(s, e1);
        float v = glm::dot(d, q) / det;
        float t = glm::dot(e2, q) / det;
        return u >= 0.0f && v >= 0.0f && u + v <= 1.0f && t > 0.0f;
    };
    ChiSquareResult r = testSampler(
        [&](glm::vec3 u) {
            glm::vec3 d;
            return sampleSphericalTriangle(p, a, b, c, glm::vec2(u.x, u.y), d) ? d : glm::vec3(0.0f);
        },
        [&](glm::vec3 d) { return inside(d) ? 1.0 / omega : 0.0; }, 31);
    EXPECT_GT(r.pValue, kSignificance) << r.describe();
}
