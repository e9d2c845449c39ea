// Rendering whole scenes through the renderer: hand-computed pixels, and every bundled model.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <vector>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "pipeline/color.h"
#include "render/renderer.h"
#include "support/interleaved_quads.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

using testing_support::headOnScene;
using testing_support::interleavedQuadsScene;
using testing_support::kSquareObj;
using testing_support::opaqueVertexCount;
using testing_support::TempFolder;
using testing_support::writeInterleavedQuads;

LinearImage renderScene(const Scene& scene) {
    const PreparedScene prepared = prepareScene(scene);
    Framebuffer framebuffer(scene.width, scene.height);
    DrawContext scratch;
    renderFrame(prepared, framebuffer, scratch);
    return toImage(framebuffer);
}

// A textured unit square facing +z whose material "t" is `mtlBody` (naming `texel.png`), its 2×2
// texture all `texel`; the path of the OBJ.
std::filesystem::path texturedSquare(const TempFolder& dir, vec4 texel, const std::string& mtlBody) {
    LinearImage texture;
    texture.width = texture.height = 2;
    texture.pixels.assign(4, texel);
    writeImage(dir.path() / "texel.png", texture);
    dir.write("square.mtl", "newmtl t\n" + mtlBody);
    return dir.write("square.obj",
                     std::string("mtllib square.mtl\nusemtl t\n") +
                         "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                         "vn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/4/1\n");
}

// c = k_d·(N·L) + k_s·(N·H)^n with N = L = V = H = +z at the centre: k_d + k_s, both decoded from sRGB.
TEST(Render, HeadOnSquareHasTheHandComputedColour) {
    TempFolder dir;
    const auto obj = dir.write("square.obj", std::string("mtllib square.mtl\nusemtl grey\n") + kSquareObj);
    dir.write("square.mtl", "newmtl grey\nKa 0 0 0\nKd 0.5 0.25 0.75\nKs 0.2 0.2 0.2\nNs 10\n");
    const LinearImage image = renderScene(headOnScene(obj));
    const vec4 centre = image.at(32, 24);
    const float ks = srgbToLinear(0.2f);
    EXPECT_NEAR(centre.r, srgbToLinear(0.5f) + ks, 1e-4f);
    EXPECT_NEAR(centre.g, srgbToLinear(0.25f) + ks, 1e-4f);
    EXPECT_NEAR(centre.b, srgbToLinear(0.75f) + ks, 1e-4f);
    EXPECT_EQ(centre.a, 1.0f);
    // The corner shows the background (default, decoded from sRGB).
    const Scene defaults;
    EXPECT_NEAR(image.at(0, 0).r, srgbToLinear(defaults.background.r), 1e-6f);
    EXPECT_NEAR(image.at(0, 0).b, srgbToLinear(defaults.background.b), 1e-6f);
}

TEST(Render, LightFromBehindLeavesOnlyAmbientAndEmission) {
    TempFolder dir;
    const auto obj = dir.write("square.obj", std::string("mtllib square.mtl\nusemtl glow\n") + kSquareObj);
    dir.write("square.mtl", "newmtl glow\nKa 1 1 1\nKd 0.5 0.5 0.5\nKs 1 1 1\nKe 0.1 0.2 0.3\n");
    Scene scene = headOnScene(obj);
    scene.lights[0].direction = vec3(0, 0, 1);  // travelling towards the viewer: lights the back
    scene.ambientLight = vec3(0.5f);
    const vec4 centre = renderScene(scene).at(32, 24);
    // c = k_e + a_global ⊗ k_a: no diffuse, no specular (N·L < 0).
    EXPECT_NEAR(centre.r, srgbToLinear(0.1f) + srgbToLinear(0.5f), 1e-5f);
    EXPECT_NEAR(centre.g, srgbToLinear(0.2f) + srgbToLinear(0.5f), 1e-5f);
    EXPECT_NEAR(centre.b, srgbToLinear(0.3f) + srgbToLinear(0.5f), 1e-5f);
}

// The GL preset takes colours as given (no sRGB decoding) and writes them without encoding, as
// OpenGL 1.x does: the centre is k_d exactly, and its 8-bit code is round(255·c).
TEST(Render, GlPresetUsesColoursAsGivenAndWritesThemUnencoded) {
    TempFolder dir;
    const auto obj = dir.write("square.obj", std::string("mtllib square.mtl\nusemtl grey\n") + kSquareObj);
    dir.write("square.mtl", "newmtl grey\nKa 0 0 0\nKd 0.5 0.25 0.6\nKs 0 0 0\n");
    Scene scene = headOnScene(obj);
    scene.lighting.preset = LightingPreset::GL;
    const PreparedScene prepared = prepareScene(scene);
    EXPECT_EQ(prepared.encoding, kGlEncoding);  // linear codes, rounded half to even as Mesa rounds
    EXPECT_EQ(prepared.draws.front().frequency, ShadingFrequency::Gouraud);  // OpenGL 1.x's default
    const vec4 centre = renderScene(scene).at(32, 24);
    EXPECT_NEAR(centre.r, 0.5f, 1e-6f);
    EXPECT_NEAR(centre.g, 0.25f, 1e-6f);
    EXPECT_NEAR(centre.b, 0.6f, 1e-6f);
    EXPECT_EQ(encodeChannel(centre.g, prepared.encoding), 64);  // 0.25 · 255 = 63.75
    EXPECT_EQ(encodeChannel(centre.g, kSrgbEncoding), 137);
}

// A spot light at (0, 0, 2) aimed at the square's centre with a 10° cutoff lights the centre
// (attenuated by 1/(c0 + c1·d + c2·d²) at d = 2) and leaves a point 0.9 from the centre (24° off the
// axis) dark.
TEST(Render, SpotLightConeAndAttenuation) {
    TempFolder dir;
    const auto obj = dir.write("square.obj", std::string("mtllib square.mtl\nusemtl white\n") + kSquareObj);
    dir.write("square.mtl", "newmtl white\nKa 0 0 0\nKd 1 1 1\nKs 0 0 0\n");
    Scene scene = headOnScene(obj);
    scene.lighting.preset = LightingPreset::GL;  // colours as given: the numbers stay readable
    LightSpec spot;
    spot.type = LightKind::Spot;
    spot.position = vec3(0, 0, 2);
    spot.direction = vec3(0, 0, -1);
    spot.spotCutoffDegrees = 10.0f;
    spot.attenuation = vec3(0.5f, 0.25f, 0.125f);  // 1/(0.5 + 0.5 + 0.5) at d = 2
    scene.lights = {spot};
    scene.lighting.shading = ShadingFrequency::Phong;  // the cone is narrower than the square's triangles
    const LinearImage image = renderScene(scene);
    EXPECT_NEAR(image.at(32, 24).r, 1.0f / 1.5f, 2e-3f);  // the pixel centre is a hair off the axis
    // Pixel (44, 24) is about 0.9 units right of the centre on the square (camera at 5, fovy 40).
    EXPECT_EQ(image.at(44, 24).r, 0.0f);
    EXPECT_EQ(image.at(44, 24).g, 0.0f);
}

// Flat shading lights each triangle once, with its face normal: vertex normals that lean outwards do
// not matter, and with no specular term every pixel of a square facing the light is k_d.
TEST(Render, FlatShadingUsesTheFaceNormal) {
    TempFolder dir;
    const auto obj = dir.write("square.obj",
                               "mtllib square.mtl\nusemtl grey\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                               "vn -1 -1 1\nvn 1 -1 1\nvn 1 1 1\nvn -1 1 1\nf 1//1 2//2 3//3 4//4\n");
    dir.write("square.mtl", "newmtl grey\nKa 0 0 0\nKd 0.5 0.5 0.5\nKs 0 0 0\n");
    Scene scene = headOnScene(obj);
    scene.lighting.shading = ShadingFrequency::Flat;
    const LinearImage flat = renderScene(scene);
    int covered = 0;
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x)
            if (flat.at(x, y).g > 0.1f) {
                ++covered;
                ASSERT_FLOAT_EQ(flat.at(x, y).g, srgbToLinear(0.5f)) << x << ", " << y;
            }
    EXPECT_GT(covered, 300);
    // Gouraud with the leaning normals is darker towards the corners.
    scene.lighting.shading = ShadingFrequency::Gouraud;
    const LinearImage smooth = renderScene(scene);
    EXPECT_LT(smooth.at(22, 14).g, srgbToLinear(0.5f) * 0.9f);
}

// Three overlapping half-transparent quads at different depths, facing the camera: with sorting, every
// order of submission gives the colour of the over operator applied back to front,
//   c = α_n·c_n + (1 − α_n)·(α_m·c_m + (1 − α_m)·(α_f·c_f + (1 − α_f)·c_background));
// without sorting, an order that is not back to front gives another colour. The gl preset keeps the
// numbers as written; each quad's colour is its emission alone.
struct TransparentQuad {
    const char* name;
    float z;
    vec3 color;
    float alpha;
};

// A 2×2 quad whose colour is its emission alone, at opacity `alpha`; its left edge at depth zLeft, its
// right edge at zRight (equal: facing the camera).
std::filesystem::path writeEmissiveQuad(TempFolder& dir, const std::string& name, float zLeft, float zRight,
                                        vec3 color, float alpha) {
    dir.write(name + ".mtl", "newmtl m\nKa 0 0 0\nKd 0 0 0\nKs 0 0 0\nKe " + std::to_string(color.r) + " " +
                                 std::to_string(color.g) + " " + std::to_string(color.b) + "\nd " +
                                 std::to_string(alpha) + "\n");
    const std::string zl = std::to_string(zLeft), zr = std::to_string(zRight);
    return dir.write(name + ".obj", "mtllib " + name + ".mtl\nusemtl m\nv -1 -1 " + zl + "\nv 1 -1 " + zr +
                                        "\nv 1 1 " + zr + "\nv -1 1 " + zl + "\nf 1 2 3 4\n");
}

TEST(Render, TransparentQuadsGiveTheOverOperatorInEveryOrderWhenSorted) {
    TempFolder dir;
    const TransparentQuad quads[3] = {{"far", -1.0f, vec3(1.0f, 0.0f, 0.0f), 0.5f},
                                      {"middle", 0.0f, vec3(0.0f, 1.0f, 0.0f), 0.25f},
                                      {"near", 1.0f, vec3(0.0f, 0.0f, 1.0f), 0.75f}};
    std::filesystem::path files[3];
    for (int k = 0; k < 3; ++k)
        files[k] =
            writeEmissiveQuad(dir, quads[k].name, quads[k].z, quads[k].z, quads[k].color, quads[k].alpha);
    vec3 expected(0.0f);  // the black background, then over, back to front
    for (const TransparentQuad& q : quads)
        expected = q.alpha * q.color + (1.0f - q.alpha) * expected;

    int order[3] = {0, 1, 2};
    int unsortedWrong = 0;
    do {
        Scene scene = headOnScene(files[0]);
        scene.lighting.preset = LightingPreset::GL;
        scene.background = vec4(0.0f, 0.0f, 0.0f, 1.0f);
        scene.camera.near = 0.5f;
        scene.camera.far = 20.0f;
        scene.objects.clear();
        for (int k : order) {
            ObjectSpec object;
            object.model = files[k];
            scene.objects.push_back(object);
        }
        const vec4 sorted = renderScene(scene).at(32, 24);
        EXPECT_NEAR(sorted.r, expected.r, 1e-6f) << order[0] << order[1] << order[2];
        EXPECT_NEAR(sorted.g, expected.g, 1e-6f) << order[0] << order[1] << order[2];
        EXPECT_NEAR(sorted.b, expected.b, 1e-6f) << order[0] << order[1] << order[2];

        scene.transparency.mode = TransparencyMode::Unsorted;
        const vec4 unsorted = renderScene(scene).at(32, 24);
        const bool backToFront = order[0] == 0 && order[1] == 1 && order[2] == 2;
        const float error = glm::length(vec3(unsorted) - expected);
        if (backToFront) {
            EXPECT_LT(error, 1e-6f);
        } else {
            EXPECT_GT(error, 0.01f) << "submitted " << order[0] << order[1] << order[2] << ", drawn unsorted";
            ++unsortedWrong;
        }
    } while (std::next_permutation(order, order + 3));
    EXPECT_EQ(unsortedWrong, 5);
}

// "gamma": {"decode_inputs": false} reads colours as linear values; the chosen curve encodes the output.
TEST(Render, GammaOptionsDecideDecodingAndEncoding) {
    TempFolder dir;
    const auto obj = dir.write("square.obj", std::string("mtllib square.mtl\nusemtl grey\n") + kSquareObj);
    dir.write("square.mtl", "newmtl grey\nKa 0 0 0\nKd 0.5 0.25 0.6\nKs 0 0 0\n");
    Scene scene = headOnScene(obj);
    scene.gamma.decodeInputs = false;
    scene.gamma.encode = TransferCurve::Power;
    scene.gamma.exponent = 2.2f;
    const PreparedScene prepared = prepareScene(scene);
    EXPECT_EQ(prepared.encoding, (ColorEncoding{TransferCurve::Power, 2.2f}));
    const vec4 centre = renderScene(scene).at(32, 24);
    EXPECT_NEAR(centre.r, 0.5f, 1e-6f);  // not decoded: 0.5 stays 0.5
    EXPECT_NEAR(centre.g, 0.25f, 1e-6f);
    EXPECT_EQ(encodeChannel(centre.r, prepared.encoding), 186);  // 0.5^(1/2.2) = 0.7297
}

// The turntable turns the objects about the vertical axis through the scene's centre: a whole turn
// is the scene as written, a quarter turn of a square seen head-on shows its edge (nothing drawn).
TEST(Render, TurntableTurnsAboutTheVerticalAxis) {
    TempFolder dir;
    const auto obj = dir.write("square.obj", std::string("mtllib square.mtl\nusemtl grey\n") + kSquareObj);
    dir.write("square.mtl", "newmtl grey\nKa 0 0 0\nKd 0.5 0.5 0.5\nKs 0 0 0\n");
    Scene scene = headOnScene(obj);
    scene.pipeline.cull = CullMode::None;
    PreparedScene prepared = prepareScene(scene);
    const mat4 original = prepared.draws.front().uniforms.viewFromObject;
    setTurntable(prepared, 360.0f);
    const mat4 whole = prepared.draws.front().uniforms.viewFromObject;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            EXPECT_NEAR(whole[c][r], original[c][r], 1e-5f);
    setTurntable(prepared, 90.0f);
    // The square's corner (1, 0, 0) turns to (0, 0, −1): 1 farther from the eye at z = 5.
    const vec4 corner = prepared.draws.front().uniforms.viewFromObject * vec4(1.0f, 0.0f, 0.0f, 1.0f);
    EXPECT_NEAR(corner.x, 0.0f, 1e-5f);
    EXPECT_NEAR(corner.z, -6.0f, 1e-5f);
    Framebuffer framebuffer(scene.width, scene.height);
    DrawContext context(1);
    const DrawStats stats = renderFrame(prepared, framebuffer, context);
    EXPECT_EQ(stats.fragmentsShaded, 0u);  // edge-on: zero area
}

// A texture's alpha makes a part transparent: drawn in the transparent pass, its alpha in the image.
TEST(Render, TextureAlphaMakesThePartTransparent) {
    TempFolder dir;
    const auto obj =
        texturedSquare(dir, vec4(1.0f, 1.0f, 1.0f, 0.5f), "Ka 0 0 0\nKd 1 1 1\nKs 0 0 0\nmap_Kd texel.png\n");
    Scene scene = headOnScene(obj);
    scene.background = vec4(0.0f, 0.0f, 0.0f, 1.0f);
    const PreparedScene prepared = prepareScene(scene);
    ASSERT_EQ(prepared.draws.size(), 1u);
    EXPECT_TRUE(prepared.draws.front().transparent);
    EXPECT_EQ(prepared.transparentTriangles.size(), 2u);
    const vec4 centre = renderScene(scene).at(32, 24);
    EXPECT_NEAR(centre.r, 0.5f, 2e-3f);  // white at α = 0.5 over black (the 8-bit alpha is 128/255)
}

// map_Ke without Ke: the texture is the emission (Ke taken as 1); unlit, the square shows the texel.
TEST(Render, EmissionMapWithoutKeGlowsWithTheTexture) {
    TempFolder dir;
    const auto obj =
        texturedSquare(dir, vec4(0.2f, 0.6f, 0.9f, 1.0f), "Ka 0 0 0\nKd 0 0 0\nKs 0 0 0\nmap_Ke texel.png\n");
    const vec4 texel = readImage(dir.path() / "texel.png").at(0, 0);  // the 8-bit file's value
    Scene scene = headOnScene(obj);
    scene.background = vec4(0.0f, 0.0f, 0.0f, 1.0f);
    const PreparedScene prepared = prepareScene(scene);
    ASSERT_EQ(prepared.draws.size(), 1u);
    EXPECT_NE(prepared.draws.front().uniforms.emissionMap, nullptr);
    EXPECT_EQ(prepared.draws.front().uniforms.material.emission, vec3(1.0f));
    const vec4 centre = renderScene(scene).at(32, 24);
    EXPECT_NEAR(centre.r, texel.r, 1e-5f);
    EXPECT_NEAR(centre.g, texel.g, 1e-5f);
    EXPECT_NEAR(centre.b, texel.b, 1e-5f);
}

// The memory budget covers all textures of a render together: the second texture that would pass it
// is refused, named, before it is decoded.
TEST(Render, TexturesTogetherBeyondTheBudgetAreAnError) {
    TempFolder dir;
    LinearImage texture;
    texture.width = texture.height = 64;  // 16 KiB each as 8-bit texels
    texture.pixels.assign(64 * 64, vec4(0.5f, 0.5f, 0.5f, 1.0f));
    writeImage(dir.path() / "first.png", texture);
    writeImage(dir.path() / "second.png", texture);
    const auto obj =
        dir.write("two.obj", std::string("mtllib two.mtl\n") +
                                 "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvn 0 0 1\n"
                                 "usemtl a\nf 1/1/1 2/1/1 3/1/1\nusemtl b\nf 1/1/1 3/1/1 4/1/1\n");
    dir.write("two.mtl", "newmtl a\nmap_Kd first.png\nnewmtl b\nmap_Kd second.png\n");
    const Scene scene = headOnScene(obj);
    TextureLimits limits;
    limits.maxTotalBytes = 2 * 64 * 64 * 4;
    EXPECT_EQ(prepareScene(scene, limits).assets->textures.size(), 2u);  // exactly fits
    limits.maxTotalBytes -= 1;
    try {
        prepareScene(scene, limits);
        FAIL() << "no error";
    } catch (const InputError& e) {
        const std::string message = e.what();
        // Refused by their total, from the headers, before either is decoded.
        EXPECT_EQ(message.rfind("the 2 textures of this render need 32.0 KiB together", 0), 0u) << message;
    }
}

// Every object copies its model: the scene's triangles (objects × their models') are bounded before
// the copies are made. Breaks if the total counts each model once, or is checked after the draws.
TEST(Render, SceneDrawingTooManyTrianglesIsAnError) {
    TempFolder dir;
    std::string strip = "v 0 0 0\nv 0 1 0\n";
    constexpr int kTriangles = 20000;
    for (int i = 1; i <= kTriangles / 2; ++i)
        strip += "v " + std::to_string(i) + " 0 0\nv " + std::to_string(i) + " 1 0\n";
    for (int i = 0; i < kTriangles / 2; ++i) {
        const int a = 2 * i + 1;  // (a, a+1) is the left edge of quad i, (a+2, a+3) its right edge
        strip += "f " + std::to_string(a) + " " + std::to_string(a + 2) + " " + std::to_string(a + 3) + "\n";
        strip += "f " + std::to_string(a) + " " + std::to_string(a + 3) + " " + std::to_string(a + 1) + "\n";
    }
    dir.write("strip.obj", strip);
    const std::size_t fits = kMaxSceneTriangles / kTriangles;
    const auto sceneOf = [&](std::size_t objects) {
        std::string list = R"({"model": "strip.obj"})";
        for (std::size_t i = 1; i < objects; ++i)
            list += R"(, {"model": "strip.obj"})";
        return loadScene(dir.write("scene.json", R"({"width": 8, "height": 8, "objects": [)" + list + "]}"));
    };
    try {
        prepareScene(sceneOf(fits + 1));
        FAIL() << "no error";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("the scene draws " + std::to_string((fits + 1) * kTriangles) + " triangles"),
                  std::string::npos)
            << message;
    }
    EXPECT_EQ(prepareScene(sceneOf(2)).triangleCount, 2u * kTriangles);
}

