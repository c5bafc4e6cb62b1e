#include "core/frame/footprints.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/frame/estimator_policy.h"
#include "core/frame/frame_setup.h"
#include "shared/eye_trace.h"
#include "shared/sppm.h"

namespace photon {

Footprints measureFootprints(const Scene& scene, const CameraDesc& camera, const RenderSettings& settings) {
    const RenderSettings& s = settings;
    Bindings bindings = hostSceneBindings(scene, camera, settings);
    std::uint32_t columns = std::min<std::uint32_t>(48, s.width);
    std::uint32_t rows = std::min<std::uint32_t>(36, s.height);
    std::vector<float> widths;
    widths.reserve(std::size_t(columns) * rows);
    for (std::uint32_t j = 0; j < rows; ++j) {
        for (std::uint32_t i = 0; i < columns; ++i) {
            std::uint32_t x = (2 * i + 1) * s.width / (2 * columns);
            std::uint32_t y = (2 * j + 1) * s.height / (2 * rows);
            HitPoint hp = tracePixel(bindings, y * s.width + x);
            if (hp.material != NONE) {
                float w = pixelFootprint(bindings.params.camera, s.height, hp.position);
                if (w > 0.0f && std::isfinite(w)) {
                    widths.push_back(w);
                }
            }
        }
    }
    Footprints f;
    if (widths.empty()) {
        return f;
    }
    std::sort(widths.begin(), widths.end());
    f.median = widths[widths.size() / 2];
    f.high = widths[std::min(widths.size() - 1, widths.size() * 9 / 10)];
    f.any = true;
    return f;
}

}  // namespace photon
