// photon-bench's options as the command line gives them (photon_bench.cpp defines them), read by
// each of its jobs.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/render/devices.h"

namespace photon {

struct BenchOptions {
    std::string backends = "cpu";
    std::string scenes = "cornell";
    std::string scenesDir = PHOTON_SCENES_DIR;
    std::string resolutions = "640x480,800x600,1024x768,1280x720,1920x1080,2560x1600,3840x2400";
    std::string photons = "1000000";
    std::string estimator;  // empty: what a render of many frames of the scene gets (chooseDefaults)
    std::vector<std::string> vary;
    std::string gridSweep;
    std::string jsonPath;
    std::string csvPath;
    std::uint32_t frames = 20;
    std::uint32_t warmup = 3;
    std::uint32_t cpuFrames = 3;
    bool launchSweep = false;
    bool readback = false;
    bool primaryRays = false;
    bool imageWriters = false;
    std::uint32_t writes = 11;
    std::uint32_t photonUse = 0;
    std::string imageDir = ".";
    std::uint32_t bvhBuilds = 0;
    std::string threads = "0";
    DeviceOptions options;
};

}  // namespace photon
