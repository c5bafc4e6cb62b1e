#include "core/frame/frame_setup.h"

#include <algorithm>
#include <cmath>

#include "core/frame/estimator_policy.h"
#include "core/spectral/spectrum.h"

namespace photon {
namespace {

std::uint32_t nextPowerOfTwo(std::uint64_t n) {
    std::uint64_t p = 1;
    while (p < n) {
        p <<= 1;
    }
    return static_cast<std::uint32_t>(std::min<std::uint64_t>(p, 1u << 30));
}

}  // namespace

PhotonBudget planPhotons(const Scene& scene, const RenderSettings& settings) {
    PhotonBudget b;
    b.splitCaustics = scene.hasCausticTargets() && settings.causticFraction > 0.0f;
    if (b.splitCaustics) {
        b.causticPaths = static_cast<std::uint32_t>(std::lround(double(settings.photons) * settings.causticFraction));
        b.causticPaths = std::min(b.causticPaths, settings.photons - 1u);
    }
    b.globalPaths = settings.photons - b.causticPaths;
    b.sppm = settings.estimator == Estimator::Sppm;
    b.deterministic = settings.deterministic;
    b.aovs = keepsAovs(settings);
    b.denoise = denoises(settings);
    b.history = settings.reproject;
    // A global path stores at most one photon per bounce; Russian roulette makes the mean small.
    // A caustic path stores at most one photon: at its first non-specular surface.
    double perPath = std::min<double>(settings.photonCapacity, settings.maxPhotonDepth);
    b.capacity[MAP_GLOBAL] =
        static_cast<std::uint32_t>(std::min(std::ceil(double(b.globalPaths) * perPath), double(kMapCapacityMax)));
    if (b.splitCaustics) {
        b.capacity[MAP_CAUSTIC] = b.causticPaths;
    } else {
        b.capacity[MAP_CAUSTIC] = scene.makesCausticPaths() ? b.globalPaths : 0u;
    }
    // A global path scatters in media at most once per bounce, as it stores on surfaces.
    b.capacity[MAP_VOLUME] = scene.media.empty() ? 0u : b.capacity[MAP_GLOBAL];
    for (std::uint32_t map = 0; map < MAP_COUNT; ++map) {
        if (settings.grid == GridKind::Bounded) {
            std::uint64_t k = settings.gridResolution;
            b.cells[map] = static_cast<std::uint32_t>(k * k * k);
        } else {
            b.cells[map] = nextPowerOfTwo(std::max<std::uint64_t>(b.capacity[map], 1024));
        }
    }
    return b;
}

FrameParams makeFrameParams(const Scene& scene, const CameraDesc& camera, const RenderSettings& settings,
                            const PhotonBudget& budget, std::uint32_t frameIndex, std::uint32_t accumulated,
                            const FrameRadii& radii, const PathSplit& split) {
    FrameParams p{};
    p.camera = makeCamera(camera, settings.width, settings.height);

    SceneInfo& info = p.scene;
    info.planeCount = static_cast<std::uint32_t>(scene.planes.size());
    info.lightCount = static_cast<std::uint32_t>(scene.lights.size());
    info.targetCount = budget.splitCaustics ? static_cast<std::uint32_t>(scene.targets.size()) : 0u;
    bool linear = scene.primitiveRefs.size() <= LINEAR_PRIMITIVES_MAX;
    info.bvhNodeCount = linear ? 0u : static_cast<std::uint32_t>(scene.bvhNodes.size());
    info.linearCount = linear ? static_cast<std::uint32_t>(scene.primitiveRefs.size()) : 0u;
    info.infiniteLight = 0u;  // the scene's one, its environment (Scene::finalize)
    info.environmentLight = scene.environmentLight;
    info.medium = scene.medium;

    glm::vec3 extent = scene.boundsMax - scene.boundsMin;
    float cube = std::max({extent.x, extent.y, extent.z});
    for (std::uint32_t map = 0; map < MAP_COUNT; ++map) {
        GridParams& g = p.grids[map];
        g.radius = radii.radius[map];
        g.kind = settings.grid == GridKind::Bounded ? GRID_BOUNDED : GRID_HASHED;
        // Hashed cells start at the camera, where the image needs precision (a far object that
        // stretches the bounds changes nothing).
        g.origin = settings.grid == GridKind::Bounded ? scene.boundsMin : camera.position;
        if (settings.grid == GridKind::Bounded) {
            g.resolution = settings.gridResolution;
            g.cellSize = cube / float(settings.gridResolution);
        } else {
            g.resolution = 0;
            g.cellSize = settings.cellSize * g.radius;
        }
        g.cellCount = budget.cells[map];
        g.cellOffset = budget.cellOffset(map);
        g.photonOffset = budget.photonOffset(map);
        g.photonCapacity = budget.capacity[map];
    }

    p.width = settings.width;
    p.height = settings.height;
    p.frameIndex = frameIndex;
    p.seed = settings.seed;
    p.globalPaths = budget.globalPaths;
    p.causticPaths = budget.causticPaths;
    p.maxPhotonDepth = settings.maxPhotonDepth;
    p.maxEyeDepth = settings.maxEyeDepth;
    p.eyeSplits = settings.eyeSplits;
    p.estimator = static_cast<std::uint32_t>(settings.estimator);
    p.kernel = static_cast<std::uint32_t>(settings.kernel);
    p.knnK = settings.k;
    p.globalMode = static_cast<std::uint32_t>(settings.globalMode);
    p.gatherRays = settings.gatherRays;
    p.lightSamples = settings.lightSamples;
    p.view = static_cast<std::uint32_t>(settings.view);
    p.flags = (settings.pixelCenter ? FLAG_PIXEL_CENTER : 0u) | (budget.splitCaustics ? FLAG_SPLIT_CAUSTICS : 0u) |
              (settings.deterministic ? FLAG_DETERMINISTIC : 0u) | (isSpectral(settings) ? FLAG_SPECTRAL : 0u) |
              (keepsAovs(settings) ? FLAG_AOVS : 0u) | (denoises(settings) ? FLAG_DENOISE : 0u);
    if (isSpectral(settings)) {
        p.spectrum = frameSpectrum(frameIndex, settings.seed, settings.wavelength);
    }
    p.accumulated = accumulated;
    p.gatherBudget = settings.gatherBudget;
    for (std::uint32_t map = 0; map < MAP_COUNT; ++map) {
        p.sppm[map] = radii.sppm[map];
    }
    p.alpha = settings.alpha;
    p.branchShrink = radii.branchShrink;
    p.pathFirst = 0;
    p.pathCount = static_cast<std::uint32_t>(budget.totalPaths());
    splitPaths(p, split);
    return p;
}

Bindings hostSceneBindings(const Scene& scene, const CameraDesc& camera, const RenderSettings& settings) {
    RenderSettings s = settings;
    s.pixelCenter = true;
    Bindings bindings{};
    bindings.params = makeFrameParams(scene, camera, s, PhotonBudget{}, 0, 0, FrameRadii{});
    bindSceneArrays(bindings, scene);
    return bindings;
}

void splitPaths(FrameParams& params, const PathSplit& split) {
    std::uint64_t count = params.pathCount;
    std::uint64_t first = count * split.rank / split.ranks;
    params.pathFirst += static_cast<std::uint32_t>(first);
    params.pathCount = static_cast<std::uint32_t>(count * (split.rank + 1) / split.ranks - first);
}

}  // namespace photon
