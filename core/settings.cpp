#include "settings.h"

#include <array>
#include <utility>

namespace photon {
namespace {

template <typename E, std::size_t N>
using Names = std::array<std::pair<E, const char*>, N>;

constexpr Names<Estimator, 4> kEstimators{{{Estimator::Cell, "cell"},
                                           {Estimator::Radius, "radius"},
                                           {Estimator::Knn, "knn"},
                                           {Estimator::Progressive, "progressive"}}};
constexpr Names<Kernel, 3> kKernels{{{Kernel::Box, "box"}, {Kernel::Cone, "cone"}, {Kernel::Epanechnikov, "epanechnikov"}}};
constexpr Names<GridKind, 2> kGrids{{{GridKind::Bounded, "bounded"}, {GridKind::Hashed, "hashed"}}};
constexpr Names<GlobalMode, 2> kGlobalModes{{{GlobalMode::Direct, "direct"}, {GlobalMode::FinalGather, "final-gather"}}};
constexpr Names<View, 5> kViews{{{View::Final, "final"},
                                 {View::Direct, "direct"},
                                 {View::Global, "global"},
                                 {View::Caustic, "caustic"},
                                 {View::Grid, "grid"}}};
constexpr Names<Tonemap, 3> kTonemaps{{{Tonemap::Clamp, "clamp"}, {Tonemap::Reinhard, "reinhard"}, {Tonemap::Aces, "aces"}}};

template <typename E, std::size_t N>
const char* nameOf(const Names<E, N>& names, E e) {
    for (const auto& [value, name] : names) {
        if (value == e) {
            return name;
        }
    }
    return "?";
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

const char* toString(Estimator e) { return nameOf(kEstimators, e); }
const char* toString(Kernel k) { return nameOf(kKernels, k); }
const char* toString(GridKind g) { return nameOf(kGrids, g); }
const char* toString(GlobalMode m) { return nameOf(kGlobalModes, m); }
const char* toString(View v) { return nameOf(kViews, v); }
const char* toString(Tonemap t) { return nameOf(kTonemaps, t); }

bool parse(const std::string& s, Estimator& out) { return valueOf(kEstimators, s, out); }
bool parse(const std::string& s, Kernel& out) { return valueOf(kKernels, s, out); }
bool parse(const std::string& s, GridKind& out) { return valueOf(kGrids, s, out); }
bool parse(const std::string& s, GlobalMode& out) { return valueOf(kGlobalModes, s, out); }
bool parse(const std::string& s, View& out) { return valueOf(kViews, s, out); }
bool parse(const std::string& s, Tonemap& out) { return valueOf(kTonemaps, s, out); }

std::string choices(Estimator) { return list(kEstimators); }
std::string choices(Kernel) { return list(kKernels); }
std::string choices(GridKind) { return list(kGrids); }
std::string choices(GlobalMode) { return list(kGlobalModes); }
std::string choices(View) { return list(kViews); }
std::string choices(Tonemap) { return list(kTonemaps); }

}  // namespace photon
