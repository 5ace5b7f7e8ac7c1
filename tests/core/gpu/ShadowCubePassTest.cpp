// Shadow cubes rendered from the scene's lights and from arbitrary points (virtual point lights).
#include "base/Error.h"
#include "gpu/ShadowCubePass.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"

#include <shared/CubeFaces.h>

#include <cmath>
#include <cstring>
#include <optional>
#include <random>
#include <vector>

using namespace bl;

namespace {

constexpr std::uint32_t kResolution = 16; // texels per face side
constexpr std::uint32_t kDownFace = 3;    // CubeFaces.h: -y
// Stored distances come from interpolated world positions at texel centres: float precision.
constexpr float kRelativeTolerance = 1e-5f;

class ShadowCubePassTest : public test::VulkanTest {};

// Distance from a point at `height` over the plane y = 0 along the centre ray of texel (i, j) of
// the -y face.
float distanceToFloor(float height, std::uint32_t i, std::uint32_t j) {
    glm::vec3 r, u, f;
    shader::blCubeFaceBasis(kDownFace, r, u, f);
    const glm::vec2 c = (glm::vec2(i, j) + 0.5f) / float(kResolution) * 2.0f - 1.0f;
    const glm::vec3 ray = glm::normalize(f + c.x * r - c.y * u);
    return height / -ray.y;
}

// Largest relative error of cube `cube`'s -y face against a floor `height` below its centre.
float worstFloorError(const vk::Context& ctx, const gpu::ShadowCubePass& pass, std::uint32_t cube, float height) {
    std::vector<std::byte> raw = pass.maps().download(ctx, VK_IMAGE_LAYOUT_GENERAL, 6 * cube + kDownFace);
    // shaders/gpu/ShadowTexel.glsl: per texel the distance's float bits, then the packed normal.
    std::vector<float> stored(raw.size() / sizeof(float));
    std::memcpy(stored.data(), raw.data(), stored.size() * sizeof(float));
    constexpr std::uint32_t kStride = gpu::ShadowCubePass::kBytesPerTexel / sizeof(float);
    float worst = 0.0f;
    for (std::uint32_t j = 0; j < kResolution; ++j) {
        for (std::uint32_t i = 0; i < kResolution; ++i) {
            const float expected = distanceToFloor(height, i, j);
            worst = std::max(worst, std::abs(stored[kStride * (j * kResolution + i)] - expected) / expected);
        }
    }
    return worst;
}

} // namespace

// The analytic scene's light hangs 1 over a 10 x 10 floor; a virtual point 0.5 over it goes into
// cube 1. Each cube's downward face must hold its own distances, and rendering cube 1 must leave
// the light's cube 0 as it was.
TEST_F(ShadowCubePassTest, CubeFromAnArbitraryPointIntoAChosenLayer) {
    Scene scene = loadScene(test::sourcePath("data/analytic/point-over-plane.toml"));
    gpu::GpuScene gpuScene(ctx(), scene);
    gpu::ShadowCubePass pass(ctx(), gpuScene, kResolution, 2);
    ASSERT_EQ(pass.lightCount(), 1u);
    const float lightHeight = scene.lights[0].position.y;
    const glm::vec3 virtualLight(0.3f, 0.5f, -0.2f);

    ctx().submitAndWait([&](VkCommandBuffer cmd) {
        pass.record(cmd, 0.0, nullptr);
        pass.record(cmd, virtualLight, 1, 0.0, nullptr);
    });
    EXPECT_LT(worstFloorError(ctx(), pass, 0, lightHeight), kRelativeTolerance);
    EXPECT_LT(worstFloorError(ctx(), pass, 1, virtualLight.y), kRelativeTolerance);
    // The test can fail: the light's cube does not hold the virtual point's distances.
    EXPECT_GT(worstFloorError(ctx(), pass, 0, virtualLight.y), 0.5f);
}

