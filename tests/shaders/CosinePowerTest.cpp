// Sharp lobes in float (shaders/shared/CosinePower.h): cos^e and the lobe samplers against double
// precision at exponents to 1e8, where pow(dot(a, b), e) in float is off by percents (the stress
// suite's phong-1e6 read 3.7% apart between the GPU modes and the reference).
#include <gtest/gtest.h>
#include <shared/BrdfSampling.h>
#include <shared/CosinePower.h>

#include <cmath>

using namespace bl::shader;

namespace {

// Unit float vectors at angle theta about an axis tilted off the coordinate axes (so that neither
// has exact components), and their angle recomputed in double from the floats themselves.
struct Pair {
    glm::vec3 a, b;
    double oneMinusCos; // of the float vectors, in double
};

glm::dvec3 d3(glm::vec3 v) { return glm::dvec3(v); }

Pair pairAt(double theta) {
    const glm::dvec3 axis = glm::normalize(glm::dvec3(0.3, 0.8, 0.52));
    const glm::dvec3 side = glm::normalize(glm::cross(axis, glm::dvec3(0, 0, 1)));
    Pair p;
    p.a = glm::vec3(axis);
    p.b = glm::vec3(std::cos(theta) * axis + std::sin(theta) * side);
    const glm::dvec3 a = glm::normalize(d3(p.a)), b = glm::normalize(d3(p.b));
    const glm::dvec3 diff = a - b;
    p.oneMinusCos = 0.5 * glm::dot(diff, diff);
    return p;
}

double exactPower(double oneMinusCos, double e) { return std::exp(e * std::log1p(-oneMinusCos)); }

} // namespace

// Where the lobe has weight (e x = e (1 - cos) <= 20, cos^e >= 2e-9), float's relative error of
// |a - b|^2 is a few ulps (<= 4 x 6e-8), which moves the power by e x times that: <= 5e-6.
TEST(CosinePower, MatchesDoubleAcrossSharpLobes) {
    for (double e : {1.0, 1e2, 1e4, 1e6, 1e8}) {
        for (double ex : {0.01, 0.1, 0.5, 1.0, 2.0, 5.0, 20.0}) {
            if (ex / e > 0.5) continue; // beyond 60 degrees: not a sharp lobe's concern
            const Pair p = pairAt(std::acos(1.0 - ex / e));
            const double want = exactPower(p.oneMinusCos, e);
            const double got = blCosinePower(p.a, p.b, float(e));
            EXPECT_NEAR(got / want, 1.0, 5e-6) << "e " << e << " e(1-cos) " << ex;
        }
    }
    EXPECT_EQ(blCosinePower(glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), 1.0f), 0.0f); // cos = 0
    EXPECT_EQ(blCosinePower(glm::vec3(0, 0, 1), glm::vec3(0, 0.6f, -0.8f), 3.0f), 0.0f); // cos < 0
    EXPECT_EQ(blCosinePower(glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), 1e6f), 1.0f);
}

// What the old code computed, for the record: pow(dot(a, b), e) in float is off by more than 1%
// somewhere in the 1e6 lobe (so the test above can tell the two apart).
TEST(CosinePower, FloatPowOfDotIsNotAccurateEnough) {
    double worst = 0.0;
    for (double ex = 0.05; ex < 5.0; ex += 0.05) {
        const Pair p = pairAt(std::acos(1.0 - ex / 1e6));
        const double naive = std::pow(glm::dot(p.a, p.b), 1e6f);
        worst = std::max(worst, std::abs(naive / exactPower(p.oneMinusCos, 1e6) - 1.0));
    }
    EXPECT_GT(worst, 0.01);
}

// The samplers' 1 - cos: the exact CDF of the lobe cos^e (density (e + 1) cos^e on the
// hemisphere's cos), F(1 - cos = t) = 1 - (1 - t)^(e + 1), must give back u. Float's own 1 - cos
// near 1 would be quantized to 6e-8, i.e. to steps of 6% of the 1e6 lobe's width.
TEST(CosinePower, LobeSampleInvertsTheExactCdf) {
    for (double e : {1.0, 1e2, 1e4, 1e6, 1e8}) {
        for (double u : {1e-4, 0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99}) {
            const double t = blOneMinusCosineSample(float(u), float(e));
            const double back = 1.0 - exactPower(t, e + 1.0);
            EXPECT_NEAR(back, double(float(u)), 2e-6) << "e " << e << " u " << u;
        }
    }
}

// The whole Phong sampler: the sampled direction's angle to the lobe axis, from the float
// direction in double, follows the same CDF (the frame and the sine are computed accurately too).
TEST(CosinePower, PhongSamplerDirectionFollowsTheLobe) {
    const glm::vec3 r = glm::normalize(glm::vec3(0.3f, 0.8f, 0.52f));
    for (double e : {1e4, 1e6}) {
        for (double u : {0.05, 0.3, 0.6, 0.9}) {
            const glm::vec3 d = blSamplePhongLobe(float(e), r, glm::vec2(float(u), 0.37f));
            const glm::dvec3 diff = glm::normalize(d3(d)) - glm::normalize(d3(r));
            const double t = 0.5 * glm::dot(diff, diff);
            const double back = 1.0 - exactPower(t, e + 1.0);
            // 1e-3: the float direction's own rounding near the axis (the old sampler: 0.03 (1 - u))
            EXPECT_NEAR(back, u, 1e-3) << "e " << e << " u " << u;
        }
    }
}
