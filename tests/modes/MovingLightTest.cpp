// A keyframed point light over a Lambertian plane: raster and reference, each at two scene times,
// against the closed form E = I cos(theta) / r^2 at the light's position at that time.
#include "modes/Registry.h"
#include "support/AnalyticScenes.h"
#include "support/VulkanTest.h"

#include <gtest/gtest.h>

using namespace bl;

namespace {

constexpr float kAlbedo = 0.5f;
constexpr float kIntensity = 10.0f;
constexpr float kHeight = 1.0f;
constexpr int kResolution = 48;
constexpr double kLaterTime = 2.0; // seconds: the light's second key
// The light starts at the plain point-over-plane position and moves sideways and up.
const glm::vec3 kLaterPosition(1.5f, 1.6f, -0.5f);
// Sub-pixel grid for the closed form averaged over a pixel (the reference's box filter).
constexpr int kFootprintSamples = 6;
// Where the plane's edge crosses pixels: keep away from it (the plane spans |x|, |z| < 4).
constexpr float kPlaneInterior = 3.8f;

Scene movingLightScene() {
    Scene s = bl::test::pointLightOverPlane(kAlbedo, kIntensity, kHeight, kResolution);
    Light& light = s.lights.at(0);
    light.keys.push_back({0.0, light.position, light.direction});
    light.keys.push_back({kLaterTime, kLaterPosition, light.direction});
    return s;
}

ImageSet render(const std::string& mode, const Scene& scene, double time, std::uint32_t iterations,
                const std::vector<std::string>& settings, vk::Context* ctx) {
    std::unique_ptr<Mode> m = createMode(mode, settings);
    m->setScene(scene, ctx);
    for (std::uint32_t i = 0; i < iterations; ++i) {
        m->iterate({i, 0, time, time, 0});
    }
    return m->resolve();
}

// Compares `image` with the closed form for the light at `time`; the worst relative error.
float worstError(const Scene& s, const Image& image, double time, bool footprint, int& checked) {
    const glm::vec3 light = s.lightsAt(time).at(0).position;
    float worst = 0.0f;
    checked = 0;
    for (int y = 0; y < kResolution; ++y) {
        for (int x = 0; x < kResolution; ++x) {
            float t;
            glm::vec3 p = bl::test::cameraRayHitY(s, glm::vec2(x + 0.5f, y + 0.5f), 0.0f, t);
            if (t <= 0.0f || std::abs(p.x) > kPlaneInterior || std::abs(p.z) > kPlaneInterior) {
                continue;
            }
            float expected = bl::test::pointLitFloorRadiance(p, light, kIntensity, kAlbedo);
            if (footprint) {
                expected = 0.0f;
                for (int j = 0; j < kFootprintSamples; ++j) {
                    for (int i = 0; i < kFootprintSamples; ++i) {
                        glm::vec2 q(x + (i + 0.5f) / kFootprintSamples, y + (j + 0.5f) / kFootprintSamples);
                        expected += bl::test::pointLitFloorRadiance(bl::test::cameraRayHitY(s, q, 0.0f, t), light,
                                                                    kIntensity, kAlbedo) /
                                    float(kFootprintSamples * kFootprintSamples);
                    }
                }
            }
            worst = std::max(worst, std::abs(image.at(x, y).x - expected) / expected);
            ++checked;
        }
    }
    return worst;
}

// The two times must give clearly different images, or the comparison proves nothing.
void expectTimesDiffer(const Image& early, const Image& late) {
    constexpr double kMinimumChange = 0.1; // relative change of the mean radiance
    const double a = early.mean().x, b = late.mean().x;
    EXPECT_GT(std::abs(a - b), kMinimumChange * a) << "means " << a << " and " << b;
}

} // namespace

class MovingLight : public bl::test::VulkanTest {};

TEST_F(MovingLight, RasterFollowsTheLightAtEachTime) {
    const Scene s = movingLightScene();
    Image images[2];
    for (int k = 0; k < 2; ++k) {
        const double time = k == 0 ? 0.0 : kLaterTime;
        images[k] = render("raster", s, time, 1, {}, &ctx()).radiance();
        int checked = 0;
        const float worst = worstError(s, images[k], time, false, checked);
        EXPECT_GT(checked, kResolution * kResolution / 2);
        EXPECT_LT(worst, 0.01f) << "time " << time << ": worst relative error over " << checked << " pixels";
    }
    expectTimesDiffer(images[0], images[1]);
}

TEST(MovingLightReference, ReferenceFollowsTheLightAtEachTime) {
    const Scene s = movingLightScene();
    constexpr std::uint32_t kSamplesPerPixel = 16;
    Image images[2];
    for (int k = 0; k < 2; ++k) {
        const double time = k == 0 ? 0.0 : kLaterTime;
        images[k] = render("reference", s, time, kSamplesPerPixel, {"max_segments=2"}, nullptr).radiance();
        int checked = 0;
        const float worst = worstError(s, images[k], time, true, checked);
        EXPECT_GT(checked, kResolution * kResolution / 2);
        EXPECT_LT(worst, 0.01f) << "time " << time << ": worst relative error over " << checked << " pixels";
    }
    expectTimesDiffer(images[0], images[1]);
}
