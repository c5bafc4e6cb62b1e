// Preetham, Shirley & Smits 1999, "A Practical Analytic Model for Daylight" (SIGGRAPH 99):
//   sky:  Appendix A.2, the Perez distribution of luminance Y and chromaticities x, y, each
//         Y(θ, γ) = Y_z F(θ, γ) / F(0, θs),  F(θ, γ) = (1 + A e^(B / cos θ)) (1 + C e^(D γ) + E cos² γ),
//         θ the view direction's zenith angle, γ its angle to the sun, θs the sun's zenith angle,
//         A … E linear in turbidity T; the zenith values Y_z, x_z, y_z from T and θs.
//   sun:  Appendix A.1, the extraterrestrial solar spectrum through Rayleigh scattering,
//         Ångström's aerosol turbidity, ozone and water vapour along the relative air mass m.
// The coefficients below were checked against the paper's appendices as reproduced in
// E. Bruneton's clear-sky-models (atmosphere/model/preetham/preetham.cc, Table 2 and Appendices
// 1–2), the solar spectrum also against Sunflow's and LuxCore's sun tables (sunsky / sun_spect.h).
#include "core/scene/sky_model.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/system/parallel.h"
#include "shared/environment.h"

namespace photon {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kLumensPerWatt = 683.0;  // photopic: cd/m² ÷ 683 = the RGB units' luminance

// ---- The sky ------------------------------------------------------------------------------------

// One of the three Perez functions (for Y, x or y), split into its two factors: the gradation
// 1 + A e^(B / cos θ) depends on the row only, the indicatrix 1 + C e^(D γ) + E cos² γ on the sun.
struct Perez {
    float a, b, c, d, e;
    float gradation(float cosTheta) const { return 1.0f + a * std::exp(b / std::max(cosTheta, 1e-4f)); }
    float indicatrix(float gamma, float cosGamma) const {
        return 1.0f + c * std::exp(d * gamma) + e * cosGamma * cosGamma;
    }
};

// Appendix A.2: each coefficient is (slope · T + offset).
Perez makePerez(const float (&k)[5][2], float t) {
    return {k[0][0] * t + k[0][1], k[1][0] * t + k[1][1], k[2][0] * t + k[2][1], k[3][0] * t + k[3][1],
            k[4][0] * t + k[4][1]};
}
constexpr float kPerezY[5][2] = {{0.1787f, -1.4630f}, {-0.3554f, 0.4275f}, {-0.0227f, 5.3251f}, {0.1206f, -2.5771f},
                                 {-0.0670f, 0.3703f}};
constexpr float kPerezX[5][2] = {{-0.0193f, -0.2592f}, {-0.0665f, 0.0008f}, {-0.0004f, 0.2125f}, {-0.0641f, -0.8989f},
                                 {-0.0033f, 0.0452f}};
constexpr float kPerezYc[5][2] = {{-0.0167f, -0.2608f}, {-0.0950f, 0.0092f}, {-0.0079f, 0.2102f}, {-0.0441f, -1.6537f},
                                  {-0.0109f, 0.0529f}};

// Zenith chromaticity: [T² T 1] · M · [θs³ θs² θs 1]ᵀ.
double zenithChromaticity(const double (&m)[3][4], double t, double thetaS) {
    double row[3];
    for (int i = 0; i < 3; ++i) {
        row[i] = ((m[i][0] * thetaS + m[i][1]) * thetaS + m[i][2]) * thetaS + m[i][3];
    }
    return row[0] * t * t + row[1] * t + row[2];
}
constexpr double kZenithX[3][4] = {
    {0.00166, -0.00375, 0.00209, 0.0}, {-0.02903, 0.06377, -0.03202, 0.00394}, {0.11693, -0.21196, 0.06052, 0.25886}};
constexpr double kZenithY[3][4] = {
    {0.00275, -0.00610, 0.00317, 0.0}, {-0.04214, 0.08970, -0.04153, 0.00516}, {0.15346, -0.26756, 0.06670, 0.26688}};

// Zenith luminance [kcd/m²]: Y_z = (4.0453 T − 4.9710) tan χ − 0.2155 T + 2.4192,
// χ = (4/9 − T/120)(π − 2 θs).
double zenithLuminance(double t, double thetaS) {
    double chi = (4.0 / 9.0 - t / 120.0) * (kPi - 2.0 * thetaS);
    return (4.0453 * t - 4.9710) * std::tan(chi) - 0.2155 * t + 2.4192;
}

// CIE XYZ to linear sRGB (IEC 61966-2-1: Rec. 709 primaries, D65 white), colours outside the
// gamut clipped to it (a negative channel becomes 0).
template <typename Vec>
glm::vec3 xyzToLinearSrgb(Vec c) {
    using T = typename Vec::value_type;
    Vec rgb(T(3.2406) * c.x - T(1.5372) * c.y - T(0.4986) * c.z, T(-0.9689) * c.x + T(1.8758) * c.y + T(0.0415) * c.z,
            T(0.0557) * c.x - T(0.2040) * c.y + T(1.0570) * c.z);
    return glm::vec3(glm::max(rgb, Vec(T(0))));
}

// The sky of one SkyDesc, ready to evaluate per texel.
struct Sky {
    glm::vec3 sun;      // the model's sun: the real one, or lifted onto the horizon when below it
    Perez perez[3];     // Y, x, y
    float zenith[3];    // Y_z / F(0, θs) [W·sr⁻¹·m⁻²] (faded below the horizon), x_z / F, y_z / F

