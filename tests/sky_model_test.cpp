// The environments made on the host: Preetham's daylight sky with its sun, and the studio.
// Checked against the paper's formulas (computed here again), the Perez distribution's shape,
// the sun disc's power at coarse and fine resolutions, and the maps' conventions.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/scene/sky_model.h"
#include "core/scene/studio_environment.h"
#include "shared/environment.h"

namespace photon {
namespace {

constexpr double kPi = 3.14159265358979323846;

double luminance(glm::vec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// Towards elevation e and azimuth a (degrees; azimuth from −Z towards +X, the map's convention).
glm::vec3 toward(double e, double a) {
    e *= kPi / 180.0;
    a *= kPi / 180.0;
    return glm::vec3(float(std::cos(e) * std::sin(a)), float(std::sin(e)), float(-std::cos(e) * std::cos(a)));
}

double texelSolidAngle(const EnvironmentMap& m, std::uint32_t y) {
    double theta0 = kPi * y / m.height;
    return 2.0 * kPi / m.width * (std::cos(theta0) - std::cos(theta0 + kPi / m.height));
}

glm::vec3 texelDirection(const EnvironmentMap& m, std::uint32_t x, std::uint32_t y) {
    return equirectDirection((x + 0.5f) / float(m.width), (y + 0.5f) / float(m.height));
}

// The irradiance of a surface facing up, by the midpoint rule over the texels above the horizon.
glm::dvec3 upIrradiance(const EnvironmentMap& m) {
    glm::dvec3 e(0.0);
    for (std::uint32_t y = 0; y < m.height; ++y) {
        double cosTheta = std::cos(kPi * (y + 0.5) / m.height);
        for (std::uint32_t x = 0; cosTheta > 0.0 && x < m.width; ++x) {
            e += glm::dvec3(m.texels[y * m.width + x]) * cosTheta * texelSolidAngle(m, y);
        }
    }
    return e;
}

SkyDesc sky(double elevation, double azimuth, float turbidity, std::uint32_t width = 512, std::uint32_t height = 256) {
    SkyDesc d;
    d.sunDirection = toward(elevation, azimuth);
    d.turbidity = turbidity;
    d.width = width;
    d.height = height;
    return d;
}

TEST(SkyModel, ZenithIsPreethamsZenithLuminanceAndChromaticity) {
    // Appendix A.2 for T = 3 and the sun 45° high: Y_z [kcd/m²], x_z, y_z.
    double t = 3.0;
    double thetaS = kPi / 4.0;
    double chi = (4.0 / 9.0 - t / 120.0) * (kPi - 2.0 * thetaS);
    double yz = (4.0453 * t - 4.9710) * std::tan(chi) - 0.2155 * t + 2.4192;
    auto poly = [&](double a, double b, double c, double d) { return ((a * thetaS + b) * thetaS + c) * thetaS + d; };
    double xz = poly(0.00166, -0.00375, 0.00209, 0) * t * t + poly(-0.02903, 0.06377, -0.03202, 0.00394) * t +
                poly(0.11693, -0.21196, 0.06052, 0.25886);
    double yzc = poly(0.00275, -0.00610, 0.00317, 0) * t * t + poly(-0.04214, 0.08970, -0.04153, 0.00516) * t +
                 poly(0.15346, -0.26756, 0.06670, 0.26688);
    EXPECT_NEAR(yz, 7.320, 0.001);  // kcd/m²
    double expected = yz * 1000.0 / 683.0;  // W·sr⁻¹·m⁻² in the photopic sense

    SkyDesc d = sky(45.0, 30.0, 3.0f);
    glm::vec3 zenith = skyRadiance(d, glm::vec3(0, 1, 0));
    EXPECT_NEAR(luminance(zenith), expected, 1e-3 * expected);
    // Back to XYZ by sRGB's matrix: the chromaticity is the paper's.
    glm::dvec3 c(zenith);
    glm::dvec3 xyz(0.4124 * c.x + 0.3576 * c.y + 0.1805 * c.z, 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z,
                   0.0193 * c.x + 0.1192 * c.y + 0.9505 * c.z);
    double sum = xyz.x + xyz.y + xyz.z;
    EXPECT_NEAR(xyz.x / sum, xz, 2e-3);
    EXPECT_NEAR(xyz.y / sum, yzc, 2e-3);

    // The map's first row circles the zenith 0.35° away: its mean is the zenith's.
    EnvironmentMap map = makeSkyMap(d);
    double row = 0.0;
    for (std::uint32_t x = 0; x < map.width; ++x) {
        row += luminance(map.texels[x]);
    }
    EXPECT_NEAR(row / map.width, expected, 0.01 * expected);
}

TEST(SkyModel, PerezIsBrightestNearTheSunDarkestAwayFromItBrightAgainOppositeOnTheHorizon) {
    SkyDesc d = sky(45.0, 0.0, 3.0f);
    double nearSun = luminance(skyRadiance(d, toward(40.0, 0.0)));
    double atRightAngle = luminance(skyRadiance(d, toward(45.0, 180.0)));  // 90° from the sun
    double oppositeHorizon = luminance(skyRadiance(d, toward(2.0, 180.0)));
    EXPECT_GT(nearSun, 2.0 * oppositeHorizon);
    EXPECT_GT(oppositeHorizon, 1.2 * atRightAngle);
    // Over the whole sky: the brightest direction is at the sun, the darkest 70°–110° from it.
    glm::vec3 sun = glm::normalize(d.sunDirection);
    double brightest = 0.0, darkest = 1e30, brightestAngle = 0.0, darkestAngle = 0.0;
    for (int e = 1; e <= 90; ++e) {
        for (int a = 0; a < 360; a += 2) {
            glm::vec3 v = toward(e, a);
            double l = luminance(skyRadiance(d, v));
            double angle = std::acos(std::clamp(double(glm::dot(v, sun)), -1.0, 1.0)) * 180.0 / kPi;
            if (l > brightest) {
                brightest = l;
                brightestAngle = angle;
            }
            if (l < darkest) {
                darkest = l;
                darkestAngle = angle;
            }
        }
    }
    EXPECT_LT(brightestAngle, 2.0);
    EXPECT_GT(darkestAngle, 70.0);
    EXPECT_LT(darkestAngle, 110.0);
}

// Σ (texel − sky) · texel solid angle near the sun = the sun's radiance × its solid angle.
void expectSunPower(const SkyDesc& d) {
    EnvironmentMap map = makeSkyMap(d);
    glm::vec3 sun = glm::normalize(d.sunDirection);
    double texelSize = std::max(kPi / map.height, 2.0 * kPi / map.width);
    double touching = kSunAngularRadius + texelSize;  // a texel that touches the disc has its centre nearer
    glm::dvec3 power(0.0);
    double brightest = 0.0;
    double brightestAngle = 0.0;
    for (std::uint32_t y = 0; y < map.height; ++y) {
        for (std::uint32_t x = 0; x < map.width; ++x) {
            glm::vec3 v = texelDirection(map, x, y);
            double angle = std::acos(std::clamp(double(glm::dot(v, sun)), -1.0, 1.0));
            glm::vec3 texel = map.texels[y * map.width + x];
            if (angle < 3.0 * kPi / 180.0 + touching) {
                power += glm::dvec3(texel - skyRadiance(d, v)) * texelSolidAngle(map, y);
            }
            if (luminance(texel) > brightest) {
                brightest = luminance(texel);
                brightestAngle = angle;
            }
        }
    }
    glm::dvec3 expected = glm::dvec3(sunRadiance(d)) * sunSolidAngle();
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(power[i], expected[i], 0.01 * expected[i]) << map.width << "×" << map.height << " channel " << i;
    }
    // The disc is where shared/environment.h's directions put the sun: the brightest texel touches it.
    EXPECT_LT(brightestAngle, touching) << map.width << "×" << map.height;
}

TEST(SkyModel, SunDiscKeepsItsPowerAtEveryResolution) {
    EXPECT_NEAR(sunSolidAngle(), 6.8e-5, 0.1e-5);
    for (double elevation : {45.0, 10.0, 89.9}) {
        expectSunPower(sky(elevation, 30.0, 3.0f, 512, 256));
        expectSunPower(sky(elevation, 30.0, 3.0f, 4096, 2048));
        expectSunPower(sky(elevation, -100.0, 5.0f, 1001, 333));
        expectSunPower(sky(elevation, 0.0, 3.0f, 64, 32));  // texels of 5.6°, the disc 0.53°
        expectSunPower(sky(elevation, 180.0, 3.0f, 512, 256));  // on the seam u = 0 = 1
    }
}

TEST(SkyModel, HazeBrightensTheHorizonAndReddensTheSun) {
    // Mean luminance of the band 0°–10° above the horizon, all the way round.
    auto horizon = [](const SkyDesc& d) {
        double sum = 0.0;
        int n = 0;
        for (int e = 1; e < 10; ++e) {
            for (int a = 0; a < 360; a += 5, ++n) {
                sum += luminance(skyRadiance(d, toward(e, a)));
            }
        }
        return sum / n;
    };
    // From 3 to 8 the horizon brightens (by 32% for a sun 45° high). From 2 it does not: at
    // T = 2 the Perez gradation at the zenith, 1 + A e^B, is 0.17 (it reaches 0 at T ≈ 1.7, the
    // model's limit), which makes that clear sky's horizon 4× its zenith and brighter than T = 8's.
    EXPECT_GT(horizon(sky(45.0, 0.0, 8.0f)), 1.2 * horizon(sky(45.0, 0.0, 3.0f)));
    // What haze does from 2 on: the sky as a whole brightens, its zenith 4× and its light on the
    // ground (the map's irradiance less the sun's direct part) …
    SkyDesc clear = sky(45.0, 0.0, 2.0f, 256, 128);
    SkyDesc hazy = sky(45.0, 0.0, 8.0f, 256, 128);
    glm::vec3 up(0, 1, 0);
    EXPECT_GT(luminance(skyRadiance(hazy, up)), 3.0 * luminance(skyRadiance(clear, up)));
    auto skyIrradiance = [](const SkyDesc& d) {
        glm::dvec3 direct = glm::dvec3(sunRadiance(d)) * sunSolidAngle() * std::sin(kPi / 4.0);
        return luminance(glm::vec3(upIrradiance(makeSkyMap(d)) - direct));
    };
    EXPECT_GT(skyIrradiance(hazy), 1.2 * skyIrradiance(clear));
    // … and the sun dims and reddens (aerosols take more blue than red).
    glm::vec3 sunClear = sunRadiance(clear);
    glm::vec3 sunHazy = sunRadiance(hazy);
    EXPECT_LT(luminance(sunHazy), luminance(sunClear));
    EXPECT_GT(sunHazy.x / sunHazy.z, 1.1f * sunClear.x / sunClear.z);
    // A low sun is redder than a high one.
    glm::vec3 sunLow = sunRadiance(sky(5.0, 0.0, 3.0f));
    glm::vec3 sunHigh = sunRadiance(sky(60.0, 0.0, 3.0f));
    EXPECT_GT(sunLow.x / sunLow.z, 1.5f * sunHigh.x / sunHigh.z);
}

TEST(SkyModel, NoTexelIsNegativeOrNotFinite) {
    for (float t : {1.7f, 2.0f, 3.0f, 6.0f, 10.0f}) {
        for (double e : {-90.0, -10.0, -3.0, -0.2, 0.0, 0.1, 1.0, 10.0, 45.0, 89.99, 90.0}) {
            EnvironmentMap map = makeSkyMap(sky(e, 70.0, t, 128, 64));
            for (glm::vec3 c : map.texels) {
                ASSERT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z)) << t << " " << e;
                ASSERT_TRUE(c.x >= 0.0f && c.y >= 0.0f && c.z >= 0.0f) << t << " " << e;
            }
        }
    }
}

