// Base fixture of every Vulkan test: one validated context per test binary (lavapipe unless
// BL_TEST_DEVICE names another), and a check after each test that no validation error occurred.
#pragma once

#include "vk/Context.h"

#include <gtest/gtest.h>

namespace bl::test {

vk::Context& sharedContext();

class VulkanTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;
    vk::Context& ctx() { return sharedContext(); }

private:
    std::size_t mErrorsBefore = 0;
};

} // namespace bl::test
