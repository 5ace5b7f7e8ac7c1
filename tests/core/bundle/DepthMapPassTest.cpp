// The directional depth map: several records in one command buffer, each with its own frame
// (defect 6 of issue 10: a host-written uniform made every record see the last frame).
#include "bundle/BundleFrame.h"
#include "bundle/DepthMapPass.h"
#include "core/gpu/ImageSnapshot.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"

using namespace bl;

namespace {

constexpr std::uint32_t kResolution = 32; // bundle pixels per side

class DepthMapPassTest : public test::VulkanTest {};

std::vector<float> depths(const vk::Context& ctx, const vk::GpuImage& image) {
    std::vector<std::byte> raw = image.download(ctx, VK_IMAGE_LAYOUT_GENERAL);
    const auto* texels = reinterpret_cast<const float*>(raw.data());
    return {texels, texels + std::size_t(kResolution) * kResolution};
}

std::size_t differing(const std::vector<float>& a, const std::vector<float>& b) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.size(); ++i) n += a[i] != b[i] ? 1 : 0;
    return n;
}

} // namespace

TEST_F(DepthMapPassTest, TwoRecordsInOneCommandBufferSeeTheirOwnFrames) {
    Scene scene = loadScene(test::sourcePath("data/analytic/ao-blocks.toml"));
    gpu::GpuScene gpuScene(ctx(), scene);
    DepthMapPass pass(ctx(), gpuScene, kResolution);
    const Bounds bounds = scene.bounds();
    const shader::BundleFrame above =
        bundleFrameForSphere(glm::vec3(0.0f, 1.0f, 0.0f), 0.0f, bounds.center(), bounds.radius(), kResolution);
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