// Two half-transparent quads that cross each other along x = 0 (z = x/2 and z = −x/2): left of the
// crossing the second is nearer, right of it the first. No order of their triangles is right on both
// sides; exact transparency (per-pixel fragment lists) is, and gives the over operator of the nearer
// surface over the farther one at every pixel.
TEST(Render, ExactTransparencyIsRightWhereSortingCannotBe) {
    TempFolder dir;
    const vec3 red(1.0f, 0.0f, 0.0f), blue(0.0f, 0.0f, 1.0f);
    Scene scene = headOnScene(writeEmissiveQuad(dir, "rising", -0.5f, 0.5f, red, 0.5f));
    ObjectSpec falling;
    falling.model = writeEmissiveQuad(dir, "falling", 0.5f, -0.5f, blue, 0.5f);
    scene.objects.push_back(falling);
    scene.lighting.preset = LightingPreset::GL;
    scene.background = vec4(0.0f, 0.0f, 0.0f, 1.0f);
    scene.pipeline.cull = CullMode::None;

    const auto over = [](vec3 near, vec3 far) { return 0.5f * near + 0.5f * (0.5f * far); };
    const vec3 left = over(blue, red), right = over(red, blue);  // expected either side of the crossing
    scene.transparency.mode = TransparencyMode::Exact;
    const LinearImage exact = renderScene(scene);
    scene.transparency.mode = TransparencyMode::Sorted;
    const LinearImage sorted = renderScene(scene);
    int sortedWrong = 0;
    for (int y : {14, 24, 34}) {
        for (int x : {24, 28}) {  // left of the crossing (the image centre is x = 32)
            EXPECT_NEAR(glm::length(vec3(exact.at(x, y)) - left), 0.0f, 1e-5f) << x << ", " << y;
            sortedWrong += glm::length(vec3(sorted.at(x, y)) - left) > 0.1f;
        }
        for (int x : {36, 40}) {
            EXPECT_NEAR(glm::length(vec3(exact.at(x, y)) - right), 0.0f, 1e-5f) << x << ", " << y;
            sortedWrong += glm::length(vec3(sorted.at(x, y)) - right) > 0.1f;
        }
    }
    EXPECT_GT(sortedWrong, 0) << "sorting per triangle should get some of these pixels wrong";
}

