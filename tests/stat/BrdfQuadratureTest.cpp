// Oracles for the shared BRDFs (shaders/shared/Brdf.h; CONVENTIONS.md "BRDFs"): normalization and
// directional albedo by deterministic quadrature over the sphere of outgoing directions, compared
// with closed forms derived here. Nothing here uses the BRDFs' samplers or pdfs: the reference
// path tracer and every mode share Brdf.h, so a wrong constant in it would pass every comparison
// between them; it cannot pass these.
#include <gtest/gtest.h>
#include <shared/Brdf.h>

#include <cmath>
#include <functional>

using namespace bl::shader;

namespace {

constexpr double kPiD = 3.14159265358979323846;

// Integral of g(w) over the cap of directions w with axis . w >= cosMin, by the midpoint rule in
// (s, phi) with cos(alpha) = 1 - (1 - cosMin) s^2: points crowd toward the axis (the first cell
// spans 1 - cos ~ 1e-7), so a lobe of exponent 1e3 about the axis gets ~100 cells across it.
// d omega = d cos(alpha) d phi = 2 (1 - cosMin) s ds dphi.
double integrateCap(const std::function<double(glm::vec3)>& g, glm::vec3 axis, double cosMin, int steps = 2000,
                    int azimuths = 256) {
    glm::vec3 t, b;
    blOrthonormalBasis(axis, t, b);
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double s = (i + 0.5) / steps;
        const double cosA = 1.0 - (1.0 - cosMin) * s * s, sinA = std::sqrt(std::max(0.0, 1.0 - cosA * cosA));
        double ring = 0.0;
        for (int j = 0; j < azimuths; ++j) {
            const double phi = 2.0 * kPiD * (j + 0.5) / azimuths;
            const glm::vec3 w = glm::normalize(float(sinA * std::cos(phi)) * t + float(sinA * std::sin(phi)) * b +
                                               float(cosA) * axis);
            ring += g(w);
        }
        sum += ring * 2.0 * (1.0 - cosMin) * s;
    }
    return sum * (1.0 / steps) * (2.0 * kPiD / azimuths);
}

const glm::vec3 kNormal(0.0f, 0.0f, 1.0f);

glm::vec3 incident(double degrees) {
    const double a = degrees * kPiD / 180.0;
    return glm::vec3(float(std::sin(a)), 0.0f, float(std::cos(a)));
}

glm::vec3 mirror(glm::vec3 wi) { return 2.0f * glm::dot(kNormal, wi) * kNormal - wi; }

// Cosine-weighted directional albedo of f(wi, .) over the upper hemisphere, integrated in
// coordinates about `axis` (the lobe's peak) over the whole sphere, the lower half cut off.
double albedo(const std::function<glm::vec3(glm::vec3)>& f, glm::vec3 axis) {
    return integrateCap([&](glm::vec3 wo) { return wo.z > 0.0f ? double(f(wo).x) * wo.z : 0.0; }, axis, -1.0);
}

// g(e) = integral over u = cos(theta_h) from 1/sqrt(2) to 1 of u^e (2 u^2 - 1): the reflected
// direction's cosine 2 u^2 - 1 at normal incidence, over the half vectors that keep it above the
// surface (theta_h < 45 degrees).
double halfVectorMoment(double e) {
    const double c = std::sqrt(0.5);
    return 2.0 * (1.0 - std::pow(c, e + 3.0)) / (e + 3.0) - (1.0 - std::pow(c, e + 1.0)) / (e + 1.0);
}

} // namespace

// Lambert: f = albedo / pi (independent of wi), so the cosine-weighted albedo is the albedo.
TEST(BrdfQuadrature, LambertAlbedoIsItsAlbedo) {
    EXPECT_NEAR(albedo([](glm::vec3) { return blLambert(glm::vec3(0.7f)); }, kNormal), 0.7, 1e-5);
}

// Normalized Phong lobe f = s (n + 2) / (2 pi) cos^n(r . wo). At normal incidence r = n and
//   integral f cos d omega = s (n + 2) / (2 pi) * 2 pi / (n + 2) = s      (cosine-weighted albedo)
//   integral f d omega     = s (n + 2) / (n + 1)                          (the lobe's mass)
// At oblique incidence the lobe is cut by the surface and weighted by cos(theta_o) < cos(alpha)
// on one side: albedo < s, falling with the angle. (A normalization (n + 1) / (2 pi) would give
// (n + 1) / (n + 2) at normal incidence: 1/3 off at n = 1, 0.1% at n = 1000.)
TEST(BrdfQuadrature, PhongLobeNormalizationAndAlbedo) {
    for (float n : {0.0f, 1.0f, 4.0f, 30.0f, 300.0f, 1000.0f}) {
        const auto lobe = [&](glm::vec3 wi) {
            return [=](glm::vec3 wo) { return blPhongLobe(glm::vec3(1.0f), n, kNormal, wi, wo); };
        };
        const double normal = albedo(lobe(kNormal), kNormal);
        const double mass =
            integrateCap([&](glm::vec3 wo) { return double(lobe(kNormal)(wo).x); }, kNormal, 0.0);
        EXPECT_NEAR(normal, 1.0, 2e-4) << "exponent " << n;
        EXPECT_NEAR(mass, (n + 2.0) / (n + 1.0), 2e-4 * (n + 2.0) / (n + 1.0)) << "exponent " << n;
        double previous = normal;
        for (double degrees : {30.0, 60.0, 85.0}) {
            const glm::vec3 wi = incident(degrees);
            const double a = albedo(lobe(wi), mirror(wi));
            EXPECT_LE(a, previous + 2e-4) << "exponent " << n << " at " << degrees;
            EXPECT_GT(a, 0.0);
            previous = a;
        }
    }
}