    explicit Sky(const SkyDesc& desc) {
        glm::vec3 s = glm::normalize(desc.sunDirection);
        float fade = 1.0f;
        if (s.y < 0.0f) {
            // Below the horizon the model has no sun; keep its horizon sky and dim it to black
            // at −5° elevation.
            float elevationDegrees = float(std::asin(double(s.y)) * 180.0 / kPi);
            fade = std::clamp(1.0f + elevationDegrees / 5.0f, 0.0f, 1.0f);
            glm::vec3 flat(s.x, 0.0f, s.z);
            s = glm::dot(flat, flat) > 1e-12f ? glm::normalize(flat) : glm::vec3(0.0f, 0.0f, -1.0f);
        }
        sun = s;
        double t = desc.turbidity;
        double thetaS = std::acos(std::clamp(double(s.y), -1.0, 1.0));
        perez[0] = makePerez(kPerezY, float(t));
        perez[1] = makePerez(kPerezX, float(t));
        perez[2] = makePerez(kPerezYc, float(t));
        double zenithValue[3] = {zenithLuminance(t, thetaS) * 1000.0 / kLumensPerWatt * fade,
                                 zenithChromaticity(kZenithX, t, thetaS), zenithChromaticity(kZenithY, t, thetaS)};
        for (int i = 0; i < 3; ++i) {
            // F(0, θs): the zenith's own angle to the sun is θs.
            double f0 = double(perez[i].gradation(1.0f)) * perez[i].indicatrix(float(thetaS), s.y);
            zenith[i] = float(zenithValue[i] / f0);
        }
    }

    // The gradations of a row (its cos θ), for Y, x, y.
    void gradations(float cosTheta, float (&g)[3]) const {
        for (int i = 0; i < 3; ++i) {
            g[i] = perez[i].gradation(cosTheta) * zenith[i];
        }
    }

