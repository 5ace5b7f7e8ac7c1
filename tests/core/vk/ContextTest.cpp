#include "base/Error.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"
#include "vk/Buffer.h"
#include "vk/Check.h"
#include "vk/Descriptors.h"
#include "vk/GpuImage.h"
#include "vk/GpuTimer.h"
#include "vk/Pipeline.h"

#include <cstring>
#include <glm/glm.hpp>
#include <numeric>
#include <tests/smoke.comp.spv.h>

using namespace bl;
using bl::test::errorOf;

class VkCore : public bl::test::VulkanTest {};

TEST_F(VkCore, DeviceIsDescribed) {
    const vk::DeviceInfo& info = ctx().info();
    EXPECT_FALSE(info.name.empty());
    EXPECT_FALSE(info.driverName.empty());
    EXPECT_EQ(info.apiVersion.rfind("1.3", 0), 0u) << info.apiVersion;
    EXPECT_GT(ctx().limits().timestampPeriod, 0.0f);
}

TEST_F(VkCore, AllocationAndBufferLimitsComeFromTheDevice) {
    // Vulkan guarantees at least 2^30 bytes for both (the spec's required limits table).
    constexpr VkDeviceSize kSpecMinimumBytes = VkDeviceSize(1) << 30;
    EXPECT_GE(ctx().maxAllocationBytes(), kSpecMinimumBytes);
    EXPECT_GE(ctx().maxBufferBytes(), kSpecMinimumBytes);
}

// A wait that gives up (here: a zero timeout on a submission that is certainly still running) must
// throw without freeing the command buffer or fence the queue still holds; the validation layers
// (checked by the fixture) report any such free as an error.
TEST_F(VkCore, SubmissionThatTimesOutKeepsWhatTheQueueStillUses) {
    // Enough fill work that the submission is still running when the zero-timeout wait looks.
    constexpr VkDeviceSize kFillBytes = VkDeviceSize(64) << 20;
    constexpr int kFills = 32;
    vk::Buffer target(ctx(), kFillBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Device);
    const std::string e = errorOf([&] {
        ctx().submitAndWait(
            [&](VkCommandBuffer cmd) {
                for (int i = 0; i < kFills; ++i) {
                    vkCmdFillBuffer(cmd, target.get(), 0, VK_WHOLE_SIZE, std::uint32_t(i));
                }
            },
            0);
    });
    if (e.empty()) {
        GTEST_SKIP() << "the device finished the fills before a zero-timeout wait looked";
    }
    EXPECT_NE(e.find("VK_TIMEOUT"), std::string::npos) << e;
    // The buffer outlives the submission: the test owns it, so it waits before destroying it.
    BL_VK_CHECK(vkDeviceWaitIdle(ctx().device()));
    // The context stays usable, and reclaims the abandoned submission once it has finished.
    std::uint32_t first = 0;
    ctx().submitAndWait([&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, target.get(), 0, 4, 7u); });
    target.download(ctx(), &first, sizeof(first));
    EXPECT_EQ(first, 7u);
}

TEST_F(VkCore, BufferBeyondTheDeviceLimitIsAClearError) {
    const VkDeviceSize tooLarge = std::min(ctx().maxBufferBytes(), ctx().maxAllocationBytes()) + 1;
    std::string e = errorOf(
        [&] { vk::Buffer(ctx(), tooLarge, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Device); });
    EXPECT_NE(e.find("exceeds the largest buffer of '" + ctx().info().name + "'"), std::string::npos) << e;
}

TEST_F(VkCore, BufferRoundTrip) {
    std::vector<float> data(1000);
    std::iota(data.begin(), data.end(), 0.5f);
    vk::Buffer b = vk::makeBuffer<float>(ctx(), data, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    std::vector<float> back(data.size());
    b.download(ctx(), back.data(), back.size() * sizeof(float));
    EXPECT_EQ(back, data);
    EXPECT_NE(errorOf([&] { b.upload(ctx(), data.data(), 8000, 8); }).find("8008 bytes into a buffer of 4000"),
              std::string::npos);
}

// A pool counts what it hands out: a set it has no room for is refused with the counts named on
// every device (lavapipe itself would allocate past the pool's sizes).
TEST_F(VkCore, DescriptorPoolRefusesSetsItHasNoRoomFor) {
    VkDevice d = ctx().device();
    const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    vk::DescriptorSetLayout two = vk::makeDescriptorSetLayout(
        d, {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cs}, {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cs}});
    vk::DescriptorSetLayout one = vk::makeDescriptorSetLayout(d, {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cs}});
    vk::DescriptorPool pool(d, 2, 2);
    pool.allocate(two.get());
    EXPECT_NE(errorOf([&] { pool.allocate(one.get()); }).find("needs 1 descriptor(s) of type 3, the pool has 0 left of 2"),
              std::string::npos);
    vk::DescriptorPool sets(d, 1, 4);
    sets.allocate(one.get());
    EXPECT_NE(errorOf([&] { sets.allocate(one.get()); }).find("all 1 sets handed out"), std::string::npos);
}

