// The base of the classes that own Vulkan objects and destroy them in their destructor (the
// context, the pipelines, the viewer's passes and targets): a copy would destroy them twice, so
// there is none, as with boost::noncopyable. Derive privately: `class Pipelines : NonCopyable {`.
#pragma once

namespace photon::vk {

class NonCopyable {
public:
    NonCopyable(const NonCopyable&) = delete;
    NonCopyable& operator=(const NonCopyable&) = delete;

protected:
    NonCopyable() = default;
    ~NonCopyable() = default;
};

}  // namespace photon::vk