    // Yxy → XYZ → linear sRGB, for a direction with the row gradations g and cos γ to the sun.
    glm::vec3 radiance(const float (&g)[3], float cosGamma) const {
        cosGamma = std::clamp(cosGamma, -1.0f, 1.0f);
        float gamma = std::acos(cosGamma);
        float luminance = g[0] * perez[0].indicatrix(gamma, cosGamma);
        float x = g[1] * perez[1].indicatrix(gamma, cosGamma);
        float y = g[2] * perez[2].indicatrix(gamma, cosGamma);
        if (!(luminance > 0.0f && y > 0.0f)) {
            return glm::vec3(0.0f);
        }
        float perY = luminance / y;
        return xyzToLinearSrgb(glm::vec3(x * perY, luminance, (1.0f - x - y) * perY));
    }
};

// ---- The sun ------------------------------------------------------------------------------------

// 380, 390, … 750 nm: what the coarse spectral sum runs over (the solar table ends at 750 nm; the
// CIE ȳ is below 1.2e-4 beyond it). Mixed gases (O₂'s 760 nm band) absorb outside this range only.
constexpr int kBands = 38;
constexpr double kBandFirst = 380.0;
constexpr double kBandWidth = 10.0;  // [nm]

// Extraterrestrial solar spectral radiance [W·m⁻²·sr⁻¹·nm⁻¹]: Preetham's Table 2 (165.5 … 182.6)
// × 100, the factor the tables' users note; × the disc's 6.8e-5 sr it gives 1.95 W·m⁻²·nm⁻¹ at
// 500 nm, the solar spectral irradiance above the atmosphere.
constexpr double kSolar[kBands] = {165.5, 162.3, 211.2, 258.8, 258.2, 242.3, 267.6, 296.6, 305.4, 300.6,
                                   306.6, 288.3, 287.1, 278.2, 271.0, 272.3, 263.6, 255.0, 250.6, 253.1,
                                   253.5, 251.3, 246.3, 241.7, 236.8, 232.1, 228.2, 223.4, 219.7, 215.3,
                                   211.0, 207.3, 202.4, 198.7, 194.3, 190.7, 186.3, 182.6};

// Ozone absorption k_o [cm⁻¹] (Preetham Table 2, from Iqbal 1983; none tabulated below 450 nm,
// where the Chappuis band has not begun).
constexpr double kOzone[kBands] = {0,     0,     0,     0,     0,     0,     0,     0.003, 0.006, 0.009,
                                   0.014, 0.021, 0.030, 0.040, 0.048, 0.063, 0.075, 0.085, 0.103, 0.120,
                                   0.120, 0.115, 0.125, 0.120, 0.105, 0.090, 0.079, 0.067, 0.057, 0.048,
                                   0.036, 0.028, 0.023, 0.018, 0.014, 0.011, 0.010, 0.009};

// Water vapour absorption k_wa [cm⁻¹] (Table 2): only from 690 nm.
constexpr double kWater[kBands] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
                                   0, 0, 0, 0, 0, 0.016, 0.024, 0.0125, 1.0, 0.87, 0.061, 0.001};

// CIE 1931 2° colour matching functions x̄, ȳ, z̄ at the same wavelengths.
constexpr double kCmf[kBands][3] = {
    {0.001368, 0.000039, 0.006450}, {0.004243, 0.000120, 0.020050}, {0.014310, 0.000396, 0.067850},
    {0.043510, 0.001210, 0.207400}, {0.134380, 0.004000, 0.645600}, {0.283900, 0.011600, 1.385600},
    {0.348280, 0.023000, 1.747060}, {0.336200, 0.038000, 1.772110}, {0.290800, 0.060000, 1.669200},
    {0.195360, 0.090980, 1.287640}, {0.095640, 0.139020, 0.812950}, {0.032010, 0.208020, 0.465180},
    {0.004900, 0.323000, 0.272000}, {0.009300, 0.503000, 0.158200}, {0.063270, 0.710000, 0.078250},
    {0.165500, 0.862000, 0.042160}, {0.290400, 0.954000, 0.020300}, {0.433450, 0.994950, 0.008750},
    {0.594500, 0.995000, 0.003900}, {0.762100, 0.952000, 0.002100}, {0.916300, 0.870000, 0.001650},
    {1.026300, 0.757000, 0.001100}, {1.062200, 0.631000, 0.000800}, {1.002600, 0.503000, 0.000340},
    {0.854450, 0.381000, 0.000190}, {0.642400, 0.265000, 0.000050}, {0.447900, 0.175000, 0.000020},
    {0.283500, 0.107000, 0.0},      {0.164900, 0.061000, 0.0},      {0.087400, 0.032000, 0.0},
    {0.046770, 0.017000, 0.0},      {0.022700, 0.008210, 0.0},      {0.011359, 0.004102, 0.0},
    {0.005790, 0.002091, 0.0},      {0.002899, 0.001047, 0.0},      {0.001440, 0.000520, 0.0},
    {0.000690, 0.000249, 0.0},      {0.000332, 0.000120, 0.0}};

