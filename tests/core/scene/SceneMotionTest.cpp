// Scene bounds over the whole motion of animated meshes, not only at their keyframes.
#include "scene/Scene.h"

#include <gtest/gtest.h>

using namespace bl;

namespace {

// A long thin bar along x: two triangles from x = -kHalfLength to +kHalfLength.
constexpr float kHalfLength = 10.0f;
constexpr float kHalfWidth = 0.1f;

Mesh bar() {
    Mesh m;
    m.positions = {{-kHalfLength, 0, -kHalfWidth}, {kHalfLength, 0, -kHalfWidth},
                   {kHalfLength, 0, kHalfWidth},   {-kHalfLength, 0, kHalfWidth}};
    m.triangles = {{0, 2, 1}, {0, 3, 2}};
    return m;
}

// Every transformed vertex at `samples` times over [t0, t1] lies inside `b` (within `slack`).
void expectMotionInside(const Scene& scene, const Bounds& b, double t0, double t1, int samples) {
    const float slack = 1e-4f * b.radius();
    for (int i = 0; i <= samples; ++i) {
        const double t = t0 + (t1 - t0) * i / samples;
        for (const Mesh& m : scene.meshes) {
            const glm::mat4 transform = m.animation.at(t);
            for (const glm::vec3& p : m.positions) {
                const glm::vec3 w(transform * glm::vec4(p, 1.0f));
                for (int a = 0; a < 3; ++a) {
                    ASSERT_GE(w[a], b.lo[a] - slack) << "t " << t << " axis " << a;
                    ASSERT_LE(w[a], b.hi[a] + slack) << "t " << t << " axis " << a;
                }
            }
        }
    }
}

} // namespace

TEST(SceneMotion, BoundsContainARotatingBarBetweenItsKeyframes) {
    Scene scene;
    Mesh m = bar();
    // Half a turn about y: along x at both keys, along z at mid-rotation.
    m.animation.addKey({0.0, glm::vec3(0.0f), rotationFromEulerDegrees({0, 0, 0})});
    m.animation.addKey({1.0, glm::vec3(0.0f), rotationFromEulerDegrees({0, 180, 0})});
    scene.meshes.push_back(m);
    const Bounds b = scene.bounds();
    EXPECT_GE(b.hi.z, kHalfLength * 0.999f);
    expectMotionInside(scene, b, -0.5, 1.5, 200);
}

TEST(SceneMotion, BoundsContainRotationCombinedWithTranslation) {
    Scene scene;
    Mesh m = bar();
    m.animation.addKey({0.0, glm::vec3(0.0f), rotationFromEulerDegrees({0, 0, 0})});
    m.animation.addKey({2.0, glm::vec3(5.0f, 3.0f, -4.0f), rotationFromEulerDegrees({30, 170, 10})});
    m.animation.addKey({3.0, glm::vec3(-5.0f, 0.0f, 0.0f), rotationFromEulerDegrees({0, 0, 90})});
    scene.meshes.push_back(m);
    const Bounds b = scene.bounds();
    expectMotionInside(scene, b, 0.0, 3.0, 600);
    // Conservative, not loose: no more than a few percent beyond the swept extent.
    Bounds sampled;
    for (int i = 0; i <= 3000; ++i) {
        const glm::mat4 transform = m.animation.at(3.0 * i / 3000);
        for (const glm::vec3& p : m.positions) {
            sampled.extend(glm::vec3(transform * glm::vec4(p, 1.0f)));
        }
    }
    constexpr float kAllowedLooseness = 0.05f; // of the swept radius, per side
    EXPECT_LE(glm::length(b.lo - sampled.lo), kAllowedLooseness * sampled.radius());
    EXPECT_LE(glm::length(b.hi - sampled.hi), kAllowedLooseness * sampled.radius());
}

TEST(SceneMotion, KeyframedLightsMoveLinearlyAndClampOutsideTheirKeys) {
    Scene scene;
    Light spot;
    spot.type = Light::Type::Spot;
    spot.position = glm::vec3(9.0f); // replaced by the keys
    spot.intensity = glm::vec3(1.0f);
    spot.keys.push_back({0.0, glm::vec3(0, 1, 0), glm::vec3(0, -1, 0)});
    spot.keys.push_back({2.0, glm::vec3(4, 1, 0), glm::vec3(1, 0, 0)});
    scene.lights.push_back(spot);
    Light fixed;
    fixed.position = glm::vec3(0, 5, 0);
    scene.lights.push_back(fixed);

    const std::vector<Light> mid = scene.lightsAt(1.0);
    ASSERT_EQ(mid.size(), 2u);
    EXPECT_EQ(mid[0].position, glm::vec3(2, 1, 0));
    EXPECT_NEAR(glm::length(mid[0].direction), 1.0f, 1e-6f);
    EXPECT_NEAR(mid[0].direction.x, -mid[0].direction.y, 1e-6f); // halfway between -y and +x
    EXPECT_EQ(mid[0].intensity, glm::vec3(1.0f));
    EXPECT_EQ(mid[1].position, glm::vec3(0, 5, 0));
    EXPECT_EQ(scene.lightsAt(-1.0)[0].position, glm::vec3(0, 1, 0));
    EXPECT_EQ(scene.lightsAt(5.0)[0].position, glm::vec3(4, 1, 0));
    EXPECT_TRUE(scene.features().animated);
}
