// Instance, validation messenger, device selection and the queue. The boring part of Vulkan,
// kept in one place.
#include "context.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "check.h"
#include "core/system/error.h"
#include "shared/bindings.h"

namespace photon::vk {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr std::uint32_t kApiVersion = VK_API_VERSION_1_3;

bool envFlag(const char* name) {
    const char* value = std::getenv(name);
    return value != nullptr && std::strcmp(value, "") != 0 && std::strcmp(value, "0") != 0;
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

std::vector<VkExtensionProperties> deviceExtensionsOf(VkPhysicalDevice device) {
    std::uint32_t count = 0;
    VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr));
    std::vector<VkExtensionProperties> extensions(count);
    VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data()));
    return extensions;
}

bool hasExtension(const std::vector<VkExtensionProperties>& available, const char* name) {
    return std::any_of(available.begin(), available.end(),
                       [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

bool hasLayer(const char* name) {
    std::uint32_t count = 0;
    VK_CHECK(vkEnumerateInstanceLayerProperties(&count, nullptr));
    std::vector<VkLayerProperties> layers(count);
    VK_CHECK(vkEnumerateInstanceLayerProperties(&count, layers.data()));
    return std::any_of(layers.begin(), layers.end(),
                       [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

// Lower is better: discrete GPUs first, the CPU (lavapipe) last.
int typeRank(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
        default: return 4;
    }
}

// Why the device cannot run the backend, or "" if it can. Fills the queue family.
std::string checkDevice(DeviceCandidate& c, VkSurfaceKHR surface, const std::vector<const char*>& deviceExtensions,
                        bool graphics) {
    if (c.properties.apiVersion < kApiVersion) {
        return "Vulkan 1.3 is required";
    }
    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &subgroup};
    vkGetPhysicalDeviceProperties2(c.physicalDevice, &properties);
    if (!(subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) ||
        !(subgroup.supportedOperations & VK_SUBGROUP_FEATURE_ARITHMETIC_BIT)) {
        return "no subgroup arithmetic in compute shaders";
    }
    // Every stage binds the whole buffer list of shared/bindings.h in one set.
    const VkPhysicalDeviceLimits& limits = c.properties.limits;
    std::uint32_t storageBuffers = std::min(limits.maxPerStageDescriptorStorageBuffers, limits.maxDescriptorSetStorageBuffers);
    if (storageBuffers < kBufferCount) {
        return "binds at most " + std::to_string(storageBuffers) + " storage buffers to a stage, and Photon's stages bind " +
               std::to_string(kBufferCount);
    }
    VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &features13};
    vkGetPhysicalDeviceFeatures2(c.physicalDevice, &features);
    if (!features13.computeFullSubgroups) {
        return "no computeFullSubgroups";
    }
    std::vector<VkExtensionProperties> extensions = deviceExtensionsOf(c.physicalDevice);
    std::uint32_t count = 0;
    for (const char* name : deviceExtensions) {
        if (!hasExtension(extensions, name)) {
            return std::string("no ") + name;
        }
    }
    vkGetPhysicalDeviceQueueFamilyProperties(c.physicalDevice, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(c.physicalDevice, &count, families.data());
    int best = -1;
    for (std::uint32_t f = 0; f < count; ++f) {
        VkBool32 present = VK_TRUE;
        if (surface != VK_NULL_HANDLE) {
            VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(c.physicalDevice, f, surface, &present));
        }
        VkQueueFlags needed = VK_QUEUE_COMPUTE_BIT | (graphics ? VK_QUEUE_GRAPHICS_BIT : 0);
        if ((families[f].queueFlags & needed) != needed || !present) {
            continue;
        }
        // Prefer a family that can time the stages.
        if (best < 0 || (families[best].timestampValidBits == 0 && families[f].timestampValidBits > 0)) {
            best = int(f);
        }
    }
    if (best < 0) {
        return std::string("no queue family with compute") + (graphics ? ", graphics" : "") +
               (surface != VK_NULL_HANDLE ? " and present" : "");
    }
    c.queueFamily = std::uint32_t(best);
    return "";
}

std::string describe(const std::vector<DeviceCandidate>& candidates) {
    std::string s;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        // On the one line of the message: printable() would show a newline as \x0a.
        s += (i == 0 ? " " : "; ") + std::to_string(i) + ": " + candidates[i].properties.deviceName;
        if (!candidates[i].unsuitable.empty()) {
            s += " (unsuitable: " + candidates[i].unsuitable + ")";
        }
    }
    return s.empty() ? " none" : s;
}

}  // namespace

std::vector<DeviceCandidate> listDevices(VkInstance instance, VkSurfaceKHR surface,
                                         const std::vector<const char*>& deviceExtensions, bool graphics) {
    std::uint32_t count = 0;
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
    std::vector<DeviceCandidate> candidates(count);
    for (std::uint32_t i = 0; i < count; ++i) {
        candidates[i].physicalDevice = devices[i];
        vkGetPhysicalDeviceProperties(devices[i], &candidates[i].properties);
        candidates[i].unsuitable = checkDevice(candidates[i], surface, deviceExtensions, graphics);
    }
    return candidates;
}

const DeviceCandidate& pickDevice(const std::vector<DeviceCandidate>& candidates, const std::string& request) {
    const DeviceCandidate* pick = nullptr;
    bool byIndex = !request.empty() && std::all_of(request.begin(), request.end(), [](unsigned char c) { return std::isdigit(c); });
    if (byIndex) {
        if (request.size() < 6 && std::stoul(request) < candidates.size()) {
            pick = &candidates[std::stoul(request)];
        }
    } else {
        for (const DeviceCandidate& c : candidates) {
            bool named = lower(c.properties.deviceName).find(lower(request)) != std::string::npos;
            bool better = pick == nullptr || (pick->unsuitable.empty() == c.unsuitable.empty()
                                                  ? typeRank(c.properties.deviceType) < typeRank(pick->properties.deviceType)
                                                  : c.unsuitable.empty());
            if (named && better) {
                pick = &c;
            }
        }
    }
    if (pick == nullptr || !pick->unsuitable.empty()) {
        std::string what = request.empty() ? "no Vulkan device can run Photon"
                                           : "no usable Vulkan device matches '" + request + "'";
        throw RuntimeError(what + "; devices:" + describe(candidates));
    }
    return *pick;
}

VkInstance createBareInstance() {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "photon";
    app.apiVersion = kApiVersion;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    VkInstance instance = VK_NULL_HANDLE;
    VK_CHECK(vkCreateInstance(&info, nullptr, &instance));
    return instance;
}

Context::Context(const ContextOptions& options) {
    bool validation = options.validation || envFlag("PHOTON_VULKAN_VALIDATION");
    try {
        createInstance(options, validation);
        if (options.createSurface) {
            surface = options.createSurface(instance);
        }
        createDevice(options);
    } catch (...) {
        destroy();
        throw;
    }
}

Context::~Context() { destroy(); }

void Context::destroy() {
    if (device != VK_NULL_HANDLE) {
        vkDeviceWaitIdle(device);
        vkDestroyDevice(device, nullptr);
        device = VK_NULL_HANDLE;
    }
    if (surface != VK_NULL_HANDLE) {
        vkDestroySurfaceKHR(instance, surface, nullptr);
        surface = VK_NULL_HANDLE;
    }
    if (messenger != VK_NULL_HANDLE) {
        auto destroyMessenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
        destroyMessenger(instance, messenger, nullptr);
        messenger = VK_NULL_HANDLE;
    }
    if (instance != VK_NULL_HANDLE) {
        vkDestroyInstance(instance, nullptr);
        instance = VK_NULL_HANDLE;
    }
}

void Context::createInstance(const ContextOptions& options, bool validation) {
    std::uint32_t loaderVersion = 0;
    VK_CHECK(vkEnumerateInstanceVersion(&loaderVersion));
    if (loaderVersion < kApiVersion) {
        throw RuntimeError("the Vulkan loader supports Vulkan " + std::to_string(VK_API_VERSION_MAJOR(loaderVersion)) +
                           "." + std::to_string(VK_API_VERSION_MINOR(loaderVersion)) + "; Photon needs 1.3");
    }
    std::vector<const char*> layers;
    std::vector<const char*> extensions = options.instanceExtensions;
    if (validation) {
        if (!hasLayer(kValidationLayer)) {
            throw RuntimeError(std::string("Vulkan validation was asked for, but ") + kValidationLayer +
                               " is not installed (Debian: vulkan-validationlayers)");
        }
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    }

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "photon";
    app.pEngineName = "photon";
    app.apiVersion = kApiVersion;

    // Messages from instance creation itself go to the same callback.
    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messengerInfo.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messengerInfo.pfnUserCallback = &Context::onMessage;
    messengerInfo.pUserData = this;
    VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT, &messengerInfo};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;

    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pNext = validation ? &features : nullptr;
    info.pApplicationInfo = &app;
    info.enabledLayerCount = std::uint32_t(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = std::uint32_t(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VkResult result = vkCreateInstance(&info, nullptr, &instance);
    if (result == VK_ERROR_INCOMPATIBLE_DRIVER) {
        throw RuntimeError("no Vulkan driver is installed (vkCreateInstance: VK_ERROR_INCOMPATIBLE_DRIVER)");
    }
    VK_CHECK(result);
    if (validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
        VK_CHECK(create(instance, &messengerInfo, nullptr, &messenger));
    }
}

void Context::createDevice(const ContextOptions& options) {
    std::vector<DeviceCandidate> candidates = listDevices(instance, surface, options.deviceExtensions, options.graphics);
    const DeviceCandidate& chosen = pickDevice(candidates, options.device);
    physicalDevice = chosen.physicalDevice;
    queueFamily = chosen.queueFamily;

    VkPhysicalDeviceVulkan13Properties properties13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_PROPERTIES};
    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES, &properties13};
    VkPhysicalDeviceProperties2 properties2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &subgroup};
    vkGetPhysicalDeviceProperties2(physicalDevice, &properties2);
    properties = properties2.properties;
    subgroupSize = subgroup.subgroupSize;
    maxSubgroupSize = std::max(properties13.maxSubgroupSize, subgroupSize);
    vkGetPhysicalDeviceMemoryProperties(physicalDevice, &memoryProperties);

    std::uint32_t familyCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &familyCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(familyCount);
    vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &familyCount, families.data());
    timestampValidBits = families[queueFamily].timestampValidBits;

    float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = queueFamily;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;

    // The scan's subgroups must be full (gridScan.comp numbers invocations by subgroup).
    VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    features13.computeFullSubgroups = VK_TRUE;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &features13};

    std::vector<const char*> extensions = options.deviceExtensions;
    VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR executables{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR};
    if (envFlag("PHOTON_VULKAN_PIPELINE_STATISTICS")) {
        if (hasExtension(deviceExtensionsOf(physicalDevice), VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME)) {
            extensions.push_back(VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
            executables.pipelineExecutableInfo = VK_TRUE;
            features13.pNext = &executables;
            pipelineStatistics = true;
        } else {
            std::fprintf(stderr, "PHOTON_VULKAN_PIPELINE_STATISTICS: %s has no %s\n", properties.deviceName,
                         VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
        }
    }

    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queueInfo;
    info.enabledExtensionCount = std::uint32_t(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VK_CHECK(vkCreateDevice(physicalDevice, &info, nullptr, &device));
    vkGetDeviceQueue(device, queueFamily, 0, &queue);
}

void Context::checkValidation(const char* where) {
    std::vector<std::string> messages;
    {
        std::lock_guard<std::mutex> lock(messagesMutex_);
        messages.swap(messages_);
    }
    if (messages.empty()) {
        return;
    }
    std::string text = std::to_string(messages.size()) + " Vulkan validation message(s) during " + where + ":";
    for (const std::string& m : messages) {
        text += "\n  " + m;
    }
    throw RuntimeError(text);
}

VKAPI_ATTR VkBool32 VKAPI_CALL Context::onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                  VkDebugUtilsMessageTypeFlagsEXT,
                                                  const VkDebugUtilsMessengerCallbackDataEXT* data, void* self) {
    // The loader saying that VK_INSTANCE_LAYERS added the validation layer (as the viewer's test
    // asks it to) is a notice, not a finding.
    if (data->pMessage && std::strstr(data->pMessage, "env var 'VK_INSTANCE_LAYERS' defined and adding layers")) {
        return VK_FALSE;
    }
    const char* level = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning";
    std::string message = std::string("[") + level + "] " + (data->pMessageIdName ? data->pMessageIdName : "") +
                          ": " + (data->pMessage ? data->pMessage : "");
    std::fprintf(stderr, "vulkan validation %s\n", message.c_str());
    auto* context = static_cast<Context*>(self);
    std::lock_guard<std::mutex> lock(context->messagesMutex_);
    context->messages_.push_back(message);
    return VK_FALSE;
}

}  // namespace photon::vk
