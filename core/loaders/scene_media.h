// The participating media of a scene file (docs/scenes.md#media): the "media" it names, the
// medium inside a material, the medium that fills the scene.
#ifndef PHOTON_CORE_LOADERS_SCENE_MEDIA_H
#define PHOTON_CORE_LOADERS_SCENE_MEDIA_H

#include <map>
#include <string>

#include "core/loaders/json_node.h"
#include "core/loaders/model_loader.h"
#include "core/scene/scene.h"

namespace photon {

using MediaByName = std::map<std::string, Medium>;

// Where the files a medium names are: the scene file's folder (with its '/', or ""), and how to
// read them.
struct MediaFiles {
    std::string folder;
    FileReader read;
};

// "media": {"fog": {"scattering": 0.2, "absorption": 0.01, "g": 0.3}, ...}; each coefficient a
// number or an RGB array [1/scene unit], or "density" and "albedo" instead; and for a
// heterogeneous medium a "grid" from an OpenVDB file, whose voxels go into the scene's densities.
MediaByName readMedia(Scene& scene, const JsonNode& node, const MediaFiles& files);

// A material's "medium": the name of one of `media`, added to the scene; its index.
std::uint32_t readMaterialMedium(Scene& scene, const JsonNode& node, const MediaByName& media);

// The scene's "medium": a name, or {"name": ..., "min": [x, y, z], "max": [x, y, z]} for a box
// (without one: the scene's bounds).
void readSceneMedium(Scene& scene, const JsonNode& node, const MediaByName& media);

}  // namespace photon

#endif
