// The directional depth map: several records in one command buffer, each with its own frame
// (defect 6 of issue 10: a host-written uniform made every record see the last frame).
#include "bundle/BundleFrame.h"
#include "bundle/DepthMapPass.h"
#include "core/gpu/ImageSnapshot.h"
#include "reference/EmbreeScene.h"
#include "scene/SceneLoader.h"
#include "support/AnalyticScenes.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"

#include <cmath>

using namespace bl;

namespace {

constexpr std::uint32_t kResolution = 32; // bundle pixels per side

class DepthMapPassTest : public test::VulkanTest {};

// ao-blocks, its map, and the frame straight above it.
struct AoBlocksMap {
    explicit AoBlocksMap(const vk::Context& ctx)
        : scene(loadScene(test::sourcePath("data/analytic/ao-blocks.toml"))), gpuScene(ctx, scene),
          pass(ctx, gpuScene, kResolution),
          above(bundleFrameForSphere(glm::vec3(0.0f, 1.0f, 0.0f), 0.0f, scene.bounds().center(), scene.bounds().radius(),
                                     kResolution)) {}
    Scene scene;
    gpu::GpuScene gpuScene;
    DepthMapPass pass;
    shader::BundleFrame above;
};

// The map's texels: depth, then the normal of the surface's facet (-inf and 0 where empty).
std::vector<glm::vec4> texels(const vk::Context& ctx, const vk::GpuImage& image) {
    std::vector<std::byte> raw = image.download(ctx, VK_IMAGE_LAYOUT_GENERAL);
    const auto* first = reinterpret_cast<const glm::vec4*>(raw.data());
    return {first, first + std::size_t(kResolution) * kResolution};
}

std::vector<float> depths(const vk::Context& ctx, const vk::GpuImage& image) {
    std::vector<float> out;
    for (const glm::vec4& t : texels(ctx, image)) out.push_back(t.x);
    return out;
}

std::size_t differing(const std::vector<float>& a, const std::vector<float>& b) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.size(); ++i) n += a[i] != b[i] ? 1 : 0;
    return n;
}

} // namespace

TEST_F(DepthMapPassTest, TwoRecordsInOneCommandBufferSeeTheirOwnFrames) {
    AoBlocksMap blocks(ctx());
    DepthMapPass& pass = blocks.pass;
    const shader::BundleFrame& above = blocks.above;
    const Bounds bounds = blocks.scene.bounds();
    const shader::BundleFrame slanted = bundleFrameForSphere(glm::normalize(glm::vec3(1.0f, 0.5f, 0.3f)), 0.0f,
                                                             bounds.center(), bounds.radius(), kResolution);

    ctx().submitAndWait([&](VkCommandBuffer cmd) { pass.record(cmd, above, 0.0, nullptr); });
    const std::vector<float> aboveAlone = depths(ctx(), pass.map());
    ctx().submitAndWait([&](VkCommandBuffer cmd) { pass.record(cmd, slanted, 0.0, nullptr); });
    const std::vector<float> slantedAlone = depths(ctx(), pass.map());
    ASSERT_GT(differing(aboveAlone, slantedAlone), kResolution * kResolution / 4)
        << "the two directions must give different maps for this test to mean anything";

    vk::GpuImage snapshot = test::makeSnapshotImage(ctx(), pass.map());
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
        vk::transitionImage(cmd, snapshot.get(), vk::ImageTransition{});
        pass.record(cmd, above, 0.0, nullptr);
        test::recordSnapshot(cmd, pass.map(), snapshot);
        pass.record(cmd, slanted, 0.0, nullptr);
    });
    EXPECT_EQ(differing(depths(ctx(), snapshot), aboveAlone), 0u)
        << "texels of the first record that saw another frame than its own";
    EXPECT_EQ(differing(depths(ctx(), pass.map()), slantedAlone), 0u);
}

// The map carries the surface's normal beside its depth (the visibility test's creases need it):
// from straight above, ao-blocks shows only the floor and the blocks' tops, all horizontal.
TEST_F(DepthMapPassTest, MapCarriesTheNormalOfTheSurfaceNearestTheLight) {
    AoBlocksMap blocks(ctx());
    ctx().submitAndWait([&](VkCommandBuffer cmd) { blocks.pass.record(cmd, blocks.above, 0.0, nullptr); });
    std::size_t covered = 0, horizontal = 0;
    for (const glm::vec4& t : texels(ctx(), blocks.pass.map())) {
        if (!std::isfinite(t.x)) continue;
        ++covered;
        horizontal += std::abs(std::abs(t.z) - 1.0f) < 1e-5f ? 1 : 0;
    }
    EXPECT_GT(covered, std::size_t(kResolution) * kResolution / 4);
    EXPECT_EQ(horizontal, covered) << "texels whose normal is not the floor's or a top's";
}

// The normal is the facet's (its geometric normal), not the interpolated shading normal: the
// visibility test places the stored surface on that plane (bundle/DepthMapVisibility.glsl). On the
// smooth bowl of AnalyticScenes.h (shading normals up to 0.118 rad off their facets), seen along a
// slanted direction, each texel's normal against the facet an Embree ray down its centre meets, at
// the scene's scale and at a nanometre's (where the position derivatives the shader takes are
// ~6e-11 a pixel, their cross product's square under float's smallest normal): within 0.01 rad
// everywhere but where the centre ray meets an edge.
TEST_F(DepthMapPassTest, MapCarriesTheFacetPlaneNotTheShadingNormal) {
    for (float scale : {1.0f, 1e-9f}) {
        SCOPED_TRACE(scale);
        Scene s = test::bowlUnderSky(12, 32, 16);
        for (glm::vec3& p : s.meshes[0].positions) p *= scale;
        const gpu::GpuScene gpuScene(ctx(), s);
        DepthMapPass pass(ctx(), gpuScene, kResolution);
        const glm::vec3 omega = glm::normalize(glm::vec3(0.4f, 1.0f, 0.3f));
        const Bounds bounds = s.bounds();
        const shader::BundleFrame frame =
            bundleFrameForSphere(omega, 0.3f, bounds.center(), bounds.radius(), kResolution);
        ctx().submitAndWait([&](VkCommandBuffer cmd) { pass.record(cmd, frame, 0.0, nullptr); });
        const EmbreeScene rt(s, 0.0);
        const std::vector<glm::vec4> map = texels(ctx(), pass.map());
        std::size_t covered = 0, facet = 0;
        for (std::uint32_t y = 0; y < kResolution; ++y) {
            for (std::uint32_t x = 0; x < kResolution; ++x) {
                const glm::vec4 t = map[y * kResolution + x];
                if (!std::isfinite(t.x)) continue;
                const glm::vec3 ray = frame.origin + (float(x) + 0.5f) * frame.pixelSize * frame.axisX +
                                      (float(y) + 0.5f) * frame.pixelSize * frame.axisY;
                SurfaceHit hit;
                const float far = frame.depthFar + 2.0f * bounds.radius();
                if (!rt.intersect(ray + far * omega, -omega, 2.0f * far, hit)) continue;
                ++covered;
                facet += std::abs(glm::dot(glm::vec3(t.y, t.z, t.w), hit.geometricNormal)) > std::cos(0.01f) ? 1 : 0;
            }
        }
        EXPECT_GT(covered, std::size_t(kResolution) * kResolution / 4);
        EXPECT_GE(double(facet), 0.97 * double(covered)) << facet << " of " << covered << " texels hold their facet's plane";
    }
}