TEST(SkyModel, SunBelowTheHorizonLeavesADimSkyThenNight) {
    EXPECT_EQ(sunRadiance(sky(-1.0, 0.0, 3.0f)), glm::vec3(0.0f));
    double day = luminance(skyRadiance(sky(10.0, 0.0, 3.0f), glm::vec3(0, 1, 0)));
    double dusk = luminance(skyRadiance(sky(-3.0, 0.0, 3.0f), glm::vec3(0, 1, 0)));
    EXPECT_GT(dusk, 0.0);
    EXPECT_LT(dusk, day);
    EnvironmentMap night = makeSkyMap(sky(-10.0, 0.0, 3.0f, 64, 32));
    for (glm::vec3 c : night.texels) {
        EXPECT_EQ(c, glm::vec3(0.0f));
    }
}

TEST(SkyModel, RowZeroIsTheZenithAndTheGroundReflectsTheSkyAndSun) {
    SkyDesc d = sky(30.0, 45.0, 3.0f, 512, 256);
    EnvironmentMap map = makeSkyMap(d);
    double zenith = luminance(skyRadiance(d, glm::vec3(0, 1, 0)));
    EXPECT_NEAR(luminance(map.texels[0]), zenith, 0.02 * zenith);
    // Every ground texel is ρ E / π, E the sky's and sun's irradiance on the ground.
    glm::dvec3 ground = upIrradiance(map) * (0.3 / kPi);
    for (std::uint32_t y = map.height / 2; y < map.height; ++y) {
        for (std::uint32_t x = 0; x < map.width; x += 37) {
            for (int i = 0; i < 3; ++i) {
                ASSERT_NEAR(map.texels[y * map.width + x][i], ground[i], 0.01 * ground[i]);
            }
        }
    }
    // Sun 30° high: E = E_sky + L_sun Ω_sun sin 30°.
    glm::dvec3 direct = glm::dvec3(sunRadiance(d)) * sunSolidAngle() * 0.5;
    EXPECT_GT(luminance(glm::vec3(ground)) * kPi / 0.3, luminance(glm::vec3(direct)));
    d.groundAlbedo = 0.0f;
    EXPECT_EQ(makeSkyMap(d).texels.back(), glm::vec3(0.0f));
}