// The sun's radiance at the ground for a sun at zenith angle θs: Σ L_sun(λ) τ(λ) (x̄, ȳ, z̄) Δλ,
// with Appendix A.1's transmittances along the relative air mass
// m = 1 / (cos θs + 0.15 (93.885° − θs)^−1.253) (Kasten's; θs in degrees there), λ in µm:
//   Rayleigh   τ_R = exp(−0.008735 λ^−4.08 m)
//   aerosol    τ_a = exp(−β λ^−α m),  α = 1.3,  β = 0.04608 T − 0.04586 (Ångström)
//   ozone      τ_o = exp(−k_o l m),   l = 0.35 cm
//   water      τ_w = exp(−0.2385 k_wa w m / (1 + 20.07 k_wa w m)^0.45),  w = 2 cm.
glm::vec3 attenuatedSun(double turbidity, double thetaS) {
    double thetaDegrees = std::min(thetaS * 180.0 / kPi, 90.0);
    double m = 1.0 / (std::cos(thetaDegrees * kPi / 180.0) + 0.15 * std::pow(93.885 - thetaDegrees, -1.253));
    double beta = 0.04608 * turbidity - 0.04586;
    glm::dvec3 xyz(0.0);
    for (int i = 0; i < kBands; ++i) {
        double micrometres = (kBandFirst + kBandWidth * i) / 1000.0;
        double kw = kWater[i] * 2.0 * m;
        double tau = std::exp(-0.008735 * std::pow(micrometres, -4.08) * m) *
                     std::exp(-beta * std::pow(micrometres, -1.3) * m) * std::exp(-kOzone[i] * 0.35 * m) *
                     std::exp(-0.2385 * kw / std::pow(1.0 + 20.07 * kw, 0.45));
        double radiance = kSolar[i] * 100.0 * tau;
        xyz += radiance * kBandWidth * glm::dvec3(kCmf[i][0], kCmf[i][1], kCmf[i][2]);
    }
    return xyzToLinearSrgb(xyz);
}

// ---- The map ------------------------------------------------------------------------------------

void validate(const SkyDesc& desc) {
    auto fail = [](const std::string& what) { throw std::logic_error("makeSkyMap: " + what); };
    glm::dvec3 s(desc.sunDirection);
    double length2 = glm::dot(s, s);
    if (!(std::isfinite(length2) && length2 > 0.0)) {
        fail("the sun direction must be finite and nonzero");
    }
    if (!(desc.turbidity >= 1.7f && desc.turbidity <= 10.0f)) {
        fail("turbidity " + std::to_string(desc.turbidity) + " is outside the model's range [1.7, 10]");
    }
    if (!(desc.groundAlbedo >= 0.0f && desc.groundAlbedo <= 1.0f)) {
        fail("ground albedo " + std::to_string(desc.groundAlbedo) + " is outside [0, 1]");
    }
    if (desc.width < 1 || desc.height < 1 || desc.width > kEnvironmentWidthMax || desc.height > kEnvironmentHeightMax) {
        fail("a map of " + std::to_string(desc.width) + " × " + std::to_string(desc.height) + " texels");
    }
}

// Row y is ground when its centre is below the horizon (v > 0.5); the middle row of an odd height
// is sky.
bool isGroundRow(std::size_t y, std::size_t height) { return 2 * y + 1 > height; }

