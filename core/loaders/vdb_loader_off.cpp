// The OpenVDB loader of a build without OpenVDB (PHOTON_OPENVDB=OFF): every file is refused with a
// message that says why, so a scene with a .vdb medium fails the same way on every backend.
#include "core/loaders/vdb_loader.h"

#include "core/system/error.h"

namespace photon {

DensityGrid loadVdbDensity(const std::string& path, const std::string& gridName, std::uint32_t maxResolution) {
    return decodeVdbDensity(std::string(), path, gridName, maxResolution);
}

DensityGrid decodeVdbDensity(const std::string&, const std::string& path, const std::string&, std::uint32_t) {
    throw InputError(path + ": this build reads no OpenVDB files (configured with PHOTON_OPENVDB=OFF)");
}

}  // namespace photon
