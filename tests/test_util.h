// Helpers shared by the tests: Bindings over a host scene, χ² testing, image diff files.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "core/frame/estimator_policy.h"
#include "core/frame/frame_setup.h"
#include "core/image/image.h"
#include "core/scene/scene.h"
#include "shared/bindings.h"
#include "shared/intersect.h"

namespace photon::test {

// Bindings that point at a host scene, for calling shared/ functions that read buffers.
struct SceneBindings {
    Scene scene;
    Bindings bindings{};

    explicit SceneBindings(Scene s, RenderSettings settings = {}) : scene(std::move(s)) {
        scene.finalize();
        PhotonBudget budget = planPhotons(scene, settings);
        bindings.params = makeFrameParams(scene, scene.camera, settings, budget, 0, 0,
                                          firstFrameRadii(scene, settings, measureFootprints(scene, scene.camera, settings), budget));
        bindSceneArrays(bindings, scene);
    }
};

// Pearson's χ² statistic of observed counts against expected counts; bins with expected < 5
// are merged into their neighbour (as Mitsuba and pbrt do).
inline double chiSquare(const std::vector<double>& observed, const std::vector<double>& expected, int& dof) {
    double chi2 = 0.0;
    double pooledObserved = 0.0;
    double pooledExpected = 0.0;
    dof = -1;
    for (std::size_t i = 0; i < observed.size(); ++i) {
        pooledObserved += observed[i];
        pooledExpected += expected[i];
        if (pooledExpected >= 5.0) {
            chi2 += (pooledObserved - pooledExpected) * (pooledObserved - pooledExpected) / pooledExpected;
            pooledObserved = 0.0;
            pooledExpected = 0.0;
            dof += 1;
        }
    }
    return chi2;
}

// Upper quantile of the χ² distribution via the Wilson–Hilferty approximation; z = 4.26 is a
// significance of 1e-5, so a correct sampler fails about once in 100000 runs.
inline double chiSquareThreshold(int dof, double z = 4.26) {
    double k = double(dof);
    double t = 1.0 - 2.0 / (9.0 * k) + z * std::sqrt(2.0 / (9.0 * k));
    return k * t * t * t;
}

// The shipped scenes: $PHOTON_SCENES_DIR if set (a build run from another checkout, as on the
// GPU machine), else the source tree the tests were built from.
// Random rays from inside and around a scene's bounds (a quarter of them beyond on every side) in
// random directions; every third one ends at half the bounds' diagonal.
inline std::vector<Ray> randomSceneRays(const Scene& scene, int count, std::uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> u(-0.25f, 1.25f);
    std::normal_distribution<float> g(0.0f, 1.0f);
    glm::vec3 extent = scene.boundsMax - scene.boundsMin;
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i) {
        glm::vec3 origin = scene.boundsMin + extent * glm::vec3(u(random), u(random), u(random));
        glm::vec3 d(g(random), g(random), g(random));
        if (glm::dot(d, d) >= 1e-6f) {
            rays.push_back(makeRay(origin, glm::normalize(d), i % 3 == 0 ? glm::length(extent) * 0.5f : FLOAT_MAX));
        }
    }
    return rays;
}

inline std::string scenesDir() {
    const char* env = std::getenv("PHOTON_SCENES_DIR");
    return env ? env : PHOTON_SCENES_DIR;
}

// The shipped scene files with one of `extensions` (".json", ".glb", ...), in a stable order,
// less those that read OpenVDB files (smoke.json) where the build reads none (PHOTON_OPENVDB=OFF,
// as on the GPU machine).
inline std::vector<std::string> shippedScenes(const std::vector<std::string>& extensions) {
    std::vector<std::string> paths;
    for (const auto& entry : std::filesystem::directory_iterator(scenesDir())) {
        std::string ext = entry.path().extension().string();
        if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end()) {
            continue;
        }
#ifndef PHOTON_TESTS_READ_OPENVDB
        std::ifstream file(entry.path());
        std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
        if (ext == ".json" && text.find(".vdb\"") != std::string::npos) {
            continue;
        }
#endif
        paths.push_back(entry.path().string());
    }
    std::sort(paths.begin(), paths.end());
    return paths;
}

// The converged references of tests/data/: $PHOTON_TEST_DATA_DIR if set, else the source tree's.
inline std::string dataPath(const std::string& name) {
    const char* env = std::getenv("PHOTON_TEST_DATA_DIR");
    return std::string(env ? env : PHOTON_TEST_DATA_DIR) + "/" + name;
}

// Where tests write images that help explain a failure: $PHOTON_TEST_OUTPUT_DIR if set.
inline std::string testOutputPath(const std::string& name) {
    const char* env = std::getenv("PHOTON_TEST_OUTPUT_DIR");
    return std::string(env ? env : PHOTON_TEST_OUTPUT_DIR) + "/" + name;
}

}  // namespace photon::test
