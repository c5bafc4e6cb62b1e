// Comparing a GPU backend with the CPU reference, stage by stage: the photon maps (the same
// photons in every cell, bit for bit, whatever order they were appended in), the hit points, and
// the images.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "core/frame/renderer.h"
#include "core/image/image.h"
#include "core/loaders/scene_loader.h"
#include "core/system/error.h"
#include "test_render.h"
#include "test_util.h"

namespace photon::test {

struct StageOutputs {
    PhotonMaps maps;
    std::vector<HitPoint> hitPoints;
    Image frame;  // the last frame's radiance
    Image image;  // the accumulated image
    FrameStats stats;
};

inline StageOutputs renderStages(Renderer& backend, const Scene& scene, const RenderSettings& settings) {
    renderFrames(backend, scene, settings, settings.frames);
    StageOutputs out;
    out.maps = backend.readPhotonMaps();
    out.hitPoints = backend.readHitPoints();
    out.frame = backend.readFrame();
    out.image = backend.image();
    out.stats = backend.lastFrameStats();
    return out;
}

// A photon map that overflows the room the settings give it, for the GPU backends to grow: albedo
// 0.9 in a closed sphere stores ~9 photons per path; photonCapacity 1 gives room for 1 per path.
inline Scene overflowingScene() {
    Scene scene;
    std::uint32_t wall = scene.addMaterial("wall", makeDiffuse(glm::vec3(0.9f)));
    scene.addSphere(glm::vec3(0.0f), 1.0f, wall);
    scene.addPointLight(glm::vec3(0.0f), glm::vec3(10.0f));
    scene.camera.position = glm::vec3(0.0f);
    scene.camera.lookAt = glm::vec3(0, 0, -1);
    scene.finalize();
    return scene;
}

// `base` with room for one photon a path, and paths long enough to store many.
inline RenderSettings overflowingSettings(RenderSettings base) {
    base.photonCapacity = 1.0f;
    base.maxPhotonDepth = 64;
    base.radius = 0.2f;
    return base;
}

// Settings whose photon buffers are as large as they can be for their paths: every path a global
// one, with room for 64 photons (for requests too large for a device).
inline RenderSettings roomFor64PhotonsPerPath(RenderSettings base) {
    base.photonCapacity = 64.0f;
    base.maxPhotonDepth = 64;
    base.causticFraction = 0.0f;
    return base;
}

// prepare() refuses the backend's scene and settings with an InputError, before any work;
// `accepted` is the failure if it does not. `naming`: a word the message must hold (or none).
inline void expectRefused(Renderer& backend, const std::string& accepted, const char* naming = nullptr) {
    try {
        backend.prepare();
        ADD_FAILURE() << accepted;
    } catch (const InputError& e) {
        std::printf("refused: %s\n", e.what());
        if (naming != nullptr) {
            EXPECT_NE(std::string(e.what()).find(naming), std::string::npos) << e.what();
        }
    }
}

// Each cell's photons as raw bytes, sorted, so that append order does not matter.
inline std::vector<std::string> cellContents(const std::vector<MapPhoton>& photons, std::uint32_t begin, std::uint32_t end) {
    std::vector<std::string> out;
    for (std::uint32_t i = begin; i < end; ++i) {
        out.emplace_back(reinterpret_cast<const char*>(&photons[i]), sizeof(MapPhoton));
    }
    std::sort(out.begin(), out.end());
    return out;
}

// Identical cell ranges, and the same photons in every cell, bit for bit.
inline void expectSamePhotonMaps(const PhotonMaps& actual, const PhotonMaps& expected) {
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        SCOPED_TRACE(m == MAP_GLOBAL ? "global map" : "caustic map");
        ASSERT_EQ(actual.stored[m].size(), expected.stored[m].size());
        ASSERT_EQ(actual.cellStart[m].size(), expected.cellStart[m].size());
        ASSERT_TRUE(actual.cellStart[m] == expected.cellStart[m]) << "cell ranges differ";
        std::size_t differing = 0;
        for (std::size_t c = 0; c + 1 < expected.cellStart[m].size(); ++c) {
            std::uint32_t begin = expected.cellStart[m][c];
            std::uint32_t end = expected.cellStart[m][c + 1];
            if (begin != end && cellContents(actual.stored[m], begin, end) != cellContents(expected.stored[m], begin, end)) {
                differing += 1;
            }
        }
        EXPECT_EQ(differing, 0u) << "cells whose photons differ";
    }
}

