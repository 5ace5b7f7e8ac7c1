#include "vk/Check.h"

#include "base/Error.h"

#include <string>

namespace bl::vk {

const char* resultName(VkResult r) {
    switch (r) {
#define BL_CASE(x) case x: return #x
        BL_CASE(VK_SUCCESS);
        BL_CASE(VK_NOT_READY);
        BL_CASE(VK_TIMEOUT);
        BL_CASE(VK_EVENT_SET);
        BL_CASE(VK_EVENT_RESET);
        BL_CASE(VK_INCOMPLETE);
        BL_CASE(VK_ERROR_OUT_OF_HOST_MEMORY);
        BL_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY);
        BL_CASE(VK_ERROR_INITIALIZATION_FAILED);
        BL_CASE(VK_ERROR_DEVICE_LOST);
        BL_CASE(VK_ERROR_MEMORY_MAP_FAILED);
        BL_CASE(VK_ERROR_LAYER_NOT_PRESENT);
        BL_CASE(VK_ERROR_EXTENSION_NOT_PRESENT);
        BL_CASE(VK_ERROR_FEATURE_NOT_PRESENT);
        BL_CASE(VK_ERROR_INCOMPATIBLE_DRIVER);
        BL_CASE(VK_ERROR_TOO_MANY_OBJECTS);
        BL_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED);
        BL_CASE(VK_ERROR_FRAGMENTED_POOL);
        BL_CASE(VK_ERROR_UNKNOWN);
        BL_CASE(VK_ERROR_OUT_OF_POOL_MEMORY);
        BL_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE);
        BL_CASE(VK_ERROR_FRAGMENTATION);
        BL_CASE(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS);
        BL_CASE(VK_PIPELINE_COMPILE_REQUIRED);
#undef BL_CASE
    default:
        return "VK_RESULT_UNKNOWN";
    }
}

void throwVkError(VkResult result, const char* expression, const char* file, int line) {
    throw Error(std::string(file) + ":" + std::to_string(line) + ": " + expression + " failed with " +
                resultName(result) + " (" + std::to_string(static_cast<int>(result)) + ")");
}

} // namespace bl::vk
