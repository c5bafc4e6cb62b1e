#include "core/frame/fingerprint.h"

#include "core/settings/setting_specs.h"

namespace photon {
namespace {

// FNV-1a, 64 bits: stable across hosts and builds (std::hash is neither).
struct Fnv1a {
    std::uint64_t hash = 0xcbf29ce484222325ull;
    void add(const void* data, std::size_t bytes) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < bytes; ++i) {
            hash = (hash ^ p[i]) * 0x100000001b3ull;
        }
    }
    void add(double value) { add(&value, sizeof value); }
    void add(const std::string& text) { add(text.data(), text.size()); }
};

template <typename T>
std::uint64_t hashArray(const std::vector<T>& array) {
    Fnv1a h;
    std::uint64_t count = array.size();
    h.add(&count, sizeof count);
    h.add(array.data(), array.size() * sizeof(T));  // shared layouts: explicit pads, zero-initialized
    return h.hash;
}

#define PH_FINGERPRINT_SCENE_VECTOR(NAME, b, T, name, access, sizeClass) \
    PH_SCENE_ONLY_##sizeClass(out.push_back({"the scene's " #name, hashArray(scene.name)});)

}  // namespace

std::vector<Fingerprint> renderFingerprints(const Scene& scene, const CameraDesc& camera, const RenderSettings& settings) {
    std::vector<Fingerprint> out;
    PH_BUFFERS(PH_FINGERPRINT_SCENE_VECTOR)
    Fnv1a view;
    for (glm::vec3 v : {camera.position, camera.lookAt, camera.up}) {
        view.add(v.x), view.add(v.y), view.add(v.z);
    }
    view.add(camera.fovY), view.add(camera.lensRadius), view.add(camera.focusDistance);
    out.push_back({"the camera", view.hash});
    for (const SettingSpec& spec : settingSpecs()) {
        Fnv1a h;
        if (spec.kind == SettingKind::Choice) {
            h.add(spec.getName(settings));
        } else {
            h.add(spec.get(settings));
        }
        out.push_back({spec.flag, h.hash});
    }
    return out;
}

}  // namespace photon