// The straightforward way of drawing a sorted frame: every run with its part's whole vertex array and
// the part's own indices. `sorter` sees the same keys as the renderer's, frame after frame, so both
// order ties alike.
void drawRunsWithWholeParts(const PreparedScene& prepared, TransparencySorter& sorter, Framebuffer& target,
                            DrawContext& context) {
    FrameMemory keys;
    FrameStats unused;
    planFrame(prepared, TransparencyMode::Sorted, keys, unused);  // for keys.keys
    SortStats sortStats;
    const std::span<const std::uint32_t> order =
        sorter.sort(keys.keys, SortAlgorithm::InsertionWithMemory, sortStats);
    const auto drawPart = [&](const PreparedDraw& d, const DrawState& state,
                              std::span<const std::uint32_t> indices) {
        ASSERT_EQ(d.frequency, ShadingFrequency::Phong);
        draw<SurfaceShader<ShadingFrequency::Phong>>(
            state, d.uniforms, std::span<const MeshVertex>(d.vertices), indices, target, context);
    };
    target.clear(prepared.clearColor, 1.0f, context.pool);
    for (const PreparedDraw& d : prepared.draws)
        if (!d.transparent) drawPart(d, prepared.state, d.indices);
    const std::span<const TransparentTriangle> triangles = prepared.transparentTriangles;
    std::vector<std::uint32_t> run;
    for (std::size_t i = 0; i < order.size();) {
        const PreparedDraw& d = prepared.draws[triangles[order[i]].draw];
        run.clear();
        for (; i < order.size() && &prepared.draws[triangles[order[i]].draw] == &d; ++i)
            for (int c = 0; c < 3; ++c)
                run.push_back(d.indices[3 * triangles[order[i]].triangle + c]);
        DrawState state = prepared.state;
        state.depth.writeEnabled = false;
        state.blend = d.uniforms.blend;
        drawPart(d, state, run);
    }
}

