// Host tests of bidir's glossy suppression (shaders/modes/bidir/Suppression.h; [TO12] Eq. 9-12,
// EQUATIONS.md section 2, CONVENTIONS.md "BRDFs") on closed-form cases.
//
// Eq. 9 reads max D <= d / m with m = m' f (n . wi) / D: whatever distribution D the lobe is
// written with, D cancels and the bound is on the lobe itself,
//     m' (n . wi) max_wo f_lobe(wi, wo) <= d                                    (*)
// "m' neighbours' worth of the lobe's peak contribution fits in the local sample density". For
// the normalized Phong lobe f = s (n + 2) / (2 pi) cos^n that is n <= 2 pi d / (m' s cos_i) - 2
// (the conventions' bound); for Ashikhmin-Shirley at normal incidence (wi.h = cos = 1, Fresnel =
// s) f_peak = s sqrt((nu + 1)(nv + 1)) / (8 pi). Roughness clamping must land exactly on (*)'s
// equality, clamp on it at the peak, and every mode leave a lobe that (*) already admits alone.
#include <gtest/gtest.h>
#include <modes/bidir/Suppression.h>

#include <cmath>

using namespace bl::shader;

namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr float kNeighbours = 16.0f; // m' of the paper
const glm::vec3 kN(0.0f, 0.0f, 1.0f);

GpuMaterial glossy(float s, float nu, float nv) {
    GpuMaterial m{};
    m.albedo = glm::vec3(0.2f);
    m.specular = glm::vec3(s);
    m.exponentU = nu;
    m.exponentV = nv;
    return m;
}

glm::vec3 incident(double degrees) {
    const double a = degrees * kPiD / 180.0;
    return glm::vec3(float(std::sin(a)), 0.0f, float(std::cos(a)));
}

glm::vec3 mirror(glm::vec3 wi) { return 2.0f * glm::dot(kN, wi) * kN - wi; }

// The lobe's part of the suppressed BRDF at (wi, wo): the whole minus Lambert.
double lobe(const GpuMaterial& m, glm::vec3 wi, glm::vec3 wo, float density, uint mode) {
    return double(blBidirEvalBrdf(m, m.albedo, kN, wi, wo, density, mode, kNeighbours).x - blLambert(m.albedo).x);
}

} // namespace

// Nothing to suppress: mode none, no specular, no density known (<= 0 or >= 1e30), or a lobe (*)
// admits: the BRDF exactly as blEvalBrdf has it.
TEST(Suppression, LeavesAdmissibleLobesAlone) {
    const GpuMaterial m = glossy(0.5f, 100.0f, 100.0f);
    const glm::vec3 wi = incident(30.0), wo = glm::normalize(mirror(wi) + glm::vec3(0.05f, 0.0f, 0.0f));
    const float exact = blEvalBrdf(m, m.albedo, kN, wi, wo).x;
    for (uint mode : {kBidirSuppressionClamp, kBidirSuppressionRoughness}) {
        EXPECT_EQ(blBidirEvalBrdf(m, m.albedo, kN, wi, wo, 1.0f, kBidirSuppressionNone, kNeighbours).x, exact);
        EXPECT_EQ(blBidirEvalBrdf(m, m.albedo, kN, wi, wo, 0.0f, mode, kNeighbours).x, exact);
        EXPECT_EQ(blBidirEvalBrdf(m, m.albedo, kN, wi, wo, 1e31f, mode, kNeighbours).x, exact);
        const GpuMaterial matte = glossy(0.0f, 100.0f, 100.0f);
        EXPECT_EQ(blBidirEvalBrdf(matte, matte.albedo, kN, wi, wo, 1.0f, mode, kNeighbours).x, blLambert(matte.albedo).x);
        // Density at (*)'s equality for this lobe, and 1% above it: unchanged.
        const double peak = 0.5 * (100.0 + 2.0) / (2.0 * kPiD);
        const float enough = float(1.01 * kNeighbours * wi.z * peak);
        EXPECT_FLOAT_EQ(blBidirEvalBrdf(m, m.albedo, kN, wi, wo, enough, mode, kNeighbours).x, exact) << mode;
    }
}

