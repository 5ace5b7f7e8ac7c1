// The G-buffer pass: several records in one command buffer, each with its own camera (defect 6 of
// issue 10: a host-written uniform made every record see the last camera).
#include "core/gpu/ImageSnapshot.h"
#include "gpu/GBufferPass.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"

#include <shared/Bindings.h>

using namespace bl;

namespace {

constexpr std::uint32_t kSide = 32; // pixels: enough for the two views to differ everywhere

class GBufferPassTest : public test::VulkanTest {};

std::vector<glm::vec4> positions(const vk::Context& ctx, const vk::GpuImage& image) {
    std::vector<std::byte> raw = image.download(ctx, VK_IMAGE_LAYOUT_GENERAL);
    const auto* texels = reinterpret_cast<const glm::vec4*>(raw.data());
    return {texels, texels + std::size_t(kSide) * kSide};
}

std::size_t differingPixels(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.size(); ++i) n += a[i] != b[i] ? 1 : 0;
    return n;
}

} // namespace

TEST_F(GBufferPassTest, TwoRecordsInOneCommandBufferSeeTheirOwnCameras) {
    Scene scene = loadScene(test::sourcePath("data/cornell-box/cornell.toml"));
    scene.camera.resolution = {int(kSide), int(kSide)};
    gpu::GpuScene gpuScene(ctx(), scene);
    gpu::GBufferPass pass(ctx(), gpuScene, kSide, kSide);
    const shader::GpuCamera front = makeGpuCamera(scene.camera, 0.0, gpuScene.cameraNear());
    Camera turned = scene.camera;
    turned.pose.target = turned.pose.position + glm::vec3(1.0f, 0.0f, 1.0f) * 800.0f; // looks at the red wall
    const shader::GpuCamera side = makeGpuCamera(turned, 0.0, gpuScene.cameraNear());

    // Each camera alone, one submission each: what each record must reproduce.
    ctx().submitAndWait([&](VkCommandBuffer cmd) { pass.record(cmd, front, glm::vec2(0.0f), 0.0, nullptr); });
    const std::vector<glm::vec4> frontAlone = positions(ctx(), pass.attachment(shader::kGBufferPosition));
    ctx().submitAndWait([&](VkCommandBuffer cmd) { pass.record(cmd, side, glm::vec2(0.0f), 0.0, nullptr); });
    const std::vector<glm::vec4> sideAlone = positions(ctx(), pass.attachment(shader::kGBufferPosition));
    ASSERT_GT(differingPixels(frontAlone, sideAlone), kSide * kSide / 2) << "the two cameras must see different points for this test to mean anything";

    // Both in one command buffer: the first record's output is copied away before the second.
    const vk::GpuImage& target = pass.attachment(shader::kGBufferPosition);
    vk::GpuImage snapshot = test::makeSnapshotImage(ctx(), target);
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
        vk::transitionImage(cmd, snapshot.get(), vk::ImageTransition{});
        pass.record(cmd, front, glm::vec2(0.0f), 0.0, nullptr);
        test::recordSnapshot(cmd, target, snapshot);
        pass.record(cmd, side, glm::vec2(0.0f), 0.0, nullptr);
    });
    EXPECT_EQ(differingPixels(positions(ctx(), snapshot), frontAlone), 0u)
        << "pixels of the first record that saw another camera than its own";
    EXPECT_EQ(differingPixels(positions(ctx(), pass.attachment(shader::kGBufferPosition)), sideAlone), 0u);
}