// The direction of map angles (θ, φ), as equirectDirection writes it (in double precision).
glm::dvec3 mapDirection(double theta, double phi) {
    return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

// Adds the sun's disc (radiance `sun`, direction s) to the sky texels it covers. Each candidate
// texel near the sun is cut into n × n sub-texels; a sub-texel whose centre lies in the disc
// counts with its solid angle sin θ dθ dφ. The counts are then scaled so that the whole disc,
// seen or not, covers exactly its solid angle: however coarse the map, the texels hold the
// sun's power, less the part of the disc below the horizon.
void addSunDisc(EnvironmentMap& map, glm::dvec3 s, glm::vec3 sun) {
    std::size_t w = map.width;
    std::size_t h = map.height;
    double dTheta = kPi / double(h);
    double dPhi = 2.0 * kPi / double(w);
    double r = kSunAngularRadius;
    double cosR = std::cos(r);
    // Sub-texels at most r/8 apart along either edge, at least 8 × 8 a texel.
    int n = std::clamp(int(std::ceil(8.0 * std::max(dTheta, dPhi) / r)), 8, 256);
    // A texel can touch the disc only if its centre is within r + its half-extent of the sun.
    double cosNear = std::cos(std::min(r + 0.5 * (dTheta + dPhi), kPi));
    double thetaS = std::acos(std::clamp(s.y, -1.0, 1.0));
    std::size_t y0 = std::size_t(std::max(0.0, std::floor((thetaS - r) / dTheta)));
    std::size_t y1 = std::min(h - 1, std::size_t(std::max(0.0, std::floor((thetaS + r) / dTheta))));

    struct Covered {
        std::size_t texel;
        double solidAngle;  // of the disc's visible part in this texel (before scaling)
        double texelSolidAngle;
    };
    std::vector<Covered> covered;
    double total = 0.0;  // the whole disc's sub-texels, below the horizon too
    for (std::size_t y = y0; y <= y1; ++y) {
        double theta0 = dTheta * double(y);
        double texelSolidAngle = dPhi * (std::cos(theta0) - std::cos(theta0 + dTheta));
        bool sky = !isGroundRow(y, h);
        for (std::size_t x = 0; x < w; ++x) {
            if (glm::dot(mapDirection(theta0 + 0.5 * dTheta, dPhi * (double(x) + 0.5) - kPi), s) < cosNear) {
                continue;
            }
            double visible = 0.0;
            for (int j = 0; j < n; ++j) {
                double theta = theta0 + dTheta * (j + 0.5) / n;
                double subSolidAngle = std::sin(theta) * (dTheta / n) * (dPhi / n);
                for (int i = 0; i < n; ++i) {
                    double phi = dPhi * (double(x) + (i + 0.5) / n) - kPi;
                    if (glm::dot(mapDirection(theta, phi), s) >= cosR) {
                        total += subSolidAngle;
                        visible += sky && theta < 0.5 * kPi ? subSolidAngle : 0.0;
                    }
                }
            }
            if (visible > 0.0) {
                covered.push_back({y * w + x, visible, texelSolidAngle});
            }
        }
    }
    if (total == 0.0) {
        // A map so coarse that no sub-texel centre fell in the disc: all of it goes to the texel
        // of its centre (if that one is sky).
        glm::vec2 uv = equirectCoordinates(glm::vec3(s));
        std::size_t x = std::min(std::size_t(uv.x * float(w)), w - 1);
        std::size_t y = std::min(std::size_t(uv.y * float(h)), h - 1);
        if (!isGroundRow(y, h)) {
            double theta0 = dTheta * double(y);
            covered.push_back({y * w + x, 1.0, dPhi * (std::cos(theta0) - std::cos(theta0 + dTheta))});
            total = 1.0;
        }
    }
    double scale = sunSolidAngle() / total;
    for (const Covered& c : covered) {
        map.texels[c.texel] += sun * float(c.solidAngle * scale / c.texelSolidAngle);
    }
}

}  // namespace

double sunSolidAngle() { return 2.0 * kPi * (1.0 - std::cos(kSunAngularRadius)); }

glm::vec3 skyRadiance(const SkyDesc& desc, glm::vec3 toward) {
    validate(desc);
    Sky sky(desc);
    glm::vec3 d = glm::normalize(toward);
    float g[3];
    sky.gradations(std::max(d.y, 0.0f), g);
    return sky.radiance(g, glm::dot(d, sky.sun));
}