// A sorted frame cut into many runs shades, over all runs, at most three vertices per transparent
// triangle (a run's own vertices), not its part's whole vertex array once per run.
TEST(Render, SortedRunsShadeOnlyTheVerticesTheyUse) {
    TempFolder dir;
    const int quadCount = 60;
    PreparedScene prepared = prepareScene(interleavedQuadsScene(writeInterleavedQuads(dir, quadCount)));
    ASSERT_EQ(prepared.draws.size(), 5u);
    Framebuffer framebuffer(prepared.scene.width, prepared.scene.height);
    DrawContext context(2);
    FrameMemory memory;
    const FrameStats stats = renderFrame(prepared, framebuffer, context, memory);
    EXPECT_EQ(stats.transparentRuns, static_cast<std::size_t>(quadCount) + 1);
    EXPECT_LE(stats.draw.vertices, opaqueVertexCount(prepared) + 3 * prepared.transparentTriangles.size());
    EXPECT_GT(stats.draw.fragmentsWritten, 0u);

    // Each run's vertex array holds exactly the vertices its indices use, each once.
    FrameStats planStats;
    for (const PlannedDraw& call : planFrame(prepared, TransparencyMode::Sorted, memory, planStats)) {
        std::vector<bool> used(call.vertices.size(), false);
        for (const std::uint32_t index : call.indices) {
            ASSERT_LT(index, call.vertices.size());
            used[index] = true;
        }
        EXPECT_EQ(std::count(used.begin(), used.end(), true), static_cast<std::ptrdiff_t>(used.size()));
    }
}