TEST_F(ShadowCubePassTest, TooFewCubesForTheLightsIsAClearError) {
    Scene scene = loadScene(test::sourcePath("data/analytic/point-over-plane.toml"));
    gpu::GpuScene gpuScene(ctx(), scene);
    EXPECT_THROW(gpu::ShadowCubePass(ctx(), gpuScene, kResolution, 0), Error);
}

// The refresh rule the modes share: a static scene's light cubes once, a moving scene's whenever
// the scene time changes, never without lights.
TEST_F(ShadowCubePassTest, RefreshesOnceForStaticScenesAndOnEveryNewTimeForMovingOnes) {
    Scene still = loadScene(test::sourcePath("data/analytic/point-over-plane.toml"));
    gpu::GpuScene stillGpu(ctx(), still);
    gpu::ShadowCubePass stillPass(ctx(), stillGpu, kResolution);
    EXPECT_TRUE(stillPass.refreshFor(ctx(), stillGpu, 0.0));
    EXPECT_FALSE(stillPass.refreshFor(ctx(), stillGpu, 0.0));
    EXPECT_FALSE(stillPass.refreshFor(ctx(), stillGpu, 1.0)); // nothing moves: the cubes hold

    Scene moving = loadScene(test::sourcePath("data/cornell-box/cornell-animated.toml"));
    ASSERT_TRUE(moving.features().animated);
    gpu::GpuScene movingGpu(ctx(), moving);
    gpu::ShadowCubePass movingPass(ctx(), movingGpu, kResolution);
    EXPECT_TRUE(movingPass.refreshFor(ctx(), movingGpu, 0.0));
    EXPECT_FALSE(movingPass.refreshFor(ctx(), movingGpu, 0.0));
    EXPECT_TRUE(movingPass.refreshFor(ctx(), movingGpu, 0.5));
    EXPECT_FALSE(movingPass.refreshFor(ctx(), movingGpu, 0.5));
    EXPECT_TRUE(movingPass.refreshFor(ctx(), movingGpu, 0.0));

    Scene dark = loadScene(test::sourcePath("data/cornell-box/cornell.toml")); // an area light only
    gpu::GpuScene darkGpu(ctx(), dark);
    gpu::ShadowCubePass darkPass(ctx(), darkGpu, kResolution);
    EXPECT_FALSE(darkPass.refreshFor(ctx(), darkGpu, 0.0));
}

namespace {

bool inside(const VkRect2D& rect, std::uint32_t i, std::uint32_t j) {
    return i >= std::uint32_t(rect.offset.x) && i < rect.offset.x + rect.extent.width && j >= std::uint32_t(rect.offset.y) &&
           j < rect.offset.y + rect.extent.height;
}

// The centre ray of texel (i, j) of `face` (CubeFaces.h: column (x + 1) / 2 N, row (1 - y) / 2 N).
glm::vec3 centreRay(std::uint32_t face, std::uint32_t i, std::uint32_t j, std::uint32_t n) {
    glm::vec3 r, u, f;
    shader::blCubeFaceBasis(face, r, u, f);
    const float x = (float(i) + 0.5f) / float(n) * 2.0f - 1.0f;
    const float y = 1.0f - (float(j) + 0.5f) / float(n) * 2.0f;
    return f + x * r + y * u;
}

} // namespace

