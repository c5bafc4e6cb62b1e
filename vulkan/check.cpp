// VkResult names and the check behind VK_CHECK.
#include "check.h"

#include <string>

#include "core/system/error.h"

namespace photon::vk {

const char* resultName(VkResult result) {
    switch (result) {
#define PHOTON_RESULT(name) \
    case name:              \
        return #name;
        PHOTON_RESULT(VK_SUCCESS)
        PHOTON_RESULT(VK_NOT_READY)
        PHOTON_RESULT(VK_TIMEOUT)
        PHOTON_RESULT(VK_EVENT_SET)
        PHOTON_RESULT(VK_EVENT_RESET)
        PHOTON_RESULT(VK_INCOMPLETE)
        PHOTON_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
        PHOTON_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        PHOTON_RESULT(VK_ERROR_INITIALIZATION_FAILED)
        PHOTON_RESULT(VK_ERROR_DEVICE_LOST)
        PHOTON_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
        PHOTON_RESULT(VK_ERROR_LAYER_NOT_PRESENT)
        PHOTON_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
        PHOTON_RESULT(VK_ERROR_FEATURE_NOT_PRESENT)
        PHOTON_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
        PHOTON_RESULT(VK_ERROR_TOO_MANY_OBJECTS)
        PHOTON_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
        PHOTON_RESULT(VK_ERROR_FRAGMENTED_POOL)
        PHOTON_RESULT(VK_ERROR_UNKNOWN)
        PHOTON_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY)
        PHOTON_RESULT(VK_ERROR_INVALID_EXTERNAL_HANDLE)
        PHOTON_RESULT(VK_ERROR_FRAGMENTATION)
        PHOTON_RESULT(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
        PHOTON_RESULT(VK_PIPELINE_COMPILE_REQUIRED)
        PHOTON_RESULT(VK_ERROR_SURFACE_LOST_KHR)
        PHOTON_RESULT(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
        PHOTON_RESULT(VK_SUBOPTIMAL_KHR)
        PHOTON_RESULT(VK_ERROR_OUT_OF_DATE_KHR)
        PHOTON_RESULT(VK_ERROR_VALIDATION_FAILED_EXT)
#undef PHOTON_RESULT
        default:
            return "VkResult(?)";
    }
}

VkResult check(VkResult result, const char* call, const char* file, int line) {
    if (result < 0) {
        std::string where = std::string(file);
        where = where.substr(where.find_last_of('/') + 1) + ":" + std::to_string(line);
        throw RuntimeError(std::string(call) + " failed with " + resultName(result) + " (" +
                           std::to_string(int(result)) + ", " + where + ")");
    }
    return result;
}

}  // namespace photon::vk