TEST(SkyModel, RefusesWhatTheLoaderShouldHaveRefused) {
    SkyDesc d;
    d.turbidity = 1.5f;
    EXPECT_THROW(makeSkyMap(d), std::logic_error);
    d.turbidity = std::nanf("");
    EXPECT_THROW(makeSkyMap(d), std::logic_error);
    d = SkyDesc{};
    d.sunDirection = glm::vec3(0.0f);
    EXPECT_THROW(makeSkyMap(d), std::logic_error);
    d.sunDirection = glm::vec3(INFINITY, 1.0f, 0.0f);
    EXPECT_THROW(makeSkyMap(d), std::logic_error);
    d = SkyDesc{};
    d.width = 0;
    EXPECT_THROW(makeSkyMap(d), std::logic_error);
    EXPECT_THROW(makeStudioMap(0, 10), std::logic_error);
}

TEST(SkyModel, Makes2048By1024Quickly) {
    SkyDesc d;  // 2048 × 1024
    double best = 1e30;
    for (int i = 0; i < 5; ++i) {
        auto start = std::chrono::steady_clock::now();
        EnvironmentMap map = makeSkyMap(d);
        best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        ASSERT_EQ(map.texels.size(), 2048u * 1024u);
    }
    std::printf("makeSkyMap 2048×1024: %.1f ms (best of 5)\n", best);
    RecordProperty("milliseconds", std::to_string(best));
}

