// vk::BoundSet: the bindings listed once make a set a shader reads and writes through, rebind()
// really points a binding elsewhere, and a list that cannot be a set is refused by name.
#include "support/TestFiles.h"
#include "support/VulkanTest.h"
#include "vk/BoundSet.h"
#include "vk/Buffer.h"
#include "vk/ComputePass.h"

#include <numeric>
#include <tests/smoke.comp.spv.h>

using namespace bl;
using bl::test::errorOf;

class BoundSetTest : public bl::test::VulkanTest {
protected:
    // smoke.comp: out[i] = 2 in[i] + 1 for i < n (binding 0 in, binding 1 out, push n).
    std::vector<float> run(const vk::BoundSet& set, const vk::Buffer& out, std::uint32_t n) {
        vk::ComputePass<std::uint32_t> pass(ctx().device(), kSpv_tests_smoke_comp, {set.layout()});
        ctx().submitAndWait([&](VkCommandBuffer cmd) { pass.dispatch(cmd, n, vk::groupCount(n, 64), set.sets()); });
        std::vector<float> result(n);
        out.download(ctx(), result.data(), n * sizeof(float));
        return result;
    }
};

TEST_F(BoundSetTest, ShaderReadsAndWritesThroughTheListedBindingsAndRebind) {
    const std::uint32_t n = 300;
    std::vector<float> input(n);
    std::iota(input.begin(), input.end(), 0.0f);
    vk::Buffer in = vk::makeBuffer<float>(ctx(), input, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    const std::vector<float> zeros(n, 0.0f);
    vk::Buffer first = vk::makeBuffer<float>(ctx(), zeros, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    vk::Buffer second = vk::makeBuffer<float>(ctx(), zeros, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    vk::BoundSet set(ctx().device(), {vk::Bound::storageBuffer(0, in.get()), vk::Bound::storageBuffer(1, first.get())});
    ASSERT_TRUE(set);
    std::vector<float> a = run(set, first, n);
    for (std::uint32_t i = 0; i < n; ++i) ASSERT_EQ(a[i], 2.0f * input[i] + 1.0f) << i;

    // After rebind the shader writes the second buffer and leaves the first as it was.
    set.rebind(1, second.get());
    const std::vector<float> before = a;
    std::vector<float> b = run(set, second, n);
    for (std::uint32_t i = 0; i < n; ++i) ASSERT_EQ(b[i], 2.0f * input[i] + 1.0f) << i;
    std::vector<float> stillFirst(n);
    first.download(ctx(), stillFirst.data(), n * sizeof(float));
    EXPECT_EQ(stillFirst, before);
}

TEST_F(BoundSetTest, RefusesListsThatCannotBeASet) {
    VkDevice d = ctx().device();
    vk::Buffer buffer(ctx(), 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Device);
    EXPECT_NE(errorOf([&] {
                  vk::BoundSet(d, {vk::Bound::storageBuffer(3, buffer.get()), vk::Bound::storageBuffer(3, buffer.get())});
              }).find("binding 3 is listed twice"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { vk::BoundSet(d, {vk::Bound::storageBuffer(2, VK_NULL_HANDLE)}); })
                  .find("binding 2 is given no resource"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { vk::BoundSet(d, {vk::Bound::storageImage(1, VK_NULL_HANDLE)}); })
                  .find("binding 1 is given no resource"),
              std::string::npos);
    vk::BoundSet set(d, {vk::Bound::storageBuffer(0, buffer.get())});
    EXPECT_NE(errorOf([&] { set.rebind(5, buffer.get()); }).find("binding 5 is not one of the set's"), std::string::npos);
    EXPECT_NE(errorOf([&] { set.rebind(0, VkImageView(VK_NULL_HANDLE)); }).find("binding 0 holds a buffer, not an image"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { set.rebind(0, VkBuffer(VK_NULL_HANDLE)); }).find("binding 0 is given no buffer"),
              std::string::npos);
    // A moved-from set holds nothing.
    vk::BoundSet moved = std::move(set);
    EXPECT_TRUE(moved);
    EXPECT_FALSE(set); // what a move leaves behind is the point here
}
