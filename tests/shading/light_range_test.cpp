// A light's range and its windowed falloff, Cook-Torrance's attenuation, and area lights' emitter
// cosine and shadow samples (lighting.h), each against a computation in double written here from the
// literature: Real-Time Rendering, 4th ed., §5.2.2 (the window functions), Shirley and Chiu 1997 (the
// concentric map of a square onto a disk).
#include <cmath>
#include <set>
#include <span>
#include <utility>

#include <gtest/gtest.h>

#include "shading/lighting.h"

namespace facet {
namespace {

// RTR4 §5.2.2: f_win(d) = (1 − (d/r)⁴)²₊ (Karis 2013) and Just Cause 2's (1 − (d/r)²)²₊, in double.
double windowUe4(double d, double r) {
    const double t = std::max(1.0 - std::pow(d / r, 4.0), 0.0);
    return t * t;
}
double windowJc2(double d, double r) {
    const double t = std::max(1.0 - std::pow(d / r, 2.0), 0.0);
    return t * t;
}

LightParams pointWithRange(float range, RangeWindow window) {
    LightParams light;
    light.kind = LightKind::Point;
    light.range = range;
    light.window = window;
    return light;
}

// 1 at the light, 0 at r_max and beyond, 0.9375² = 0.87890625 (UE4) and 0.75² = 0.5625 (JC2) at r/2,
// and the double formula across the range. Breaks if the exponent is wrong (x² in UE4's), the clamp
// is missing (beyond r_max (1 − x⁴)² grows again) or d is not divided by r_max.
TEST(LightRange, WindowMatchesTheFormulaInDouble) {
    for (const float r : {0.5f, 3.0f, 40.0f}) {
        for (const RangeWindow w : {RangeWindow::Ue4, RangeWindow::Jc2}) {
            SCOPED_TRACE(testing::Message() << "r = " << r << ", window " << nameOf(w));
            const LightParams light = pointWithRange(r, w);
            EXPECT_EQ(rangeWindow(light, 0.0f), 1.0f);
            EXPECT_EQ(rangeWindow(light, r), 0.0f);
            EXPECT_EQ(rangeWindow(light, 1.5f * r), 0.0f);
            EXPECT_EQ(rangeWindow(light, 10.0f * r), 0.0f);
            EXPECT_NEAR(rangeWindow(light, 0.5f * r), w == RangeWindow::Ue4 ? 0.87890625 : 0.5625, 1e-6);
            for (int i = 0; i <= 100; ++i) {
                const double d = r * i / 80.0;
                const double expected = w == RangeWindow::Ue4 ? windowUe4(d, r) : windowJc2(d, r);
                EXPECT_NEAR(rangeWindow(light, float(d)), expected, 1e-6) << "d = " << d;
                EXPECT_NEAR(rangeWindow(light, d), expected, 1e-12) << "d = " << d;  // double lanes
            }
        }
    }
    // No range, or a directional light: 1 everywhere.
    LightParams none;
    none.kind = LightKind::Point;
    EXPECT_EQ(rangeWindow(none, 1e6f), 1.0f);
    LightParams directional = pointWithRange(1.0f, RangeWindow::Ue4);
    directional.kind = LightKind::Directional;
    EXPECT_EQ(rangeWindow(directional, 5.0f), 1.0f);
}

// Eight lanes give the one lane's bits. Breaks if the wide path computes another formula.
TEST(LightRange, EightLanesMatchOne) {
    const LightParams light = pointWithRange(2.0f, RangeWindow::Ue4);
    Float8 d;
    for (int i = 0; i < 8; ++i)
        d[i] = 0.3f * float(i);
    const Float8 w = rangeWindow(light, d);
    for (int i = 0; i < 8; ++i)
        EXPECT_EQ(w[i], rangeWindow(light, d[i]));
}

// The window multiplies the falloff in both models: the standard att·f_win and Cook-Torrance's.
// Without a range each falloff is what it was. Breaks if the window is left out of either model.
TEST(LightRange, WindowMultipliesTheFalloffInEveryModel) {
    LightParams light = pointWithRange(4.0f, RangeWindow::Ue4);
    light.c0 = 1.0f;
    light.c1 = 0.5f;
    light.c2 = 0.25f;
    const float d = 3.0f;
    const double att = 1.0 / (1.0 + 0.5 * 3 + 0.25 * 9);
    EXPECT_NEAR(standardFalloff(light, d), att * windowUe4(3, 4), 1e-6);
    light.attenuationGiven = true;
    EXPECT_NEAR(physicalFalloff(light, d), att * windowUe4(3, 4), 1e-6);
    light.attenuationGiven = false;
    EXPECT_NEAR(physicalFalloff(light, d), windowUe4(3, 4) / 9.0, 1e-6);
    light.range = 0.0f;
    EXPECT_EQ(standardFalloff(light, d), attenuation(light, d));
    EXPECT_EQ(physicalFalloff(light, d), 1.0f / (d * d));

    // A whole evaluation: beyond the range the light adds nothing, in each model.
    LightParams far = pointWithRange(1.0f, RangeWindow::Jc2);
    far.position = vec3(0.0f, 0.0f, 2.0f);
    const std::span<const LightParams> lights(&far, 1);
    const LightingTerms<vec3> standard = standardLighting<float>(
        vec3(0.0f), vec3(0, 0, 1), vec3(0, 0, 5), PhongMaterial{.specular = vec3(1.0f)}, vec3(0.0f), lights);
    EXPECT_EQ(standard.diffuse, vec3(0.0f));
    EXPECT_EQ(standard.specular, vec3(0.0f));
    const LightingTerms<vec3> pbr = physicallyBasedTerms<float>(
        vec3(0.0f), vec3(0, 0, 1), vec3(0, 0, 5), PbrMaterial{}, vec3(0.8f), vec3(0.0f), vec3(0.0f), lights);
    EXPECT_EQ(pbr.diffuse, vec3(0.0f));
    EXPECT_EQ(pbr.specular, vec3(0.0f));
    far.range = 0.0f;
    EXPECT_GT(physicallyBasedTerms<float>(vec3(0.0f), vec3(0, 0, 1), vec3(0, 0, 5), PbrMaterial{}, vec3(0.8f),
                                          vec3(0.0f), vec3(0.0f), lights)
                  .diffuse.x,
              0.0f);
}

// Cook-Torrance: 1/d² by default, the polynomial 1/(c0 + c1·d + c2·d²) where the scene gave one. The
// diffuse term of a white Lambertian dielectric lit head-on (F at normal incidence 0.04) scales by the
// falloff. Breaks if the given attenuation is ignored (both 1/d²) or used without being given.
TEST(LightRange, CookTorranceHonoursAGivenAttenuation) {
    LightParams light;
    light.kind = LightKind::Point;
    light.position = vec3(0.0f, 0.0f, 2.0f);
    light.c0 = 1.0f;
    light.c1 = 0.0f;
    light.c2 = 1.0f;  // 1/(1 + d²) = 0.2 at d = 2, against 1/d² = 0.25
    const auto diffuse = [&](const LightParams& l) {
        return physicallyBasedTerms<float>(vec3(0.0f), vec3(0, 0, 1), vec3(0, 0, 5), PbrMaterial{},
                                           vec3(1.0f), vec3(0.0f), vec3(0.0f),
                                           std::span<const LightParams>(&l, 1))
            .diffuse.x;
    };
    const float inverseSquare = diffuse(light);
    light.attenuationGiven = true;
    const float polynomial = diffuse(light);
    EXPECT_NEAR(polynomial / inverseSquare, 0.2 / 0.25, 1e-5);
    // π·c_light·falloff·(1 − F)·c_base/π with F = 0.04 at normal incidence: 0.96·0.25.
    EXPECT_NEAR(inverseSquare, 0.96 * 0.25, 1e-4);
}

// An area light's emitter cosine max(−L·n, 0): a one-sided Lambertian emitter. Breaks if the sign is
// wrong (lit from behind) or the factor is left out (1 at a grazing angle).
TEST(AreaLight, EmitterCosineIsOneSided) {
    LightParams light;
    light.kind = LightKind::Rect;
    light.areaNormal = vec3(0.0f, -1.0f, 0.0f);
    const double angle = 0.7;
    const vec3 below = vec3(float(std::sin(angle)), float(std::cos(angle)), 0.0f);  // L from a point below
    EXPECT_NEAR(spotFactor<float>(light, below), std::cos(angle), 1e-6);
    EXPECT_EQ(spotFactor<float>(light, -below), 0.0f);
    light.kind = LightKind::Point;
    EXPECT_EQ(spotFactor<float>(light, -below), 1.0f);
}

// The samples of an m×m rectangle: one in each cell of the grid over the emitter (stratified), every
// one on it; the same positions on every call. A disk's lie within its radius and keep one per
// concentric stratum: as many in each of the four quadrants. Breaks if samples pile up, leave the
// emitter or change from call to call.
TEST(AreaLight, SamplesAreStratifiedOverTheEmitter) {
    LightParams rect;
    rect.kind = LightKind::Rect;
    rect.position = vec3(1.0f, 2.0f, 3.0f);
    rect.areaU = vec3(0.5f, 0.0f, 0.0f);  // 1 wide
    rect.areaV = vec3(0.0f, 0.0f, 1.0f);  // 2 high
    for (const int m : {1, 2, 4, 8, 16}) {
        const int n = m * m;
        std::set<std::pair<int, int>> cells;
        for (int k = 0; k < n; ++k) {
            const vec3 s = areaLightSample(rect, k, n);
            EXPECT_EQ(s, areaLightSample(rect, k, n));
            EXPECT_EQ(s.y, 2.0f);
            const double a = (double(s.x) - 1.0) / 0.5, b = (double(s.z) - 3.0) / 1.0;  // in [−1, 1]
            ASSERT_LE(std::abs(a), 1.0);
            ASSERT_LE(std::abs(b), 1.0);
            cells.insert({int(std::floor((a + 1.0) / 2.0 * m)), int(std::floor((b + 1.0) / 2.0 * m))});
        }
        EXPECT_EQ(cells.size(), std::size_t(n)) << m << "×" << m;
    }
    EXPECT_EQ(areaLightSample(rect, 0, 1), rect.position);
    LightParams disk = rect;
    disk.kind = LightKind::Disk;
    disk.areaV = vec3(0.0f, 0.0f, 0.5f);  // radius 0.5
    // Area-preserving: uniform over the disk, the mean of ρ² is R²/2 (a map with ρ uniform gives R²/3).
    double meanSquare = 0;
    glm::dvec2 mean(0.0);
    for (int k = 0; k < 64; ++k) {
        const vec3 s = areaLightSample(disk, k, 64);
        const double a = double(s.x) - 1.0, b = double(s.z) - 3.0;
        EXPECT_LE(std::hypot(a, b), 0.5 + 1e-6);
        meanSquare += (a * a + b * b) / 64.0;
        mean += glm::dvec2(a, b) / 64.0;
    }
    EXPECT_NEAR(meanSquare, 0.125, 0.006);
    EXPECT_NEAR(mean.x, 0.0, 0.02);
    EXPECT_NEAR(mean.y, 0.0, 0.02);
}

}  // namespace
}  // namespace facet
