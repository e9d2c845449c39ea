// The shading of one fragment, recomputed with the records on: it is the pipeline's output bit for bit
// over every fragment of real renders (every shading frequency and reflection model, fog, textures,
// blends), and its screens show the numbers substituted into the lecture's formulas.
#include "step/shading_view.h"

#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "pipeline/names.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "step/screens.h"

namespace facet::step {
namespace {

// ---- Real renders --------------------------------------------------------------------------------

// Every fragment of a frame traced again as the step mode traces it.
struct ShadingChecker : NullObserver {
    static constexpr bool enabled = true;
    const PreparedScene* prepared = nullptr;
    const PreparedDraw* draw = nullptr;
    std::vector<bool> clipped;       // per triangle of the current draw
    std::vector<bool> swapped;       // per triangle: the setup exchanged v1 and v2
    std::uint64_t fragments = 0;     // traced, the shader having run
    std::uint64_t mismatches = 0;    // the recomputed output is not the pipeline's
    std::uint64_t mixedChecked = 0;  // Gouraud, unclipped: the corners' mix checked
    std::uint64_t mixedWrong = 0;    // … and not what the interpolator gave
    std::uint64_t flatChecked = 0;   // flat, unclipped: the provoking corner's colour checked
    std::uint64_t flatWrong = 0;     // … and not the flat varying, bit for bit
    std::uint64_t longLines = 0;     // screen lines beyond 80 columns
    std::uint64_t mipsMixed = 0;     // trilinear, λ between two mip levels
    std::string trilinearScreen;     // a lighting screen of such a fragment
    std::string firstProblem;