// Runs with their own compact vertex arrays draw the same bytes as runs drawn against their part's whole
// vertex array, frame after frame of a turntable (the order remembered), with one thread or two.
TEST(Render, SortedRunsDrawTheSameBytesAsRunsOverWholeParts) {
    TempFolder dir;
    PreparedScene prepared = prepareScene(interleavedQuadsScene(writeInterleavedQuads(dir, 45)));
    for (const int threads : {1, 2}) {
        DrawContext context(threads);
        FrameMemory memory;
        TransparencySorter referenceSorter;
        for (const float degrees : {0.0f, 10.0f, 25.0f, 60.0f}) {
            setTurntable(prepared, degrees);
            Framebuffer runs(prepared.scene.width, prepared.scene.height);
            Framebuffer whole(prepared.scene.width, prepared.scene.height);
            renderFrame(prepared, runs, context, memory);
            drawRunsWithWholeParts(prepared, referenceSorter, whole, context);
            const std::vector<vec4> a = runs.colorPixels(), b = whole.colorPixels();
            ASSERT_EQ(a.size(), b.size());
            EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(vec4)), 0)
                << threads << " threads, " << degrees << " degrees";
        }
    }
}

// Each bundled model, and the classic ones in ../shared/models, render with every default: the corner
// holds the background, the centre is the model, every value is finite.
class BundledModel : public ::testing::TestWithParam<std::string> {};