TEST(StudioMap, IsNeutralAndLightsAnUpFacingWhiteSurfaceToOne) {
    for (auto [w, h] : {std::pair{1024u, 512u}, std::pair{256u, 128u}, std::pair{300u, 151u}}) {
        EnvironmentMap map = makeStudioMap(w, h);
        ASSERT_EQ(map.texels.size(), std::size_t(w) * h);
        for (glm::vec3 c : map.texels) {
            ASSERT_TRUE(c.x == c.y && c.y == c.z && c.x >= 0.0f && std::isfinite(c.x));
        }
        glm::dvec3 e = upIrradiance(map);
        EXPECT_NEAR(e.x, kPi, 0.05 * kPi) << w << "×" << h;
        // Row 0 is the top of the backdrop, the last row the floor.
        EXPECT_NEAR(map.texels[0].x, 0.8f, 0.01f);
        EXPECT_NEAR(map.texels.back().x, 0.15f, 0.01f);
    }
    // The key (front left, 45° up) is the brightest light, brighter than the fill and the rim.
    EnvironmentMap map = makeStudioMap();
    auto at = [&](double e, double a) {
        glm::vec2 uv = equirectCoordinates(toward(e, a));
        return map.texels[std::min(std::uint32_t(uv.y * map.height), map.height - 1) * map.width +
                          std::min(std::uint32_t(uv.x * map.width), map.width - 1)].x;
    };
    float key = at(45.0, -135.0), fill = at(20.0, 120.0), rim = at(45.0, 20.0), wall = at(10.0, 0.0);
    EXPECT_GT(key, rim);
    EXPECT_GT(rim, fill);
    EXPECT_GT(fill, wall);
    std::printf("studio radiance: key %.3f, fill %.3f, rim %.3f, backdrop at 10° %.3f\n", key, fill, rim, wall);
}

}  // namespace
}  // namespace photon