// A one-sided emitter's cube renders only the texels that can see its front (frontTexels): every
// texel whose centre ray has d . front >= 0 must lie in its face's rectangle, for fronts in every
// direction; a face-on front keeps one whole face, four halves (and a texel's margin) and no sixth.
TEST(ShadowCubeFront, RectanglesHoldEveryTexelThatCanBeLit) {
    constexpr std::uint32_t n = 16;
    std::mt19937 rng(7);
    std::normal_distribution<float> normal;
    for (int trial = 0; trial < 500; ++trial) {
        const glm::vec3 front = glm::normalize(glm::vec3(normal(rng), normal(rng), normal(rng)));
        for (std::uint32_t face = 0; face < 6; ++face) {
            const std::optional<VkRect2D> rect = gpu::ShadowCubePass::frontTexels(face, front, n);
            for (std::uint32_t j = 0; j < n; ++j) {
                for (std::uint32_t i = 0; i < n; ++i) {
                    if (glm::dot(centreRay(face, i, j, n), front) >= 0.0f) {
                        ASSERT_TRUE(rect && inside(*rect, i, j)) << "front " << front.x << " " << front.y << " "
                                                                 << front.z << ", face " << face << ", texel " << i
                                                                 << " " << j;
                    }
                }
            }
        }
    }
    std::uint32_t texels = 0, skipped = 0;
    for (std::uint32_t face = 0; face < 6; ++face) {
        const std::optional<VkRect2D> rect = gpu::ShadowCubePass::frontTexels(face, glm::vec3(0, -1, 0), n);
        skipped += rect ? 0u : 1u;
        texels += rect ? rect->extent.width * rect->extent.height : 0u;
        EXPECT_EQ(!rect, face == 2u) << face; // +y lies wholly behind a downward emitter
    }
    EXPECT_EQ(skipped, 1u);
    EXPECT_EQ(texels, n * n + 4 * n * (n / 2 + 1));
    for (std::uint32_t face = 0; face < 6; ++face) {
        const std::optional<VkRect2D> whole = gpu::ShadowCubePass::frontTexels(face, glm::vec3(0.0f), n);
        ASSERT_TRUE(whole);
        EXPECT_EQ(whole->extent.width * whole->extent.height, n * n);
    }
}

// Rendered with a front, a cube holds what it holds without one inside each face's rectangle and
// "nothing in the way" (+inf) outside it: a point 0.5 over the analytic floor, facing down.
TEST_F(ShadowCubePassTest, FrontPartsRenderedTheRestNothing) {
    Scene scene = loadScene(test::sourcePath("data/analytic/point-over-plane.toml"));
    gpu::GpuScene gpuScene(ctx(), scene);
    gpu::ShadowCubePass pass(ctx(), gpuScene, kResolution, 2);
    const glm::vec3 point(0.3f, 0.5f, -0.2f);
    const glm::vec3 front(0.0f, -1.0f, 0.0f);
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
        pass.record(cmd, point, 0, 0.0, nullptr);
        pass.record(cmd, point, 1, 0.0, nullptr, front);
    });
    constexpr std::uint32_t kStride = gpu::ShadowCubePass::kBytesPerTexel / sizeof(float);
    std::uint32_t kept = 0, cleared = 0;
    for (std::uint32_t face = 0; face < 6; ++face) {
        const auto read = [&](std::uint32_t cube) {
            std::vector<std::byte> raw = pass.maps().download(ctx(), VK_IMAGE_LAYOUT_GENERAL, 6 * cube + face);
            std::vector<float> texels(raw.size() / sizeof(float));
            std::memcpy(texels.data(), raw.data(), texels.size() * sizeof(float));
            return texels;
        };
        const std::vector<float> all = read(0), part = read(1);
        const std::optional<VkRect2D> rect = gpu::ShadowCubePass::frontTexels(face, front, kResolution);
        for (std::uint32_t j = 0; j < kResolution; ++j) {
            for (std::uint32_t i = 0; i < kResolution; ++i) {
                const std::size_t t = kStride * (j * kResolution + i);
                if (rect && inside(*rect, i, j)) {
                    EXPECT_EQ(part[t], all[t]) << face << " " << i << " " << j;
                    ++kept;
                } else {
                    EXPECT_TRUE(std::isinf(part[t])) << face << " " << i << " " << j << ": " << part[t];
                    ++cleared;
                }
            }
        }
    }
    // The test can fail: the floor seen by the side faces' lower halves is kept, their upper halves
    // and the upward face are cleared.
    EXPECT_EQ(cleared, kResolution * kResolution + 4 * kResolution * (kResolution / 2 - 1));
    EXPECT_GT(kept, 0u);
}