// The same photons in the same order: what deterministic photon maps promise.
inline void expectIdenticalPhotonMaps(const PhotonMaps& actual, const PhotonMaps& expected) {
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        SCOPED_TRACE(m == MAP_GLOBAL ? "global map" : "caustic map");
        ASSERT_EQ(actual.stored[m].size(), expected.stored[m].size());
        ASSERT_TRUE(actual.cellStart[m] == expected.cellStart[m]) << "cell ranges differ";
        std::size_t differing = 0;
        for (std::size_t i = 0; i < actual.stored[m].size(); ++i) {
            differing += std::memcmp(&actual.stored[m][i], &expected.stored[m][i], sizeof(MapPhoton)) != 0 ? 1 : 0;
        }
        EXPECT_EQ(differing, 0u) << "photons not in the same place";
    }
}

// Pixels whose values are not bit-identical.
// The largest difference between two backends' auxiliary images (shared/aov.h): of the albedo, the
// normal, the coverage, and the depth relative to the larger of it and 1.
inline float largestAovDifference(const std::vector<PixelAov>& a, const std::vector<PixelAov>& b) {
    float worst = 0.0f;
    for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
        glm::vec3 albedo = glm::abs(a[i].albedo - b[i].albedo);
        glm::vec3 normal = glm::abs(a[i].normal - b[i].normal);
        worst = std::max({worst, albedo.x, albedo.y, albedo.z, normal.x, normal.y, normal.z,
                          std::abs(a[i].depth - b[i].depth) / std::max(a[i].depth, 1.0f),
                          std::abs(a[i].coverage - b[i].coverage), std::abs(a[i].frames - b[i].frames)});
    }
    return worst;
}

inline std::size_t differingPixels(const Image& a, const Image& b) {
    if (a.pixels.size() != b.pixels.size()) {
        return std::max(a.pixels.size(), b.pixels.size());
    }
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        n += std::memcmp(&a.pixels[i], &b.pixels[i], sizeof(glm::vec4)) != 0 ? 1 : 0;
    }
    return n;
}

inline void expectSameHitPoints(const std::vector<HitPoint>& actual, const std::vector<HitPoint>& expected) {
    ASSERT_EQ(actual.size(), expected.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < actual.size(); ++i) {
        differing += std::memcmp(&actual[i], &expected[i], sizeof(HitPoint)) != 0 ? 1 : 0;
    }
    EXPECT_EQ(differing, 0u) << "of " << actual.size() << " hit points differ";
}

// Relative RMSE of an image against the reference; on failure writes both and their difference.
inline void expectImagesClose(const Image& actual, const Image& expected, double tolerance, const std::string& name) {
    ASSERT_TRUE(allFinite(actual)) << name << ": NaN or Inf";
    double error = relativeRmse(actual, expected);
    if (!(error <= tolerance)) {
        writeImage(testOutputPath(name + "-actual.exr"), actual, 0.0f, Tonemap::Clamp);
        writeImage(testOutputPath(name + "-expected.exr"), expected, 0.0f, Tonemap::Clamp);
        writeImage(testOutputPath(name + "-difference.png"), differenceImage(actual, expected), 0.0f, Tonemap::Clamp);
    }
    EXPECT_LE(error, tolerance) << name << ": relative RMSE (images in " << testOutputPath("") << ")";
}

// The spectral cases a GPU backend is compared on: `scene` and the dispersive prism (whose paths
// keep one wavelength each), each with the radius and the SPPM estimator, spectral on in `base`.
inline void forSpectralCases(const Scene& scene, const RenderSettings& base,
                             const std::function<void(const Scene&, const RenderSettings&)>& compare) {
    Scene prism = loadSceneFile(scenesDir() + "/prism.json");
    for (const Scene& s : {scene, prism}) {
        for (Estimator e : {Estimator::Radius, Estimator::Sppm}) {
            RenderSettings settings = base;
            settings.spectral = true;
            settings.estimator = e;
            compare(s, settings);
        }
    }
}

}  // namespace photon::test
