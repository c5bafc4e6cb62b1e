// Without OpenVDB (PHOTON_OPENVDB=OFF, the device preset) every .vdb file is refused, unread, with
// one line that says why.
#include "core/loaders/vdb_loader.h"

#include <gtest/gtest.h>

#include "core/system/error.h"

namespace photon {
namespace {

TEST(VdbLoaderOff, RefusesEveryFile) {
    try {
        loadVdbDensity("/nonexistent/smoke.vdb", "density", 64);
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "/nonexistent/smoke.vdb: this build reads no OpenVDB files (configured with PHOTON_OPENVDB=OFF)");
    }
}

}  // namespace
}  // namespace photon
