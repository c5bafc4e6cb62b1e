// Error checking for Vulkan calls: VK_CHECK(vkCall(...)) throws RuntimeError naming the call, the
// VkResult and the place, so that no failure goes unnoticed.
#pragma once

#include <vulkan/vulkan.h>

namespace photon::vk {

const char* resultName(VkResult result);

// Throws RuntimeError if result is an error; returns it otherwise (VK_SUCCESS, VK_INCOMPLETE, ...).
VkResult check(VkResult result, const char* call, const char* file, int line);

}  // namespace photon::vk

#define VK_CHECK(call) ::photon::vk::check((call), #call, __FILE__, __LINE__)
