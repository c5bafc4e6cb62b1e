#include "core/frame/glass_pixels.h"

#include "core/frame/frame_setup.h"
#include "shared/eye_trace.h"

namespace photon {

std::vector<bool> glassPixels(const Scene& scene, const CameraDesc& camera, const RenderSettings& settings) {
    const RenderSettings& s = settings;
    Bindings bindings = hostSceneBindings(scene, camera, settings);
    std::vector<bool> glass(std::size_t(s.width) * s.height, false);
    for (std::uint32_t pixel = 0; pixel < glass.size(); ++pixel) {
        Rng unused = rngCreate(pixel, 0u, 0u, STREAM_CAMERA);
        Ray ray = cameraRay(bindings.params.camera, pixel % s.width, pixel / s.width, s.width, s.height,
                            FLAG_PIXEL_CENTER, unused);
        Hit hit;
        if (traceClosest(bindings, ray, hit)) {
            Material m = surfaceAt(bindings, hit).material;
            glass[pixel] = m.type == MATERIAL_GLASS || (m.type == MATERIAL_PBR && m.transmission > 0.0f);
        }
    }
    return glass;
}

}  // namespace photon