glm::vec3 sunRadiance(const SkyDesc& desc) {
    validate(desc);
    glm::dvec3 s = glm::normalize(glm::dvec3(desc.sunDirection));
    // Some of the disc shows until its top edge sets; its radiance is that of its centre.
    if (s.y <= -std::sin(kSunAngularRadius)) {
        return glm::vec3(0.0f);
    }
    return attenuatedSun(desc.turbidity, std::acos(std::clamp(s.y, -1.0, 1.0)));
}

EnvironmentMap makeSkyMap(const SkyDesc& desc) {
    validate(desc);
    Sky sky(desc);
    EnvironmentMap map;
    map.width = desc.width;
    map.height = desc.height;
    std::size_t w = map.width;
    std::size_t h = map.height;
    map.texels.assign(w * h, glm::vec3(0.0f));
    double dTheta = kPi / double(h);
    double dPhi = 2.0 * kPi / double(w);

    // The sky, row by row, at texel centres: each row's gradations once, each column's φ once.
    std::vector<glm::vec2> sinCosPhi(w);
    for (std::size_t x = 0; x < w; ++x) {
        double phi = dPhi * (double(x) + 0.5) - kPi;
        sinCosPhi[x] = glm::vec2(float(std::sin(phi)), float(std::cos(phi)));
    }
    parallelFor(h, 4, [&](std::size_t first, std::size_t last) {
        for (std::size_t y = first; y < last && !isGroundRow(y, h); ++y) {
            double theta = dTheta * (double(y) + 0.5);
            float sinTheta = float(std::sin(theta));
            float cosTheta = float(std::cos(theta));
            float g[3];
            sky.gradations(cosTheta, g);
            glm::vec3 rowToSun(sinTheta * sky.sun.x, cosTheta * sky.sun.y, -sinTheta * sky.sun.z);
            glm::vec3* row = &map.texels[y * w];
            for (std::size_t x = 0; x < w; ++x) {
                // cos γ = d · sun with d = (sin θ sin φ, cos θ, −sin θ cos φ)
                float cosGamma = rowToSun.x * sinCosPhi[x].x + rowToSun.y + rowToSun.z * sinCosPhi[x].y;
                row[x] = sky.radiance(g, cosGamma);
            }
        }
    });

    glm::vec3 sun = sunRadiance(desc);
    if (sun != glm::vec3(0.0f)) {
        addSunDisc(map, glm::normalize(glm::dvec3(desc.sunDirection)), sun);
    }

    // The ground: E = Σ texel ∫ cos θ dω over the sky texels (the part above the horizon of an
    // odd height's middle row), ∫ cos θ sin θ dθ dφ = dφ (sin² θ1 − sin² θ0) / 2; then ρ E / π.
    std::vector<glm::dvec3> rowIrradiance(h, glm::dvec3(0.0));
    parallelFor(h, 4, [&](std::size_t first, std::size_t last) {
        for (std::size_t y = first; y < last && !isGroundRow(y, h); ++y) {
            double s0 = std::sin(dTheta * double(y));
            double s1 = std::sin(std::min(dTheta * double(y + 1), 0.5 * kPi));
            glm::dvec3 sum(0.0);
            for (std::size_t x = 0; x < w; ++x) {
                sum += glm::dvec3(map.texels[y * w + x]);
            }
            rowIrradiance[y] = sum * (0.5 * dPhi * (s1 * s1 - s0 * s0));
        }
    });
    glm::dvec3 irradiance(0.0);
    for (const glm::dvec3& e : rowIrradiance) {
        irradiance += e;
    }
    glm::vec3 ground(irradiance * (double(desc.groundAlbedo) / kPi));
    for (std::size_t y = (h + 1) / 2; y < h; ++y) {
        std::fill(map.texels.begin() + std::ptrdiff_t(y * w), map.texels.begin() + std::ptrdiff_t((y + 1) * w), ground);
    }
    return map;
}

}  // namespace photon
