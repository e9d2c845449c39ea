// The surface formulas of the lecture decks against independent double-precision computations:
// Torrance-Sparrow's Gaussian distribution (its normalisation integral), anisotropic GGX and its Smith
// masking, Fresnel's equations for the two polarisations (Brewster's angle, normal incidence, glass at
// grazing angles), F0 from an index of refraction, and every row of the F0 table.
#include <cmath>
#include <numbers>
#include <random>
#include <string_view>

#include <gtest/gtest.h>

#include "shading/lighting.h"

namespace facet {
namespace {

using std::numbers::pi;

// ∫_Ω f(θ) dω = 2π ∫_0^{π/2} f(θ) sin θ dθ by the midpoint rule, in double.
template <class Integrand>
double integrateOverTheta(Integrand f) {
    constexpr int kSteps = 200000;
    const double step = (pi / 2) / kSteps;
    double sum = 0;
    for (int i = 0; i < kSteps; ++i) {
        const double theta = (i + 0.5) * step;
        sum += f(theta) * std::sin(theta);
    }
    return 2 * pi * sum * step;
}

// ---- The Gaussian distribution -----------------------------------------------------------------------

// Catches a normalisation constant that is wrong (e.g. Beckmann's 1/(π m²) for every m, which is 8%
// off at m = 0.5), or θ/m squared the wrong way.
TEST(GaussianDistribution, ProjectedAreaIntegratesToOne) {
    for (float m : {0.02f, 0.1f, 0.3f, 0.5f, 1.0f}) {
        const double integral = integrateOverTheta([&](double theta) {
            return double(distributionGaussian(float(std::cos(theta)), m)) * std::cos(theta);
        });
        EXPECT_NEAR(integral, 1.0, 2e-3) << "m = " << m;
    }
}

// c(m) against the closed form of the small-m limit, 1/(π m²) (the integral of θ e^{−θ²/m²} over
// [0, ∞) is m²/2), and the shape: D(θ = m) = c/e, D(0) = c. Catches a wrong m mapping or exponent.
TEST(GaussianDistribution, ConstantAndShape) {
    const float m = 0.01f;
    EXPECT_NEAR(gaussianNormalization(m) * pi * m * m, 1.0, 1e-3);
    const float alpha = 0.3f;
    const float c = gaussianNormalization(alpha);
    EXPECT_NEAR(distributionGaussian(1.0f, alpha), c, 1e-4f * c);
    EXPECT_NEAR(distributionGaussian(float(std::cos(0.3)), alpha), c / std::numbers::e, 1e-4 * c);
    EXPECT_EQ(distributionGaussian(-0.2f, alpha), 0.0f);
    // The constant is the lane-independent value the eight-lane and double versions use.
    EXPECT_NEAR(gaussianNormalizationExact(alpha), c, 1e-6 * c);
}

// ---- Anisotropic GGX --------------------------------------------------------------------------------

// With α_x = α_y the anisotropic D and G1 are the isotropic ones, in any tangent frame.
TEST(AnisotropicGgx, ReducesToIsotropicWhenBothRoughnessesAreEqual) {
    std::mt19937 random(7);
    std::uniform_real_distribution<float> angle(0.0f, 1.5f), turn(0.0f, 6.28f);
    for (int i = 0; i < 100; ++i) {
        const float theta = angle(random), phi = turn(random), alpha = 0.05f + 0.009f * i;
        const float hx = std::sin(theta) * std::cos(phi), hy = std::sin(theta) * std::sin(phi);
        const float hz = std::cos(theta);
        const float iso = distributionGGX(hz, alpha);
        EXPECT_NEAR(distributionGGXAnisotropic(hx, hy, hz, alpha, alpha), iso, 1e-4f * iso);
        const float g = smithG1GGX(hz, alpha);
        EXPECT_NEAR(smithG1GGXAnisotropic(hx, hy, hz, alpha, alpha), g, 1e-5f);
    }
}

// ∫ D(h)(n·h) dω = 1 over the hemisphere for α_x ≠ α_y, integrated over θ and φ in double from the
// formula written here (Walter et al. 2007 eq. 33 with its ellipse): catches a swapped α or a missing
// 1/(α_x α_y).
TEST(AnisotropicGgx, NormalisesAndStretchesAlongTheTangent) {
    const float ax = 0.15f, ay = 0.45f;
    constexpr int kTheta = 2000, kPhi = 400;
    double sum = 0;
    for (int i = 0; i < kTheta; ++i) {
        const double theta = (i + 0.5) * (pi / 2) / kTheta;
        for (int j = 0; j < kPhi; ++j) {
            const double phi = (j + 0.5) * 2 * pi / kPhi;
            const double x = std::sin(theta) * std::cos(phi), y = std::sin(theta) * std::sin(phi);
            sum += distributionGGXAnisotropic(float(x), float(y), float(std::cos(theta)), ax, ay) *
                   std::cos(theta) * std::sin(theta);
        }
    }
    EXPECT_NEAR(sum * (pi / 2 / kTheta) * (2 * pi / kPhi), 1.0, 5e-3);
    // The independent value at one h: 1/(π α_x α_y (x²/α_x² + y²/α_y² + z²)²).
    const double x = 0.1, y = 0.2, z = std::sqrt(1 - x * x - y * y);
    const double s = x * x / (ax * ax) + y * y / (ay * ay) + z * z;
    EXPECT_NEAR(distributionGGXAnisotropic(float(x), float(y), float(z), ax, ay), 1 / (pi * ax * ay * s * s),
                1e-4 / (pi * ax * ay * s * s));
    // Rougher along b: a half vector tilted towards b keeps more D than one tilted as far towards t.
    EXPECT_GT(distributionGGXAnisotropic(0.0f, 0.3f, 0.954f, ax, ay),
              distributionGGXAnisotropic(0.3f, 0.0f, 0.954f, ax, ay));
}

// Heitz 2014's Λ for an anisotropic GGX, written here: G1 = 1/(1 + Λ), Λ = (−1 + √(1 + a))/2,
// a = (α_x² x² + α_y² y²)/z².
TEST(AnisotropicGgx, SmithMaskingMatchesHeitz) {
    const double ax = 0.2, ay = 0.7, x = 0.5, y = 0.4, z = std::sqrt(1 - x * x - y * y);
    const double lambda = (-1 + std::sqrt(1 + (ax * ax * x * x + ay * ay * y * y) / (z * z))) / 2;
    EXPECT_NEAR(smithG1GGXAnisotropic(float(x), float(y), float(z), float(ax), float(ay)), 1 / (1 + lambda),
                1e-6);
}

// Kulla & Conty 2017: α_x = α(1 + a), α_y = α(1 − a).
TEST(AnisotropicGgx, AnisotropyMapping) {
    const AnisotropicAlpha a = anisotropicAlpha(0.25f, 0.5f);
    EXPECT_FLOAT_EQ(a.x, 0.375f);
    EXPECT_FLOAT_EQ(a.y, 0.125f);
    EXPECT_FLOAT_EQ(anisotropicAlpha(0.25f, 0.0f).x, 0.25f);
    EXPECT_FLOAT_EQ(anisotropicAlpha(0.25f, 1.0f).y, 1e-3f);  // kept above 0
}

// ---- Fresnel with an index of refraction ------------------------------------------------------------

// Fresnel's equations in double, from n1 = 1 into n2 = η (Hecht, Optics, §4.6.2), written here.
struct Polarized {
    double s, p;
};
Polarized fresnelReference(double thetaI, double eta) {
    const double ci = std::cos(thetaI), st = std::sin(thetaI) / eta, ct = std::sqrt(1 - st * st);
    const double rs = (ci - eta * ct) / (ci + eta * ct), rp = (ct - eta * ci) / (ct + eta * ci);
    return {rs * rs, rp * rp};
}

TEST(FresnelPolarized, MatchesFresnelsEquations) {
    for (double eta : {1.33, 1.5, 2.42}) {
        for (double degrees = 0; degrees < 90; degrees += 7.5) {
            const double theta = degrees * pi / 180;
            const Polarized expected = fresnelReference(theta, eta);
            const FresnelPolarized<float> r = fresnelPolarized(float(std::cos(theta)), float(eta));
            EXPECT_NEAR(r.s, expected.s, 1e-5) << eta << " " << degrees;
            EXPECT_NEAR(r.p, expected.p, 1e-5) << eta << " " << degrees;
            // The unpolarised mean is Cook & Torrance's closed form.
            EXPECT_NEAR(fresnelExact(float(std::cos(theta)), float(eta)), (expected.s + expected.p) / 2,
                        1e-5);
        }
    }
}

// Brewster's angle tan θ_B = η: the parallel polarisation is not reflected at all.
TEST(FresnelPolarized, BrewstersAngleReflectsNoParallelLight) {
    for (double eta : {1.33, 1.5}) {
        const double brewster = std::atan(eta);
        const FresnelPolarized<float> r = fresnelPolarized(float(std::cos(brewster)), float(eta));
        EXPECT_NEAR(r.p, 0.0f, 1e-6f);
        EXPECT_GT(r.s, 0.05f);
    }
}

// Head-on both polarisations reflect F0 = ((n1 − n2)/(n1 + n2))²: 0.04 for glass, about 0.02 for water.
TEST(FresnelPolarized, NormalIncidenceIsTheF0OfTheIor) {
    EXPECT_NEAR(f0FromEta(1.5f), 0.04f, 1e-7f);
    EXPECT_NEAR(f0FromEta(1.33f), (0.33 / 2.33) * (0.33 / 2.33), 1e-7);
    for (float eta : {1.33f, 1.5f, 2.42f}) {
        const FresnelPolarized<float> r = fresnelPolarized(1.0f, eta);
        EXPECT_NEAR(r.s, f0FromEta(eta), 1e-6f);
        EXPECT_NEAR(r.p, f0FromEta(eta), 1e-6f);
        EXPECT_NEAR(fresnelExact(1.0f, eta), f0FromEta(eta), 1e-6f);
    }
}

// Deck A: "for common glass, 4% of perpendicular incident light is reflected, at 80° about 50%"; the
// exact equations put the half-way point at 82.8° (bisection on the double formula above).
TEST(FresnelPolarized, GlassReflectsHalfNear83Degrees) {
    double lo = 60, hi = 89.9;
    for (int i = 0; i < 60; ++i) {
        const double mid = (lo + hi) / 2;
        const Polarized r = fresnelReference(mid * pi / 180, 1.5);
        ((r.s + r.p) / 2 < 0.5 ? lo : hi) = mid;
    }
    EXPECT_GT(lo, 82.0);
    EXPECT_LT(lo, 83.0);
    EXPECT_NEAR(fresnelExact(float(std::cos(lo * pi / 180)), 1.5f), 0.5f, 1e-4f);
    EXPECT_LT(fresnelExact(float(std::cos(82.0 * pi / 180)), 1.5f), 0.5f);
    EXPECT_GT(fresnelExact(float(std::cos(83.5 * pi / 180)), 1.5f), 0.5f);
}

// A dielectric with an IOR takes the exact Fresnel term at η itself, recording R_s and R_p.
TEST(FresnelPolarized, BrdfUsesTheIorAndRecordsBothPolarisations) {
    PbrMaterial glass;
    glass.ior = 1.7f;
    glass.f0 = vec3(f0FromEta(1.7f));
    const BrdfModel model{NormalDistribution::GGX, FresnelModel::Exact, GeometryTerm::SmithGGX};
    const vec3 n(0, 0, 1), l = glm::normalize(vec3(0.9f, 0, 0.4f)), v = glm::normalize(vec3(-0.9f, 0, 0.4f));
    BrdfRecord record;
    brdfLobes<float>(n, l, v, glass, glass.baseColor, model, nullptr, &record);
    const double thetaI = std::acos(double(record.VdotH));
    const Polarized expected = fresnelReference(thetaI, 1.7);
    EXPECT_NEAR(record.F.x, (expected.s + expected.p) / 2, 1e-5);
    EXPECT_NEAR(record.Rs.y, expected.s, 1e-5);
    EXPECT_NEAR(record.Rp.z, expected.p, 1e-5);
    EXPECT_EQ(record.eta, vec3(1.7f));
}

// ---- The F0 table -----------------------------------------------------------------------------------

// Every row of Real-Time Rendering, 4th ed., table 9.1 (dielectrics, linear F0; a range: its ends) and
// table 9.2 (metals, linear RGB), as printed there and in lighting-deck-C.txt, written out here.
struct PublishedRow {
    std::string_view name;
    double r, g, b;    // metals; dielectrics: r = g = b = the value (the midpoint of a range)
    double low, high;  // dielectric ranges; 0, 0 for one value
    bool metal;
};
constexpr PublishedRow kTable[] = {
    // Table 9.1
    {"water", 0.02, 0.02, 0.02, 0, 0, false},
    {"living-tissue", 0.03, 0.03, 0.03, 0.02, 0.04, false},
    {"skin", 0.028, 0.028, 0.028, 0, 0, false},
    {"eyes", 0.025, 0.025, 0.025, 0, 0, false},
    {"hair", 0.046, 0.046, 0.046, 0, 0, false},
    {"teeth", 0.058, 0.058, 0.058, 0, 0, false},
    {"fabric", 0.048, 0.048, 0.048, 0.04, 0.056, false},
    {"stone", 0.0455, 0.0455, 0.0455, 0.035, 0.056, false},
    {"plastic", 0.045, 0.045, 0.045, 0.04, 0.05, false},
    {"glass", 0.045, 0.045, 0.045, 0.04, 0.05, false},
    {"crystal-glass", 0.06, 0.06, 0.06, 0.05, 0.07, false},
    {"gems", 0.065, 0.065, 0.065, 0.05, 0.08, false},
    {"diamond", 0.165, 0.165, 0.165, 0.13, 0.2, false},
    // Table 9.2
    {"titanium", 0.542, 0.497, 0.449, 0, 0, true},
    {"chromium", 0.549, 0.556, 0.554, 0, 0, true},
    {"iron", 0.562, 0.565, 0.578, 0, 0, true},
    {"nickel", 0.660, 0.609, 0.526, 0, 0, true},
    {"platinum", 0.673, 0.637, 0.585, 0, 0, true},
    {"copper", 0.955, 0.638, 0.538, 0, 0, true},
    {"palladium", 0.733, 0.697, 0.652, 0, 0, true},
    {"mercury", 0.781, 0.780, 0.778, 0, 0, true},
    {"brass", 0.910, 0.778, 0.423, 0, 0, true},
    {"zinc", 0.664, 0.824, 0.850, 0, 0, true},
    {"gold", 1.000, 0.782, 0.344, 0, 0, true},
    {"aluminium", 0.913, 0.922, 0.924, 0, 0, true},
    {"silver", 0.972, 0.960, 0.915, 0, 0, true},
};

// Catches a mistyped value, a missing row, or a dielectric marked as a metal.
TEST(F0Table, EveryRowMatchesRealTimeRenderingTables91And92) {
    for (const PublishedRow& row : kTable) {
        const std::optional<MaterialPreset> preset = findMaterialPreset(row.name);
        ASSERT_TRUE(preset.has_value()) << row.name;
        EXPECT_EQ(preset->metal, row.metal) << row.name;
        EXPECT_NEAR(preset->f0.x, row.r, 1e-6) << row.name;
        EXPECT_NEAR(preset->f0.y, row.g, 1e-6) << row.name;
        EXPECT_NEAR(preset->f0.z, row.b, 1e-6) << row.name;
        EXPECT_NEAR(preset->low, row.low, 1e-6) << row.name;
        EXPECT_NEAR(preset->high, row.high, 1e-6) << row.name;
        if (row.high > 0) {
            EXPECT_NEAR(preset->f0.x, (row.low + row.high) / 2, 1e-6) << row.name;
        }
    }
    EXPECT_EQ(std::size(kTable), kMaterialPresets.size());  // and no row Facet has that the tables lack
}

// ---- The tangent frame (tangent.h) ---------------------------------------------------------------

namespace tangent_test {
using glm::dvec2;
using glm::dvec3;

// A planar triangle with affine uv seen through a perspective camera: the tangent the rasterizer finds
// from one pixel's screen-space derivatives (the neighbours' rays met with the plane, the uv
// derivatives taken here by central differences of the exact uv along the rays) points where the
// triangle's Lengyel tangent (written here in double: T = (e1·Δv2 − e2·Δv1)/(Δu1·Δv2 − Δu2·Δv1))
// does.
TEST(TangentFrame, ScreenDerivativesGiveTheTrianglesLengyelTangent) {
    const dvec3 p[3] = {{-1.0, -0.5, -4.0}, {1.5, -0.2, -5.0}, {0.2, 1.3, -4.5}};
    const dvec2 t[3] = {{0.1, 0.2}, {0.9, 0.35}, {0.3, 0.8}};
    const dvec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
    const dvec2 d1 = t[1] - t[0], d2 = t[2] - t[0];
    const dvec3 lengyel = (e1 * d2.y - e2 * d1.y) / (d1.x * d2.y - d2.x * d1.y);
    const dvec3 n = glm::normalize(glm::cross(e1, e2));
    const dvec3 expected = glm::normalize(lengyel - n * glm::dot(n, lengyel));

    const double k = 0.002;  // a pixel's size per unit depth
    // The uv seen at window position (x, y) (y down): the ray (x·k, −y·k, −1)·s met with the plane.
    const auto uvAt = [&](double x, double y) {
        const dvec3 d(x * k, -y * k, -1.0);
        const dvec3 q = d * (glm::dot(p[0], n) / glm::dot(d, n));
        const dvec3 c = glm::cross(e1, e2);
        const double b1 = glm::dot(glm::cross(q - p[0], e2), c) / glm::dot(c, c);
        const double b2 = glm::dot(glm::cross(e1, q - p[0]), c) / glm::dot(c, c);
        return t[0] + b1 * d1 + b2 * d2;
    };
    const dvec3 P = (p[0] + p[1] + p[2]) / 3.0;
    const double x = P.x / (-P.z) / k, y = -P.y / (-P.z) / k;
    const double h = 1e-3;
    const dvec2 ddx = (uvAt(x + h, y) - uvAt(x - h, y)) / (2 * h);
    const dvec2 ddy = (uvAt(x, y + h) - uvAt(x, y - h)) / (2 * h);

    const vec3 Pf(P), nf(n);
    const ScreenDifferentials<vec3> dP = screenDifferentials<float>(Pf, nf, vec2(float(k)), true);
    const vec3 T = tangentFromDifferentials<float>(dP.dPdx, dP.dPdy, float(ddx.x), float(ddx.y), float(ddy.x),
                                                   float(ddy.y), fallbackTangent<float>(nf));
    const TangentFrame<vec3> frame = orthonormalTangentFrame<float>(nf, T);
    EXPECT_NEAR(frame.T.x, expected.x, 1e-3);
    EXPECT_NEAR(frame.T.y, expected.y, 1e-3);
    EXPECT_NEAR(frame.T.z, expected.z, 1e-3);
    EXPECT_NEAR(glm::dot(frame.B, vec3(glm::cross(n, expected))), 1.0f, 1e-3f);
    // The same formula on the edges (the reference's use) gives Lengyel's tangent itself.
    const vec3 edges = tangentFromDifferentials<float>(vec3(e1), vec3(e2), float(d1.x), float(d1.y),
                                                       float(d2.x), float(d2.y), vec3(0.0f));
    EXPECT_NEAR(glm::length(edges - vec3(lengyel)), 0.0f, 1e-5f);
    // No uv (all derivatives 0): the eye-space x axis projected.
    const vec3 none = tangentFromDifferentials<float>(dP.dPdx, dP.dPdy, 0.0f, 0.0f, 0.0f, 0.0f,
                                                      fallbackTangent<float>(vec3(0.0f, 0.0f, 1.0f)));
    EXPECT_EQ(none, vec3(1.0f, 0.0f, 0.0f));
}
}  // namespace tangent_test

}  // namespace
}  // namespace facet