TEST_P(BundledModel, RendersWithDefaults) {
    const std::filesystem::path path = GetParam();
    const bool isScene = path.extension() == ".json";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is not here";
    Scene scene = isScene ? loadScene(path) : sceneForModel(path);
    scene.width = 160;
    scene.height = 120;
    const PreparedScene prepared = prepareScene(scene);
    EXPECT_GT(prepared.triangleCount, 0u);
    Framebuffer framebuffer(scene.width, scene.height);
    DrawContext scratch;
    const DrawStats stats = renderFrame(prepared, framebuffer, scratch);
    EXPECT_GT(stats.fragmentsWritten, 500u);
    const LinearImage image = toImage(framebuffer);
    const vec4 background = prepared.clearColor;
    EXPECT_EQ(image.at(0, 0), background);
    EXPECT_EQ(image.at(159, 119), background);
    if (!isScene) {
        // The default camera looks at the centre of the bounding box; these models are solid there.
        int modelPixels = 0;
        for (int y = 55; y < 65; ++y)
            for (int x = 75; x < 85; ++x)
                modelPixels += image.at(x, y) != background;
        EXPECT_GT(modelPixels, 50) << "the middle of the image should show the model";
    }
    for (const vec4& p : image.pixels)
        for (int k = 0; k < 4; ++k)
            ASSERT_TRUE(std::isfinite(p[k]));
}