    void onPlannedDraw(const PlannedDraw& call, const PreparedDraw& d) {
        draw = &d;
        (void)call;
        clipped.assign(d.indices.size() / 3, false);
        swapped.assign(d.indices.size() / 3, false);
    }
    void onClipped(std::uint32_t triangle, const ClipPolygon&) { clipped[triangle] = true; }
    void onSetup(std::uint32_t triangle, const WindowTriangle& window, TriangleFate, const TriangleSetup&) {
        const WindowVertex &a = window.vertices[0], &b = window.vertices[1], &c = window.vertices[2];
        // triangle_setup's orient2d: negative areas have v1 and v2 exchanged.
        const std::int64_t area =
            (b.xFixed - a.xFixed) * (c.yFixed - a.yFixed) - (b.yFixed - a.yFixed) * (c.xFixed - a.xFixed);
        swapped[triangle] = area < 0;
    }
    void onFragment(const FragmentEvent& f) {
        if (f.fate == FragmentFate::DepthFailed || f.fate == FragmentFate::Discarded) return;
        std::array<MeshVertex, 3> corners;
        std::array<int, 3> order{0, 1, 2};
        if (swapped[f.triangle]) std::swap(order[1], order[2]);
        for (int k = 0; k < 3; ++k)
            corners[static_cast<std::size_t>(k)] = draw->vertices[draw->indices[3 * f.triangle + order[k]]];
        const int provoking = order[1] == 2 ? 1 : 2;  // the last vertex as submitted
        const ShadingTrace trace = traceShading(draw->uniforms, draw->frequency, f, corners, provoking);
        ++fragments;
        const ShadingTrace::TextureFootprint& map = trace.texture;
        if (map.mapped && map.filter == TextureFilter::Trilinear && map.lod > 0.0f &&
            map.lod < static_cast<float>(map.levels - 1) && ++mipsMixed == 1)
            for (const Screen& screen : shadingScreens(trace))
                if (screen.id == "lighting") trilinearScreen = screen.text;
        if (!trace.matchesPipeline) {
            ++mismatches;
            note(f, "recomputed output differs");
        }
        if (!clipped[f.triangle] && draw->frequency == ShadingFrequency::Gouraud) {
            ++mixedChecked;
            const vec3 error = glm::abs(trace.mixedModulated - trace.fragment.modulatedIn) +
                               glm::abs(trace.mixedAdded - trace.fragment.addedIn);
            const float scale =
                1.0f + glm::length(trace.fragment.modulatedIn) + glm::length(trace.fragment.addedIn);
            if (!trace.weightsMatchCorners || error.x + error.y + error.z > 1e-3f * scale) {
                ++mixedWrong;
                note(f, "the corners' mix is not the interpolated colour");
            }
        }
        if (!clipped[f.triangle] && draw->frequency == ShadingFrequency::Flat) {
            ++flatChecked;
            const VertexLightingRecord& corner = trace.corners[0].lighting;
            if (std::memcmp(&corner.modulated, &trace.fragment.modulatedIn, sizeof(vec3)) != 0 ||
                std::memcmp(&corner.added, &trace.fragment.addedIn, sizeof(vec3)) != 0) {
                ++flatWrong;
                note(f, "the provoking corner's colour is not the flat varying");
            }
        }
        if (fragments % 101 == 0) {
            for (const Screen& screen : shadingScreens(trace)) {
                std::istringstream lines(screen.text);
                for (std::string line; std::getline(lines, line);)
                    if (columnsOf(line) > 80) {
                        ++longLines;
                        if (firstProblem.empty()) firstProblem = "long line: " + line;
                    }
                if (columnsOf(screen.title) > 80) ++longLines;
            }
            (void)toJson(trace).dump();
        }
    }
    void note(const FragmentEvent& f, const char* what) {
        if (firstProblem.empty())
            firstProblem = std::string(what) + " at (" + std::to_string(f.x) + ", " + std::to_string(f.y) +
                           "), triangle " + std::to_string(f.triangle);
    }
};

void traceEveryFragment(Scene scene, ShadingChecker& checker) {
    scene.width = 96;
    scene.height = 72;
    const PreparedScene prepared = prepareScene(scene);
    Framebuffer framebuffer(scene.width, scene.height);
    DrawContext context(1);
    FrameMemory memory;
    checker.prepared = &prepared;
    renderFrame(prepared, framebuffer, context, memory, checker);
}

TEST(ShadingView, RecomputedShadingIsThePipelinesOutputBitForBit) {
    std::uint64_t total = 0;
    // The bundled scenes, then two of the conformance scenes on the shared models (blends, the GL preset).
    std::vector<std::string> scenes{
        "models/example-scene.json", "models/lighting-scene.json",
        "models/fog-and-glass.json", "models/intersecting-quads.json",
        "models/shadows.json",       "tests/conformance/scenes/facet-emission-map-cubes.json"};
    if (std::filesystem::exists(FACET_SHARED_MODELS)) {
        scenes.push_back("tests/conformance/scenes/facet-blend-modes-spheres.json");
        scenes.push_back("tests/conformance/scenes/gl-fog-exp-transparent-teapots.json");
    }
    for (const std::string& name : scenes) {
        const Scene original = loadScene(std::filesystem::path(FACET_SOURCE_DIR) / name);
        for (const ReflectionModel model :
             {ReflectionModel::Phong, ReflectionModel::BlinnPhong, ReflectionModel::CookTorrance}) {
            for (const ShadingFrequency frequency :
                 {ShadingFrequency::Phong, ShadingFrequency::Gouraud, ShadingFrequency::Flat}) {
                Scene scene = original;
                for (ObjectSpec& object : scene.objects) {
                    object.reflection = model;
                    object.shading = frequency;
                }
                // Every fog mode and distance across the variants.
                if (scene.fog.mode == FogMode::None) {
                    scene.fog.mode = static_cast<FogMode>(1 + (static_cast<int>(model) + 2) % 3);
                    scene.fog.distance =
                        frequency == ShadingFrequency::Flat ? FogDistance::Radial : FogDistance::EyeDepth;
                    scene.fog.density = 0.15f;
                }
                if (model == ReflectionModel::Phong && frequency == ShadingFrequency::Gouraud)
                    scene.lighting.preset = LightingPreset::GL;  // clamped colours
                if (model == ReflectionModel::CookTorrance && frequency == ShadingFrequency::Gouraud)
                    scene.lighting.preset = LightingPreset::Lecture;  // the notes' BRDF, N·V clamped
                const std::string what =
                    name + ", " + std::string(nameOf(model)) + ", " + std::string(nameOf(frequency));
                ShadingChecker checker;
                traceEveryFragment(scene, checker);
                EXPECT_GT(checker.fragments, 500u) << what;
                EXPECT_EQ(checker.mismatches, 0u) << what << ": " << checker.firstProblem;
                EXPECT_EQ(checker.mixedWrong, 0u) << what << ": " << checker.firstProblem;
                EXPECT_EQ(checker.flatWrong, 0u) << what << ": " << checker.firstProblem;
                EXPECT_EQ(checker.longLines, 0u) << what << ": " << checker.firstProblem;
                if (frequency == ShadingFrequency::Gouraud) {
                    EXPECT_GT(checker.mixedChecked, 100u) << what;
                }
                if (frequency == ShadingFrequency::Flat) {
                    EXPECT_GT(checker.flatChecked, 100u) << what;
                }
                total += checker.fragments;
            }
        }
    }
    EXPECT_GT(total, 50000u);
}

// Trilinear filtering reads the fragment's texture-coordinate derivatives: the recomputed shading
// samples the same mip levels as the pipeline (it sampled level 0 when the trace lacked them), and the
// screen shows the footprint ρ and the level of detail λ.
TEST(ShadingView, TrilinearFragmentsSampleThePipelinesMipLevels) {
    Scene scene =
        sceneForModel(std::filesystem::path(FACET_SOURCE_DIR) / "models/spot/spot_triangulated.obj");
    scene.textures.filter = TextureFilter::Trilinear;
    ShadingChecker checker;
    traceEveryFragment(scene, checker);
    EXPECT_GT(checker.fragments, 500u);
    EXPECT_GT(checker.mipsMixed, 100u) << "a 1024-texel map on a 96-pixel cow is minified";
    EXPECT_EQ(checker.mismatches, 0u) << checker.firstProblem;
    for (const char* shown :
         {"Filter: trilinear", "∂uv/∂x = (", "ρ = max(", "lod = log2 ρ = ", "t = lod − ⌊lod⌋"})
        EXPECT_NE(checker.trilinearScreen.find(shown), std::string::npos) << shown << " missing from:\n"
                                                                          << checker.trilinearScreen;
}

// ---- A hand-built fragment -------------------------------------------------------------------------

// A point light at distance 2 from the point, c0 = 1, c1 = 0.5, c2 = 0.25: att = 1/3; N = (0, 0, 1),
// L = (0.6, 0, 0.8), V = (0, 0, 1), so N·L = 0.8, N·H = √0.9 and with n = 8, spec = 0.9⁴ = 0.6561.
SurfaceUniforms handBuiltUniforms() {
    SurfaceUniforms u;
    u.globalAmbient = vec3(0.2f);
    u.lightCount = 1;
    LightParams& light = u.lights[0];
    light.kind = LightKind::Point;
    light.position = vec3(1.2f, 0.0f, -0.4f);  // P + 2·(0.6, 0, 0.8)
    light.c0 = 1.0f;
    light.c1 = 0.5f;
    light.c2 = 0.25f;
    light.diffuse = vec3(1.0f, 0.5f, 0.25f);
    light.specular = vec3(1.0f);
    u.material.ambient = vec3(0.1f, 0.2f, 0.3f);
    u.material.diffuse = vec3(0.5f, 0.25f, 1.0f);
    u.material.specular = vec3(0.5f);
    u.material.shininess = 8.0f;
    u.reflection = ReflectionModel::BlinnPhong;
    u.precision = MathPrecision::Exact;
    u.fog.mode = FogMode::Linear;
    u.fog.start = 1.0f;
    u.fog.end = 5.0f;  // z = 2: f = 0.75
    u.fog.color = vec3(0.5f);
    u.opacity = 0.5f;
    u.blend = BlendMode::PremultipliedOver;
    return u;
}

// The fragment at P = (0, 0, −2) facing the eye, shaded per pixel as the pipeline would.
FragmentEvent handBuiltFragment(const SurfaceUniforms& u) {
    const PerPixelSurface::VaryingsT<float> in{vec3(0.0f, 0.0f, -2.0f), vec3(0.0f, 0.0f, 1.0f), vec2(0.0f)};
    FragmentEvent f;
    f.x = 5;
    f.y = 7;
    f.varyingCount = kVaryingFloatCount<PerPixelSurface::VaryingsT<float>>;
    std::memcpy(f.varyings.data(), &in, sizeof in);
    f.shaded = SurfaceShader<ShadingFrequency::Phong>::fragment(in, u);
    return f;
}

std::string screenText(const std::vector<Screen>& screens, const std::string& id) {
    for (const Screen& screen : screens)
        if (screen.id == id) return screen.title + "\n" + screen.text;
    return "";
}

TEST(ShadingView, ScreensShowTheNumbersSubstituted) {
    const SurfaceUniforms u = handBuiltUniforms();
    const ShadingTrace trace = traceShading(u, ShadingFrequency::Phong, handBuiltFragment(u), {}, 2);
    EXPECT_TRUE(trace.matchesPipeline);
    const std::vector<Screen> screens = shadingScreens(trace);
    ASSERT_EQ(screens.size(), 3u);
    const std::string lighting = screenText(screens, "lighting");
    EXPECT_NE(lighting.find("att = 1/(c0 + c1·d + c2·d²) = 1/(1 + 0.5·2 + 0.25·2²) = 0.3333"),
              std::string::npos)
        << lighting;
    EXPECT_NE(lighting.find("d = |p_light − P| = 2\n"), std::string::npos) << lighting;
    EXPECT_NE(lighting.find("N·L = 0.8\n"), std::string::npos) << lighting;
    EXPECT_NE(lighting.find("H = normalize(L + V) = (0.3162, 0, 0.9487)"), std::string::npos) << lighting;
    EXPECT_NE(lighting.find("spec = max(N·H, 0)^e = max(0.9487, 0)^8 = 0.6561"), std::string::npos)
        << lighting;
    // diffuse = att·spot·max(N·L,0)·l_d⊗m_d = 1/3·0.8·(0.5, 0.125, 0.25).
    EXPECT_NE(lighting.find("= 0.3333·1·max(0.8, 0)·RGB(1, 0.5, 0.25)⊗RGB(0.5, 0.25, 1)"), std::string::npos)
        << lighting;
    EXPECT_NE(lighting.find("= RGB(0.1333, 0.03333, 0.06667)"), std::string::npos) << lighting;
    EXPECT_NE(lighting.find("  a_global ⊗ m_a = RGB(0.2, 0.2, 0.2) ⊗ RGB(0.1, 0.2, 0.3)\n"
                            "                 = RGB(0.02, 0.04, 0.06)\n"),
              std::string::npos)
        << lighting;

    const std::string fog = screenText(screens, "fog");
    EXPECT_NE(fog.find("z = |z_eye| (the eye-space depth) = |-2| = 2"), std::string::npos) << fog;
    EXPECT_NE(fog.find("f = (end − z)/(end − start) = (5 − 2)/(5 − 1) = 0.75"), std::string::npos) << fog;
    EXPECT_NE(fog.find("c_p = f·c_s + (1 − f)·c_fog = 0.75·"), std::string::npos) << fog;

    const std::string output = screenText(screens, "output");
    EXPECT_NE(output.find("premultiplied alpha: the shader writes (α·c, α)"), std::string::npos) << output;
    EXPECT_NE(output.find("α·c = 0.5·"), std::string::npos) << output;
    EXPECT_NE(output.find("the same, bit for bit"), std::string::npos) << output;

    const nlohmann::json json = toJson(trace);
    EXPECT_FLOAT_EQ(json["lighting"]["lights"][0]["attenuation"].get<float>(), 1.0f / 3.0f);
    EXPECT_FLOAT_EQ(json["fog"]["f"].get<float>(), 0.75f);
    EXPECT_EQ(json["output"]["matchesPipeline"], true);
}

// The lecture preset's Cook-Torrance on the lighting screen: the form in the notes' symbols, then the
// numbers (F at N·L = 0.8, the denominator π·N·V·N·L = π·1·0.8, the metal tint), and a back-facing point
// says N·V is clamped. Catches: the screen still writing Facet's 4(N·L)(N·V) or V·H under the lecture
// fields, the tint or the clamp left off the screen, or the lecture screens breaking the 80 columns.
TEST(ShadingView, LectureFormOnTheLightingScreen) {
    SurfaceUniforms u = handBuiltUniforms();
    u.reflection = ReflectionModel::CookTorrance;
    u.pbr.baseColor = vec3(0.5f, 0.25f, 1.0f);
    u.pbr.metalness = 0.5f;
    u.pbr.roughness = 0.5f;
    u.brdf.fresnelCosine = FresnelCosine::NdotL;
    u.brdf.denominator = MicrofacetDenominator::Pi;
    u.brdf.metal = MetalBlend::TintedLobe;
    u.twoSidedFlip = false;
    u.clampNdotV = true;
    u.clampColor = true;
    const ShadingTrace trace = traceShading(u, ShadingFrequency::Phong, handBuiltFragment(u), {}, 2);
    EXPECT_TRUE(trace.matchesPipeline);
    const std::string lighting = screenText(shadingScreens(trace), "lighting");
    for (const char* shown :
         {"f_r = metalness·D·F·G/(π(N·V)(N·L))·c_base",
          "+ (1 − metalness)·(D·F·G/(π(N·V)(N·L)) + (1 − F)·c_base/π)", "F = F0 + (1 − F0)(1 − N·L)^5",
          "(1 − F0)(1 − 0.8)^5", "F0 = F0_dielectric = RGB(0.04, 0.04, 0.04)",
          "/(π·1·0.8) = ", "tint = mix(1, c_base, metalness) = RGB(0.75, 0.625, 1)"})
        EXPECT_NE(lighting.find(shown), std::string::npos) << shown << " missing from:\n" << lighting;
    EXPECT_EQ(lighting.find("4(N·L)(N·V)"), std::string::npos) << lighting;
    std::istringstream lines(lighting);
    for (std::string line; std::getline(lines, line);)
        EXPECT_LE(columnsOf(line), 80u) << line;

    // The same point seen from below: N·V < 0, clamped, no diffuse or specular light.
    const PerPixelSurface::VaryingsT<float> below{vec3(0.0f, 0.0f, -2.0f), vec3(0.0f, 0.0f, -1.0f),
                                                  vec2(0.0f)};
    FragmentEvent f = handBuiltFragment(u);
    std::memcpy(f.varyings.data(), &below, sizeof below);
    f.shaded = SurfaceShader<ShadingFrequency::Phong>::fragment(below, u);
    const ShadingTrace under = traceShading(u, ShadingFrequency::Phong, f, {}, 2);
    EXPECT_TRUE(under.matchesPipeline);
    const std::string underside = screenText(shadingScreens(under), "lighting");
    EXPECT_NE(underside.find("N·V < 0: the viewer sees the underside; N·V is clamped to 0"),
              std::string::npos)
        << underside;
    EXPECT_EQ(toJson(under)["lighting"]["underside"], true);
}

// A triangle between the point and the light: the lighting screen says the ray to the light is blocked,
// v = 0 in the diffuse and specular terms, and the terms are 0 (the ambient term stays).
TEST(ShadingView, ShadowRayOnTheScreen) {
    SurfaceUniforms u = handBuiltUniforms();
    u.fog.mode = FogMode::None;
    // The light is at P + 2·L = (1.2, 0, −0.4); the plane z = −1.2 lies across the way.
    const vec3 corners[] = {vec3(-5.0f, -5.0f, -1.2f), vec3(5.0f, -5.0f, -1.2f), vec3(0.0f, 5.0f, -1.2f)};
    const std::uint32_t indices[] = {0, 1, 2};
    const RayMesh mesh{corners, indices, true};
    const RayScene rays(std::span<const RayMesh>(&mesh, 1));
    SceneShadows shadows;
    shadows.rays = &rays;
    shadows.rayOffset = 1e-4f;
    shadows.lights[0].method = ShadowMethod::Ray;
    u.shadows = &shadows;
    const ShadingTrace trace = traceShading(u, ShadingFrequency::Phong, handBuiltFragment(u), {}, 2);
    EXPECT_TRUE(trace.matchesPipeline);
    const std::string lighting = screenText(shadingScreens(trace), "lighting");
    EXPECT_NE(lighting.find("shadow: another surface blocks the light from P: v = 0"), std::string::npos)
        << lighting;
    EXPECT_NE(lighting.find("diffuse = att·spot·v·max(N·L,0)·l_d⊗m_d\n"
                            "          = 0.3333·1·0·max(0.8, 0)"),
              std::string::npos)
        << lighting;
    EXPECT_EQ(toJson(trace)["lighting"]["lights"][0]["visibility"].get<float>(), 0.0f);
    // The plane moved behind the light: nothing blocks it.
    const vec3 beyond[] = {vec3(-5.0f, -5.0f, 0.5f), vec3(5.0f, -5.0f, 0.5f), vec3(0.0f, 5.0f, 0.5f)};
    const RayMesh behind{beyond, indices, true};
    const RayScene clear(std::span<const RayMesh>(&behind, 1));
    shadows.rays = &clear;
    const std::string lit = screenText(
        shadingScreens(traceShading(u, ShadingFrequency::Phong, handBuiltFragment(u), {}, 2)), "lighting");
    EXPECT_NE(lit.find("shadow: nothing blocks the light from P (or it casts none): v = 1"),
              std::string::npos)
        << lit;
}

TEST(ShadingView, PhongReflectionAndSpotConeOnTheScreen) {
    SurfaceUniforms u = handBuiltUniforms();
    u.reflection = ReflectionModel::Phong;
    u.lights[0].kind = LightKind::Spot;
    u.lights[0].spotDirection = vec3(0.0f, 0.0f, -1.0f);  // −L·s = 0.8
    u.lights[0].spotCutoffDegrees = 45.0f;
    u.lights[0].spotExponent = 2.0f;
    u.fog.mode = FogMode::None;
    const ShadingTrace trace = traceShading(u, ShadingFrequency::Phong, handBuiltFragment(u), {}, 2);
    const std::string lighting = screenText(shadingScreens(trace), "lighting");
    EXPECT_NE(lighting.find("R = 2(N·L)N − L = (-0.6, 0, 0.8)"), std::string::npos) << lighting;
    EXPECT_NE(lighting.find("spec = max(R·V, 0)^e = max(0.8, 0)^8 = 0.1678"), std::string::npos) << lighting;
    EXPECT_NE(lighting.find("cos angle = −L·s = 0.8"), std::string::npos) << lighting;
    EXPECT_NE(lighting.find("inside the cone: spot = max(−L·s, 0)^e = max(0.8, 0)^2 = 0.64"),
              std::string::npos)
        << lighting;
    EXPECT_NE(screenText(shadingScreens(trace), "fog").find("Fog is off"), std::string::npos);
}

// Cook-Torrance with the Gaussian D and the exact Fresnel of an IOR: the lighting screen shows c, θ_h,
// η, R_s and R_p with their numbers, and they are the formulas' (checked against the record's own).
TEST(ShadingView, GaussianDistributionAndPolarisedFresnelOnTheScreen) {
    SurfaceUniforms u = handBuiltUniforms();
    u.reflection = ReflectionModel::CookTorrance;
    u.brdf.distribution = NormalDistribution::Gaussian;
    u.brdf.fresnel = FresnelModel::Exact;
    u.pbr.ior = 1.5f;
    u.pbr.f0 = vec3(f0FromEta(1.5f));
    u.pbr.roughness = 0.5f;
    const ShadingTrace trace = traceShading(u, ShadingFrequency::Phong, handBuiltFragment(u), {}, 2);
    EXPECT_TRUE(trace.matchesPipeline);
    const std::string lighting = screenText(shadingScreens(trace), "lighting");
    EXPECT_NE(lighting.find("(Gaussian)"), std::string::npos) << lighting;
    const BrdfRecord& b = trace.fragment.lighting.lighting.lights[0].brdf;
    EXPECT_NEAR(b.gaussianC, gaussianNormalizationExact(0.25), 1e-3);
    EXPECT_NE(lighting.find("η = n2/n1 = 1.5 (n1 = 1, air)"), std::string::npos) << lighting;
    EXPECT_NE(lighting.find("F0_dielectric = ((n1 − n2)/(n1 + n2))² = ((1 − 1.5)/(1 + 1.5))² = 0.04"),
              std::string::npos)
        << lighting;
    EXPECT_NE(lighting.find("R_s = ("), std::string::npos) << lighting;
    EXPECT_NEAR((b.Rs.x + b.Rp.x) / 2, b.F.x, 1e-6f);
    EXPECT_GT(b.Rs.x, b.Rp.x);
    std::istringstream text(lighting);
    for (std::string line; std::getline(text, line);)
        EXPECT_LE(columnsOf(line), 80u) << line;
}

// The environment's reflection on the lighting screen: R, (u, v), the texel, the weight and the term,
// with the numbers; the recomputed output is still the pipeline's.
TEST(ShadingView, EnvironmentReflectionOnTheScreen) {
    Texture map;  // 4×2: the lower row dark, the upper row (v > ½) by column
    map.width = 4;
    map.height = 2;
    map.texels = {vec4(0.1f, 0.2f, 0.3f, 1),
                  vec4(0.2f, 0.2f, 0.3f, 1),
                  vec4(0.3f, 0.2f, 0.3f, 1),
                  vec4(0.4f, 0.2f, 0.3f, 1),
                  vec4(0.0f),
                  vec4(0.0f),
                  vec4(0.0f),
                  vec4(0.0f)};
    SurfaceUniforms u = handBuiltUniforms();
    u.fog.mode = FogMode::None;
    u.environment.map = &map;
    const ShadingTrace trace = traceShading(u, ShadingFrequency::Phong, handBuiltFragment(u), {}, 2);
    EXPECT_TRUE(trace.matchesPipeline);
    const std::string lighting = screenText(shadingScreens(trace), "lighting");
    // Head-on at P = (0, 0, −2), N = V = +z: R = +z, behind the eye, at the seam (u = 0 or 1), v = ½.
    EXPECT_NE(lighting.find("R = 2(N·V)N − V, N = (0, 0, 1), V = ("), std::string::npos) << lighting;
    EXPECT_NE(lighting.find("    = (0, 0, 1) (eye space)"), std::string::npos) << lighting;
    EXPECT_NE(lighting.find("weight w = m_s = RGB(0.5, 0.5, 0.5)"), std::string::npos) << lighting;
    EXPECT_NE(lighting.find("specular + reflection ="), std::string::npos) << lighting;
    const EnvironmentRecord& e = trace.fragment.environment;
    EXPECT_TRUE(e.used);
    EXPECT_NEAR(e.uv.x, 1.0f, 1e-6f);
    EXPECT_NEAR(e.uv.y, 0.5f, 1e-6f);  // halfway between the two rows' centres
    // The seam: columns 3 and 0 (0.4 and 0.1), half each, and half of the dark lower row: 0.125.
    EXPECT_NEAR(e.color.r, 0.125f, 1e-6f);
    EXPECT_NEAR(e.term.r, 0.0625f, 1e-6f);
    for (const Screen& screen : shadingScreens(trace)) {
        std::size_t start = 0;
        while (start <= screen.text.size()) {
            const std::size_t end = std::min(screen.text.find('\n', start), screen.text.size());
            EXPECT_LE(columnsOf(screen.text.substr(start, end - start)), 80u)
                << screen.text.substr(start, end - start);
            start = end + 1;
        }
    }
}

// Height fog's screen: the formula, then τ and f with the numbers.
TEST(ShadingView, HeightFogOnTheScreen) {
    SurfaceUniforms u = handBuiltUniforms();
    u.fog.mode = FogMode::Height;
    u.fog.density = 0.5f;
    u.fog.falloff = 0.0f;  // uniform density: τ = a·d = 0.5·2 = 1
    u.fog.eyeHeight = 1.0f;
    const ShadingTrace trace = traceShading(u, ShadingFrequency::Phong, handBuiltFragment(u), {}, 2);
    EXPECT_TRUE(trace.matchesPipeline);
    const std::string fog = screenText(shadingScreens(trace), "fog");
    EXPECT_NE(fog.find("density(h) = a·e^(−b·(h − h0))"), std::string::npos) << fog;
    EXPECT_NE(fog.find("a = 0.5, b = 0, h0 = 0"), std::string::npos) << fog;
    EXPECT_NE(fog.find("d = |P_eye| = |(0, 0, -2)| = 2"), std::string::npos) << fog;
    EXPECT_NE(fog.find("    = 1\n"), std::string::npos) << fog;
    EXPECT_NE(fog.find("f = e^(−τ) = 0.3679"), std::string::npos) << fog;
    EXPECT_NEAR(trace.fragment.output.fog.f, std::exp(-1.0f), 1e-6f);
}

}  // namespace
}  // namespace facet::step
