// Render settings: everything a user can choose about how a scene is rendered. Read from a scene
// file's "render" block, then overridden from the command line.
#pragma once

#include <cstdint>
#include <string>

#include "shared/constants.h"

namespace photon {

// Each option's values are the shared constants (shared/constants.h); enumCount<E>() is their
// *_COUNT, and the name tables in settings.cpp are checked against it.
enum class Estimator : std::uint32_t {
    Cell = ESTIMATOR_CELL,
    Radius = ESTIMATOR_RADIUS,
    Knn = ESTIMATOR_KNN,
    Progressive = ESTIMATOR_PROGRESSIVE,
    Sppm = ESTIMATOR_SPPM
};
enum class Kernel : std::uint32_t { Box = KERNEL_BOX, Cone = KERNEL_CONE, Epanechnikov = KERNEL_EPANECHNIKOV };
enum class GridKind : std::uint32_t { Bounded = GRID_BOUNDED, Hashed = GRID_HASHED };
enum class GlobalMode : std::uint32_t { Direct = GLOBAL_DIRECT, FinalGather = GLOBAL_FINAL_GATHER };
enum class View : std::uint32_t {
    Final = VIEW_FINAL,
    Direct = VIEW_DIRECT,
    Global = VIEW_GLOBAL,
    Caustic = VIEW_CAUSTIC,
    Grid = VIEW_GRID,
    Volume = VIEW_VOLUME
};
enum class Tonemap : std::uint32_t { Clamp = TONEMAP_CLAMP, Reinhard = TONEMAP_REINHARD, Aces = TONEMAP_ACES };
enum class Denoise : std::uint32_t { Off = DENOISE_OFF, On = DENOISE_ON };

template <typename E>
constexpr std::uint32_t enumCount();
template <> constexpr std::uint32_t enumCount<Estimator>() { return ESTIMATOR_COUNT; }
template <> constexpr std::uint32_t enumCount<Kernel>() { return KERNEL_COUNT; }
template <> constexpr std::uint32_t enumCount<GridKind>() { return GRID_KIND_COUNT; }
template <> constexpr std::uint32_t enumCount<GlobalMode>() { return GLOBAL_MODE_COUNT; }
template <> constexpr std::uint32_t enumCount<View>() { return VIEW_COUNT; }
template <> constexpr std::uint32_t enumCount<Tonemap>() { return TONEMAP_COUNT; }
template <> constexpr std::uint32_t enumCount<Denoise>() { return DENOISE_MODE_COUNT; }

struct RenderSettings {
    std::uint32_t width = 640;
    std::uint32_t height = 480;
    std::uint32_t photons = 200000;       // photon paths emitted per frame, both passes together
    std::uint32_t frames = 1;             // frames averaged into the image
    float causticFraction = 0.5f;         // share of the photons aimed at specular objects (if any)
    Estimator estimator = Estimator::Radius;
    Kernel kernel = Kernel::Epanechnikov;
    float radius = 0.0f;                  // global map query radius; 0: automatic (estimator_policy.h)
    float causticRadius = 0.0f;           // caustic map query radius; 0: automatic
    float volumeRadius = 0.0f;            // volume map beam radius (shared/volume_estimate.h); 0: automatic
    std::uint32_t k = 50;                 // photons of the k-nearest estimator
    float alpha = 2.0f / 3.0f;            // progressive radius reduction (Knaus & Zwicker)
    GlobalMode globalMode = GlobalMode::Direct;
    std::uint32_t gatherRays = 16;        // final-gather rays per hit point
    std::uint32_t lightSamples = 1;       // shadow rays per light per hit point
    std::uint32_t maxEyeDepth = 8;        // specular bounces an eye path may take
    std::uint32_t eyeSplits = 2;          // glass and mirror-coat interfaces where an eye path follows both branches
    std::uint32_t maxPhotonDepth = 8;     // surfaces a photon may hit
    GridKind grid = GridKind::Hashed;
    std::uint32_t gridResolution = 64;    // k of the bounded k³ grid
    float cellSize = 1.0f;                // hashed grid cell edge in query radii (≥ 1: ≤ 3³ cells a query)
    std::uint32_t gatherBudget = 256;     // photons a query visits per cell before subsampling it (0: all)
    float photonCapacity = 4.0f;          // stored photons reserved per global path (GPU backends)
    std::uint32_t seed = 1;
    bool pixelCenter = false;             // one ray through each pixel centre, no lens
    bool deterministic = true;            // GPUs order each cell's photons canonically: the same seed
                                          // gives the same image bit for bit (the CPU always does)
    bool spectral = false;                // paths carry wavelengths (shared/spectral.h): dispersion
    float wavelength = 0.0f;              // every path at this wavelength [nm] (implies spectral); 0: sampled
    View view = View::Final;
    Denoise denoise = Denoise::Off;       // filter the image (shared/denoise.h); photon-render and the viewer
                                          // turn it on unless told (chooseDefaults)
    bool aov = false;                     // keep the auxiliary images (albedo, normal, depth, variance)
    bool reproject = false;               // a moving camera carries the image's history (shared/reproject.h);
                                          // the viewer turns it on unless told (chooseInteractive)
    float exposure = 0.0f;                // stops
    Tonemap tonemap = Tonemap::Aces;
    std::uint64_t given = 0;              // bit i: settingSpecs()[i] was set by a file or a flag
};

// A photon map's query radius as set (0: automatic), and the flag that sets it.
float mapRadius(const RenderSettings& settings, std::uint32_t map);

// Whether paths carry wavelengths: --spectral, or one wavelength given.
inline bool isSpectral(const RenderSettings& settings) { return settings.spectral || settings.wavelength > 0.0f; }

// Whether the denoiser runs (never on the grid view, a heat map), and whether the accumulate stage
// keeps the auxiliary images (for it, or for --aov).
inline bool denoises(const RenderSettings& settings) { return settings.denoise == Denoise::On && settings.view != View::Grid; }
// Reprojection needs them too: their depths and normals tell whether a pixel still sees its surface.
inline bool keepsAovs(const RenderSettings& settings) { return settings.aov || denoises(settings) || settings.reproject; }
const char* mapRadiusFlag(std::uint32_t map);

const char* toString(Estimator e);
const char* toString(Kernel k);
const char* toString(GridKind g);
const char* toString(GlobalMode m);
const char* toString(View v);
const char* toString(Tonemap t);
const char* toString(Denoise d);

// Parse the names above; false if the name is not one of them.
bool parse(const std::string& s, Estimator& out);
bool parse(const std::string& s, Kernel& out);
bool parse(const std::string& s, GridKind& out);
bool parse(const std::string& s, GlobalMode& out);
bool parse(const std::string& s, View& out);
bool parse(const std::string& s, Tonemap& out);
bool parse(const std::string& s, Denoise& out);

// The accepted names, "a|b|c", for messages and --help.
std::string choices(Estimator);
std::string choices(Kernel);
std::string choices(GridKind);
std::string choices(GlobalMode);
std::string choices(View);
std::string choices(Tonemap);
std::string choices(Denoise);

}  // namespace photon