// The full material (Lambert + Phong lobe) at normal incidence: albedo + specular.
TEST(BrdfQuadrature, MaterialAlbedoIsLambertPlusLobe) {
    GpuMaterial m{};
    m.albedo = glm::vec3(0.3f);
    m.specular = glm::vec3(0.6f);
    m.exponentU = m.exponentV = 50.0f;
    const double a = albedo([&](glm::vec3 wo) { return blEvalBrdf(m, m.albedo, kNormal, kNormal, wo); }, kNormal);
    EXPECT_NEAR(a, 0.9, 2e-4);
}

// Ashikhmin-Shirley with specular 1 (Schlick's Fresnel is then 1): f = D(h) / (4 (wi.h)
// max(cos_i, cos_o)) with D(h) = sqrt((nu + 1)(nv + 1)) / (2 pi) (n.h)^(nu cos^2 phi + nv sin^2 phi)
// a density of half vectors (integral D d omega_h = 1, since integral over phi of
// 1 / (1 + nu cos^2 + nv sin^2) is 2 pi / sqrt((nu + 1)(nv + 1))). At normal incidence
// cos_i = 1, d omega_o = 4 (wi.h) d omega_h and cos_o = 2 (n.h)^2 - 1, so the albedo is
//   sqrt((nu + 1)(nv + 1)) / (2 pi) * integral over phi of g(e(phi)),  g = halfVectorMoment,
// a 1D integral in phi (midpoint rule, 4096 points) against the 2D quadrature of the lobe.
// Isotropic: (n + 1) g(n), e.g. 0.5 at n = 0 ... 1 - O(1/n).
TEST(BrdfQuadrature, AshikhminShirleyAlbedoAtNormalIncidence) {
    for (glm::vec2 e : {glm::vec2(1, 1), glm::vec2(10, 10), glm::vec2(200, 200), glm::vec2(5, 80), glm::vec2(1000, 20)}) {
        glm::vec3 t, b;
        blOrthonormalBasis(kNormal, t, b);
        const double a = albedo(
            [&](glm::vec3 wo) {
                return blAshikhminShirleyLobe(glm::vec3(1.0f), e.x, e.y, kNormal, t, b, kNormal, wo);
            },
            kNormal);
        double closed = 0.0;
        constexpr int kAzimuths = 4096;
        for (int j = 0; j < kAzimuths; ++j) {
            const double phi = 2.0 * kPiD * (j + 0.5) / kAzimuths, c = std::cos(phi), s = std::sin(phi);
            closed += halfVectorMoment(e.x * c * c + e.y * s * s);
        }
        closed *= std::sqrt((e.x + 1.0) * (e.y + 1.0)) / (2.0 * kPiD) * (2.0 * kPiD / kAzimuths);
        EXPECT_NEAR(a, closed, 5e-4) << "exponents " << e.x << ", " << e.y;
        EXPECT_LE(a, 1.0) << "exponents " << e.x << ", " << e.y;
        if (e.x == e.y) {
            EXPECT_NEAR(closed, (e.x + 1.0) * halfVectorMoment(e.x), 1e-9);
        }
    }
}

// Oblique incidence: every lobe's cosine-weighted albedo stays <= 1 with unit specular (energy
// conservation), by quadrature about the mirror direction.
TEST(BrdfQuadrature, AshikhminShirleyAlbedoAtMostOne) {
    glm::vec3 t, b;
    blOrthonormalBasis(kNormal, t, b);
    for (glm::vec2 e : {glm::vec2(1, 1), glm::vec2(100, 100), glm::vec2(5, 80)}) {
        for (double degrees : {30.0, 60.0, 85.0}) {
            const glm::vec3 wi = incident(degrees);
            const double a = albedo(
                [&](glm::vec3 wo) { return blAshikhminShirleyLobe(glm::vec3(1.0f), e.x, e.y, kNormal, t, b, wi, wo); },
                mirror(wi));
            EXPECT_LE(a, 1.0 + 5e-4) << "exponents " << e.x << ", " << e.y << " at " << degrees;
            EXPECT_GT(a, 0.1);
        }
    }
}