INSTANTIATE_TEST_SUITE_P(Models, BundledModel,
                         ::testing::Values(FACET_SOURCE_DIR "/models/spot/spot_triangulated.obj",
                                           FACET_SOURCE_DIR "/models/cube/cube.obj",
                                           FACET_SOURCE_DIR "/models/example-scene.json",
                                           FACET_SHARED_MODELS "/stanford-bunny/stanford-bunny.obj",
                                           FACET_SHARED_MODELS "/utah-teapot/teapot.obj",
                                           FACET_SHARED_MODELS "/suzanne/suzanne.obj",
                                           FACET_SHARED_MODELS "/cornell-box/CornellBox-Original.obj",
                                           FACET_SHARED_MODELS "/lat-long-sphere/sphere-cylcoords-4k.obj"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                             std::string name = std::filesystem::path(info.param).stem().string();
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

// A point light exactly in the plane of a face, at its centre: every point of the face sees it at
// grazing incidence (N·L = 0), so the face gets neither diffuse nor specular light, everywhere alike.
// Rounding used to put N·L a hair above 0 at some pixels and a hair below at others: highlights
// speckled the face at random, and at the light's own position L was 0/0.
TEST(Render, PointLightOnAFaceLightsItEvenly) {
    TempFolder dir;
    const auto obj = dir.write("square.obj", std::string("mtllib square.mtl\nusemtl shiny\n") + kSquareObj);
    dir.write("square.mtl", "newmtl shiny\nKa 0 0 0\nKd 0.5 0.5 0.5\nKs 1 1 1\nNs 10\n");
    for (const ReflectionModel model :
         {ReflectionModel::BlinnPhong, ReflectionModel::Phong, ReflectionModel::CookTorrance})
        for (const ShadingFrequency frequency : {ShadingFrequency::Phong, ShadingFrequency::Gouraud}) {
            Scene scene = headOnScene(obj);
            scene.background = vec4(0.25f, 0.5f, 0.75f, 1.0f);
            scene.lights[0].type = LightKind::Point;
            scene.lights[0].position = vec3(0.1f, 0.2f, 0.0f);  // in the square's plane
            scene.camera.eye = vec3(0.7f, 1.3f, 4.1f);          // at an angle: eye space rounds
            scene.lighting.model = model;
            scene.lighting.shading = frequency;
            const LinearImage image = renderScene(scene);
            const vec4 first = image.at(30, 26);
            int differing = 0, notFinite = 0;
            for (int y = 14; y < 34; ++y)  // well inside the square
                for (int x = 22; x < 42; ++x) {
                    const vec4 p = image.at(x, y);
                    notFinite += !(std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b));
                    differing +=
                        std::abs(p.r - first.r) + std::abs(p.g - first.g) + std::abs(p.b - first.b) > 1e-3f;
                }
            EXPECT_EQ(notFinite, 0) << int(model) << " " << int(frequency);
            EXPECT_EQ(differing, 0) << int(model) << " " << int(frequency) << " centre " << first.r;
        }
}

// A cube whose coordinates are multiplied by `scale`, with a shiny material, written as OBJ text.
std::string scaledCubeObj(double scale) {
    std::ostringstream obj;
    obj.precision(9);
    obj << "mtllib cube.mtl\nusemtl shiny\n";
    for (int corner = 0; corner < 8; ++corner)
        obj << "v " << ((corner & 1) ? scale : -scale) << " " << ((corner & 2) ? scale : -scale) << " "
            << ((corner & 4) ? 0.5 * scale : -0.5 * scale) << "\n";
    obj << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
    return obj.str();
}

// Framing, view and projection are computed in double and eye space is scaled to the scene's size:
// a model of 1e30 or 1e-30 units (which the OBJ importer accepts) renders as the same image as the
// unit-sized one, lighting and highlight included; so does one of 1e-7, once framed five times too
// small. (1e30 used to overflow the float projection, 1e-30 to underflow it: blank images.)
TEST(Render, ExtremeScalesRenderTheSameImageAsUnitSize) {
    TempFolder dir;
    dir.write("cube.mtl", "newmtl shiny\nKa 0 0 0\nKd 0.6 0.4 0.2\nKs 0.5 0.5 0.5\nNs 20\n");
    const auto render = [&](double scale) {
        Scene scene = sceneForModel(dir.write("cube.obj", scaledCubeObj(scale)));
        scene.width = 48;
        scene.height = 36;
        LightSpec light;  // a point light, so that attenuation and distances are scaled too
        light.type = LightKind::Point;
        light.position = vec3(glm::dvec3(2.0, 3.0, 4.0) * scale);
        light.attenuation = vec3(0.5f, float(0.3 / scale), 0.0f);  // (c2 / scale² is beyond float)
        scene.lights = {light};
        return renderScene(scene);
    };
    const LinearImage unit = render(1.0);
    int covered = 0;
    for (const vec4& p : unit.pixels)
        covered += p != unit.pixels[0];
    ASSERT_GT(covered, 200);
    for (const double scale : {1e30, 1e-30, 1e-7}) {
        const LinearImage scaled = render(scale);
        int differing = 0;
        for (std::size_t i = 0; i < unit.pixels.size(); ++i) {
            const vec4 d = abs(scaled.pixels[i] - unit.pixels[i]);
            differing += std::max({d.r, d.g, d.b, d.a}) > 1e-3f;
        }
        EXPECT_LE(differing, 2) << "scale " << scale;  // a pixel centre exactly on an edge may flip
    }
}

}  // namespace
}  // namespace facet
