#include "core/settings/settings.h"

#include <array>
#include <stdexcept>
#include <string>
#include <utility>

namespace photon {
namespace {

template <typename E, std::size_t N>
using Names = std::array<std::pair<E, const char*>, N>;

constexpr Names<Estimator, enumCount<Estimator>()> kEstimators{{{Estimator::Cell, "cell"},
                                           {Estimator::Radius, "radius"},
                                           {Estimator::Knn, "knn"},
                                           {Estimator::Progressive, "progressive"},
                                           {Estimator::Sppm, "sppm"}}};
constexpr Names<Kernel, enumCount<Kernel>()> kKernels{{{Kernel::Box, "box"}, {Kernel::Cone, "cone"}, {Kernel::Epanechnikov, "epanechnikov"}}};
constexpr Names<GridKind, enumCount<GridKind>()> kGrids{{{GridKind::Bounded, "bounded"}, {GridKind::Hashed, "hashed"}}};
constexpr Names<GlobalMode, enumCount<GlobalMode>()> kGlobalModes{{{GlobalMode::Direct, "direct"}, {GlobalMode::FinalGather, "final-gather"}}};
constexpr Names<View, enumCount<View>()> kViews{{{View::Final, "final"},
                                 {View::Direct, "direct"},
                                 {View::Global, "global"},
                                 {View::Caustic, "caustic"},
                                 {View::Grid, "grid"},
                                 {View::Volume, "volume"}}};
constexpr Names<Tonemap, enumCount<Tonemap>()> kTonemaps{{{Tonemap::Clamp, "clamp"}, {Tonemap::Reinhard, "reinhard"}, {Tonemap::Aces, "aces"}}};
constexpr Names<Denoise, enumCount<Denoise>()> kDenoise{{{Denoise::Off, "off"}, {Denoise::On, "on"}}};

// Each table lists every value once, in order, so that names[v] is the name of value v.
template <typename E, std::size_t N>
constexpr bool complete(const Names<E, N>& names) {
    for (std::size_t i = 0; i < N; ++i) {
        if (static_cast<std::size_t>(names[i].first) != i || names[i].second == nullptr) {
            return false;
        }
    }
    return true;
}
static_assert(complete(kEstimators) && complete(kKernels) && complete(kGrids) && complete(kGlobalModes) &&
              complete(kViews) && complete(kTonemaps) && complete(kDenoise), "every enumeration value needs its name, in order");

template <typename E, std::size_t N>
const char* nameOf(const Names<E, N>& names, E e) {
    auto i = static_cast<std::size_t>(e);
    if (i >= N) {
        throw std::logic_error("unknown enumeration value " + std::to_string(i));
    }
    return names[i].second;
}

template <typename E, std::size_t N>
bool valueOf(const Names<E, N>& names, const std::string& s, E& out) {
    for (const auto& [value, name] : names) {
        if (s == name) {
            out = value;
            return true;
        }
    }
    return false;
}

template <typename E, std::size_t N>
std::string list(const Names<E, N>& names) {
    std::string out;
    for (const auto& [value, name] : names) {
        out += out.empty() ? "" : "|";
        out += name;
    }
    return out;
}

}  // namespace

float mapRadius(const RenderSettings& settings, std::uint32_t map) {
    PH_COVERS(MAP_COUNT, 3u);
    switch (map) {
        case MAP_GLOBAL: return settings.radius;
        case MAP_CAUSTIC: return settings.causticRadius;
        case MAP_VOLUME: return settings.volumeRadius;
    }
    throw std::logic_error("mapRadius: no photon map " + std::to_string(map));
}

const char* mapRadiusFlag(std::uint32_t map) {
#define PH_MAP_FLAG(NAME, id, name, radiusFlag, autoFootprints, fallbackShare, sppmPhotons, sppmMin, sppmMax) radiusFlag,
    static constexpr const char* kFlags[] = {PH_MAPS(PH_MAP_FLAG)};
#undef PH_MAP_FLAG
    static_assert(sizeof(kFlags) / sizeof(kFlags[0]) == MAP_COUNT, "a radius option for every map");
    if (map >= MAP_COUNT) {
        throw std::logic_error("mapRadiusFlag: no photon map " + std::to_string(map));
    }
    return kFlags[map];
}

const char* toString(Estimator e) { return nameOf(kEstimators, e); }
const char* toString(Kernel k) { return nameOf(kKernels, k); }
const char* toString(GridKind g) { return nameOf(kGrids, g); }
const char* toString(GlobalMode m) { return nameOf(kGlobalModes, m); }
const char* toString(View v) { return nameOf(kViews, v); }
const char* toString(Tonemap t) { return nameOf(kTonemaps, t); }
const char* toString(Denoise d) { return nameOf(kDenoise, d); }

bool parse(const std::string& s, Estimator& out) { return valueOf(kEstimators, s, out); }
bool parse(const std::string& s, Kernel& out) { return valueOf(kKernels, s, out); }
bool parse(const std::string& s, GridKind& out) { return valueOf(kGrids, s, out); }
bool parse(const std::string& s, GlobalMode& out) { return valueOf(kGlobalModes, s, out); }
bool parse(const std::string& s, View& out) { return valueOf(kViews, s, out); }
bool parse(const std::string& s, Tonemap& out) { return valueOf(kTonemaps, s, out); }
bool parse(const std::string& s, Denoise& out) { return valueOf(kDenoise, s, out); }

std::string choices(Estimator) { return list(kEstimators); }
std::string choices(Kernel) { return list(kKernels); }
std::string choices(GridKind) { return list(kGrids); }
std::string choices(GlobalMode) { return list(kGlobalModes); }
std::string choices(View) { return list(kViews); }
std::string choices(Tonemap) { return list(kTonemaps); }
std::string choices(Denoise) { return list(kDenoise); }

}  // namespace photon
