// photon-bench --bvh-builds: the BVH build alone, on each thread count: median time, its phases,
// and the tree's size and SAH cost (no frames).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace photon {

// The thread counts of --threads (0: all); throws InputError on anything else.
std::vector<unsigned> parseThreadCounts(const std::string& list);

// Prints a table, a row per scene and thread count, of `builds` builds of each scene's hierarchy;
// writes the rows as JSON to `jsonPath` unless it is empty.
void benchBvhBuilds(const std::vector<std::string>& scenes, const std::string& scenesDir, std::uint32_t builds,
                    const std::vector<unsigned>& threadCounts, const std::string& jsonPath);

}  // namespace photon
