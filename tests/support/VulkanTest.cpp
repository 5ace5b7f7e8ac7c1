#include "support/VulkanTest.h"

#include <cstdlib>
#include <memory>

namespace bl::test {

vk::Context& sharedContext() {
    static std::unique_ptr<vk::Context> ctx = [] {
        const char* device = std::getenv("BL_TEST_DEVICE");
        return std::make_unique<vk::Context>(vk::ContextOptions{device ? device : "", true});
    }();
    return *ctx;
}

void VulkanTest::SetUp() { mErrorsBefore = sharedContext().validationErrorCount(); }

void VulkanTest::TearDown() {
    std::vector<std::string> errors = sharedContext().validationErrors();
    for (std::size_t i = mErrorsBefore; i < errors.size(); ++i) {
        ADD_FAILURE() << "Vulkan validation error: " << errors[i];
    }
}

} // namespace bl::test