TEST_F(VkCore, ComputeDispatchAndTimer) {
    const std::uint32_t n = 4097;
    std::vector<float> input(n);
    std::iota(input.begin(), input.end(), 0.0f);
    vk::Buffer in = vk::makeBuffer<float>(ctx(), input, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    vk::Buffer out(ctx(), n * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Device);
    VkDevice d = ctx().device();
    vk::DescriptorSetLayout layout = vk::makeDescriptorSetLayout(
        d, {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
            {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}});
    vk::DescriptorPool pool(d, 1, 2);
    VkDescriptorSet set = pool.allocate(layout.get());
    vk::DescriptorWriter()
        .buffer(0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, in.get())
        .buffer(1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, out.get())
        .update(d, set);
    VkDescriptorSetLayout layouts[] = {layout.get()};
    vk::PipelineLayout pipelineLayout = vk::makePipelineLayout(d, layouts, sizeof(std::uint32_t), VK_SHADER_STAGE_COMPUTE_BIT);
    vk::Pipeline pipeline = vk::makeComputePipeline(d, kSpv_tests_smoke_comp, pipelineLayout.get());
    vk::GpuTimer timer(ctx());
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
        timer.begin(cmd);
        std::uint32_t scope = timer.start(cmd, "smoke");
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.get());
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout.get(), 0, 1, &set, 0, nullptr);
        vkCmdPushConstants(cmd, pipelineLayout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(n), &n);
        vkCmdDispatch(cmd, vk::groupCount(n, 64), 1, 1);
        timer.stop(cmd, scope);
    });
    timer.collect();
    std::vector<float> result(n);
    out.download(ctx(), result.data(), n * sizeof(float));
    for (std::uint32_t i = 0; i < n; ++i) {
        ASSERT_EQ(result[i], 2.0f * input[i] + 1.0f) << i;
    }
    ASSERT_EQ(timer.totals().size(), 1u);
    EXPECT_EQ(timer.totals()[0].name, "smoke");
    EXPECT_EQ(timer.totals()[0].count, 1u);
    EXPECT_GE(timer.totals()[0].totalMs, 0.0);
}

TEST_F(VkCore, ImageUploadDownload) {
    vk::GpuImage img(ctx(), {3, 2, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT});
    std::vector<glm::vec4> texels(6);
    for (int i = 0; i < 6; ++i) texels[i] = glm::vec4(i, -i, 0.5f * i, 1);
    img.upload(ctx(), texels.data(), texels.size() * sizeof(glm::vec4));
    std::vector<std::byte> back = img.download(ctx(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    ASSERT_EQ(back.size(), texels.size() * sizeof(glm::vec4));
    EXPECT_EQ(std::memcmp(back.data(), texels.data(), back.size()), 0);
    EXPECT_NE(errorOf([&] { vk::GpuImage(ctx(), {0, 2, 1}); }).find("outside the device limits"), std::string::npos);
}

TEST(VkCheck, ThrowsWithExpressionFileLineAndName) {
    std::string e = errorOf([] { BL_VK_CHECK(VK_ERROR_OUT_OF_DEVICE_MEMORY); });
    EXPECT_NE(e.find("ContextTest.cpp:"), std::string::npos) << e;
    EXPECT_NE(e.find("VK_ERROR_OUT_OF_DEVICE_MEMORY failed with VK_ERROR_OUT_OF_DEVICE_MEMORY"), std::string::npos) << e;
}

TEST(VkContext, DeviceSelection) {
    std::vector<vk::DeviceInfo> devices = vk::Context::listDevices();
    ASSERT_FALSE(devices.empty());
    vk::Context byName(vk::ContextOptions{devices[0].name.substr(0, 4), true});
    EXPECT_EQ(byName.info().name, devices[0].name);
    std::string e = errorOf([] { vk::Context c(vk::ContextOptions{"99", false}); });
    EXPECT_NE(e.find("--device 99: no such device"), std::string::npos) << e;
    e = errorOf([] { vk::Context c(vk::ContextOptions{"no-such-gpu-xyz", false}); });
    EXPECT_NE(e.find("no device name contains it"), std::string::npos) << e;
    EXPECT_EQ(byName.validationErrorCount(), 0u);
}