// Roughness clamping of the Phong lobe: the exponent becomes n' = 2 pi d / (m' s cos_i) - 2
// (CONVENTIONS.md), so the clamped lobe's peak value at the mirror direction meets (*) with
// equality, at several densities and angles; its value there is therefore d / (m' cos_i). A
// density too low for any lobe gives n' = 0 (never negative).
TEST(Suppression, RoughnessClampsThePhongExponentToEquation9) {
    for (float s : {1.0f, 0.3f}) {
        const GpuMaterial m = glossy(s, 1000.0f, 1000.0f);
        for (double degrees : {0.0, 40.0, 75.0}) {
            const glm::vec3 wi = incident(degrees);
            for (float density : {20.0f, 200.0f, 2000.0f}) {
                const double nPrime = 2.0 * kPiD * density / (kNeighbours * s * wi.z) - 2.0;
                ASSERT_GT(nPrime, 0.0);
                if (nPrime >= 1000.0) continue; // dense enough for the material's own lobe
                const double atPeak = lobe(m, wi, mirror(wi), density, kBidirSuppressionRoughness);
                EXPECT_NEAR(atPeak, density / (kNeighbours * wi.z), 1e-4 * atPeak)
                    << "s " << s << " at " << degrees << " density " << density << " (n' " << nPrime << ")";
                // Away from the peak: exactly the Phong lobe of exponent n'.
                const glm::vec3 wo = glm::normalize(mirror(wi) + glm::vec3(0.0f, 0.15f, 0.0f));
                const double expected = blPhongLobe(glm::vec3(s), float(nPrime), kN, wi, wo).x;
                EXPECT_NEAR(lobe(m, wi, wo, density, kBidirSuppressionRoughness), expected, 1e-4 * expected + 1e-7);
            }
        }
        // Far too sparse: exponent 0 (a uniform lobe s / pi), not a negative exponent.
        const double flat = lobe(m, kN, incident(50.0), 1e-3f, kBidirSuppressionRoughness);
        EXPECT_NEAR(flat, s / kPiD, 1e-6) << s;
    }
}

// Clamp: the lobe truncated at d / (m' cos_i) (its peak meets (*)), untouched where it is
// already below (far from the mirror direction).
TEST(Suppression, ClampTruncatesThePhongLobeAtEquation9) {
    const GpuMaterial m = glossy(0.8f, 500.0f, 500.0f);
    const glm::vec3 wi = incident(35.0);
    const float density = 100.0f;
    const double cap = density / (kNeighbours * wi.z);
    EXPECT_NEAR(lobe(m, wi, mirror(wi), density, kBidirSuppressionClamp), cap, 1e-4 * cap);
    const glm::vec3 wo = glm::normalize(mirror(wi) + glm::vec3(0.0f, 0.12f, 0.0f));
    const double tail = blPhongLobe(m.specular, m.exponentU, kN, wi, wo).x;
    ASSERT_LT(tail, cap);
    EXPECT_NEAR(lobe(m, wi, wo, density, kBidirSuppressionClamp), tail, 1e-5 * tail + 1e-9);
}

// Ashikhmin-Shirley (Eq. 11-12, each axis like Eq. 10) at normal incidence, both exponents
// clamped: sqrt((nu' + 1)(nv' + 1)) = 8 pi d / (m' s), so the peak (h = n) meets (*) with equality.
// An anisotropic lobe whose peak sqrt((nu + 1)(nv + 1)) / (2 pi) exceeds d / m has each axis
// clamped to a' + 1 <= 2 pi d / m (an axis already below keeps its exponent), with m = m' f cos / D
// = m' s cos_i / (4 (wi.h) max(cos_i, cos_o)) at wo.
TEST(Suppression, RoughnessClampsAshikhminShirleyExponents) {
    glm::vec3 t, b;
    blOrthonormalBasis(kN, t, b);
    const float s = 0.6f;
    const GpuMaterial sharp = glossy(s, 2000.0f, 3000.0f); // (equal exponents would be Phong)
    const float density = 300.0f;
    const double atPeak = lobe(sharp, kN, kN, density, kBidirSuppressionRoughness);
    EXPECT_NEAR(atPeak, density / kNeighbours, 1e-4 * atPeak);

    const GpuMaterial aniso = glossy(s, 5.0f, 2000.0f); // peak sqrt(6 * 2001) / (2 pi) = 17.4
    const float sparse = 20.0f;
    const glm::vec3 wo = glm::normalize(glm::vec3(0.03f, 0.02f, 1.0f));
    const double kh = glm::dot(kN, glm::normalize(kN + wo));
    const double allowed = sparse / (kNeighbours * s / (4.0 * kh));
    const double bound = 2.0 * kPiD * allowed - 1.0;
    ASSERT_GT(bound, 5.0);
    ASSERT_LT(bound, 2000.0);
    const double expected = blAshikhminShirleyLobe(glm::vec3(s), 5.0f, float(bound), kN, t, b, kN, wo).x;
    EXPECT_NEAR(lobe(aniso, kN, wo, sparse, kBidirSuppressionRoughness), expected, 1e-4 * expected);
    // Its peak is below d / m at density 300: left alone, however sharp its v axis.
    EXPECT_EQ(lobe(aniso, kN, wo, density, kBidirSuppressionRoughness),
              double(blAshikhminShirleyLobe(glm::vec3(s), 5.0f, 2000.0f, kN, t, b, kN, wo).x));
}

// Eq. 10 itself: the exponent whose (a + 1) / (2 pi) peak equals the given one, never above
// the material's and never negative.
TEST(Suppression, ClampedExponentEquation10) {
    EXPECT_FLOAT_EQ(blBidirClampedExponent(100.0f, 3.0f), float(2.0 * kPiD * 3.0 - 1.0));
    EXPECT_FLOAT_EQ(blBidirClampedExponent(10.0f, 3.0f), 10.0f);
    EXPECT_FLOAT_EQ(blBidirClampedExponent(10.0f, 0.01f), 0.0f);
}
