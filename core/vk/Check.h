// BL_VK_CHECK(expr): every VkResult is checked, in every build type. A failure throws bl::Error with
// the expression, file, line and the result's name.
#pragma once

#include <vulkan/vulkan.h>

namespace bl::vk {

const char* resultName(VkResult result);
[[noreturn]] void throwVkError(VkResult result, const char* expression, const char* file, int line);

} // namespace bl::vk

#define BL_VK_CHECK(expr)                                                                          \
    do {                                                                                           \
        VkResult blVkResult_ = (expr);                                                             \
        if (blVkResult_ != VK_SUCCESS) {                                                           \
            ::bl::vk::throwVkError(blVkResult_, #expr, __FILE__, __LINE__);                        \
        }                                                                                          \
    } while (0)
