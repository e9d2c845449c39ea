// The example shaders (examples/shaders/*.cpp), loaded as facet loads a shader of one's own: each built
// into its module (examples/CMakeLists.txt), opened with dlopen, its facet_shader_module() called. Their
// vertex and fragment parts are run on chosen inputs (ShaderModule::shadeVertex, shadeFragment) and
// the Phong solution's draw is compared with the built-in shader's, pixel for pixel.
#include "float_bits.h"
#include "shaders/shader_module.h"
#include "three_lights.h"

#include <dlfcn.h>

#include <bit>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

namespace facet {
namespace {

// The module of examples/shaders/NAME.cpp, loaded once (never unloaded); null, with a test failure
// saying why, when it cannot be.
const ShaderModule* load(const std::string& name) {
    static std::map<std::string, const ShaderModule*> loaded;
    if (const auto found = loaded.find(name); found != loaded.end()) return found->second;
    // Appended piece by piece: GCC 12 at -O1 warns falsely (-Warray-bounds) on a chain of + on a
    // temporary string.
    std::string path = FACET_EXAMPLE_SHADER_DIR;
    path.append("/").append(name).append(".so");
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        ADD_FAILURE() << "dlopen " << path << ": " << dlerror();
        return loaded[name] = nullptr;
    }
    using Abi = const char* (*)();
    using Module = const ShaderModule* (*)();
    const auto abi = reinterpret_cast<Abi>(dlsym(handle, "facet_shader_abi"));
    const auto module = reinterpret_cast<Module>(dlsym(handle, "facet_shader_module"));
    if (!abi || !module) {
        ADD_FAILURE() << path << " lacks facet_shader_abi or facet_shader_module";
        return loaded[name] = nullptr;
    }
    EXPECT_STREQ(abi(), FACET_SHADER_ABI) << path;
    return loaded[name] = module();
}

// A setting of the uniform called `name`.
UniformSetting setting(const ShaderModule& module, std::string_view name, std::array<float, 4> value) {
    for (std::size_t i = 0; i < module.uniforms.size(); ++i)
        if (module.uniforms[i].name == name) return {static_cast<std::uint32_t>(i), value};
    ADD_FAILURE() << module.name << " has no uniform " << name;
    return {};
}

// The fragment part at one fragment: its colour, or nullopt where it discards.
std::optional<vec4> shade(const ShaderModule& module, const SceneUniforms& scene,
                          const std::vector<float>& varyings,
                          const std::vector<UniformSetting>& settings = {},
                          vec3 barycentric = vec3(1.0f / 3.0f)) {
    EXPECT_EQ(varyings.size(), module.varyingNames.size()) << module.name;
    ShaderCall call;
    call.scene = &scene;
    call.settings = settings;
    FragmentInput in;
    in.varyings = varyings.data();
    in.barycentric = barycentric;
    vec4 color;
    if (!module.shadeFragment(in, call, color, nullptr)) return std::nullopt;
    return color;
}

using testing_shaders::bits;

// One white directional light shining along −z (from behind the eye), no ambient light.
SceneUniforms headLight() {
    SceneUniforms u;
    u.lightCount = 1;
    u.lights[0].kind = LightKind::Directional;
    u.lights[0].direction = vec3(0.0f, 0.0f, -1.0f);
    u.material.diffuse = vec3(1.0f);
    return u;
}

// Every example loads, carries the headers' key, names its struct and varyings, and only the
// wireframe (which may discard) says it discards. Break caught: an example that no longer builds into a
// loadable module (a pipeline symbol the program does not export, a missing FACET_SHADER).
TEST(ExampleShaders, EveryExampleLoads) {
    const std::map<std::string, std::tuple<std::string_view, std::size_t, bool>> expected = {
        {"normals", {"Normals", 3, false}},
        {"toon", {"Toon", 8, false}},
        {"checker", {"Checker", 11, false}},
        {"wireframe", {"Wireframe", 6, true}},
        {"displace", {"Displace", 7, false}},
        {"phong_assignment", {"PhongAssignment", 8, false}},
        {"phong_solution", {"PhongSolution", 8, false}}};
    for (const auto& [file, what] : expected) {
        const ShaderModule* module = load(file);
        ASSERT_NE(module, nullptr) << file;
        EXPECT_EQ(module->name, std::get<0>(what));
        EXPECT_EQ(module->varyingNames.size(), std::get<1>(what)) << file;
        EXPECT_EQ(module->discards, std::get<2>(what)) << file;
    }
}

// normals: c = 0.5·n + 0.5 of the renormalised normal. Break caught: the normal not renormalised (a
// long interpolated normal would saturate), or the map written as n·0.5 without the offset.
TEST(ExampleShaders, NormalsMapsTheNormalToAColour) {
    const ShaderModule* module = load("normals");
    ASSERT_NE(module, nullptr);
    EXPECT_EQ(shade(*module, {}, {0.0f, 0.0f, 1.0f}), vec4(0.5f, 0.5f, 1.0f, 1.0f));
    EXPECT_EQ(shade(*module, {}, {3.0f, 0.0f, 0.0f}), vec4(1.0f, 0.5f, 0.5f, 1.0f));
    EXPECT_EQ(shade(*module, {}, {0.0f, -0.5f, 0.0f}), vec4(0.5f, 0.0f, 0.5f, 1.0f));
}

// toon: the light falls into exactly `bands` shades as N·L sweeps from 0 to 1, and where N·V is
// below `outline` the colour is the ink. Breaks caught: the band not clamped at I = 1 (one band too
// many), the level divided by bands instead of bands − 1 (the brightest band not fully lit), the
// outline test reversed.
TEST(ExampleShaders, ToonHasBandsLevelsAndInkedSilhouettes) {
    const ShaderModule* module = load("toon");
    ASSERT_NE(module, nullptr);
    for (int bands : {2, 3, 4, 6}) {
        std::set<float> levels;
        SceneUniforms u = headLight();
        for (int step = 0; step <= 90; ++step) {
            const float angle = glm::radians(static_cast<float>(step));
            u.lights[0].direction = vec3(std::sin(angle), 0.0f, -std::cos(angle));  // N·L = cos(angle)
            const auto c = shade(*module, u, {0.0f, 0.0f, -3.0f, 0.0f, 0.0f, 1.0f, 0.5f, 0.5f},
                                 {setting(*module, "bands", {static_cast<float>(bands)})});
            ASSERT_TRUE(c);
            levels.insert(c->r);
        }
        EXPECT_EQ(levels.size(), static_cast<std::size_t>(bands)) << bands << " bands";
        EXPECT_EQ(*levels.begin(), 0.0f);
        EXPECT_EQ(*levels.rbegin(), 1.0f);
    }
    // A normal nearly at right angles to V: N·V ≈ 0.1 < 0.25, the ink; then outline 0 turns it off.
    const std::vector<float> grazing = {0.0f, 0.0f, -3.0f, 1.0f, 0.0f, 0.1f, 0.5f, 0.5f};
    EXPECT_EQ(shade(*module, headLight(), grazing), vec4(0.02f, 0.02f, 0.05f, 1.0f));
    EXPECT_NE(shade(*module, headLight(), grazing, {setting(*module, "outline", {0.0f})}),
              vec4(0.02f, 0.02f, 0.05f, 1.0f));
}

// checker: neighbouring cells alternate between the two colours along u and along v, cells two apart
// match, negative coordinates too; fromPosition reads the object position. Breaks caught: C's fmod in
// place of GLSL's mod (negative cells would not alternate), the two colours swapped, scale ignored.
TEST(ExampleShaders, CheckerAlternates) {
    const ShaderModule* module = load("checker");
    ASSERT_NE(module, nullptr);
    const SceneUniforms u = headLight();  // lit head-on: the colour is the albedo itself
    auto at = [&](float s, float t, std::vector<UniformSetting> settings = {}) {
        const auto c = shade(*module, u, {0, 0, -3, 0, 0, 1, s, t, s, t, 0}, settings);
        EXPECT_TRUE(c);
        return c ? vec3(*c) : vec3(-1.0f);
    };
    const vec3 a(0.85f, 0.85f, 0.8f), b(0.1f, 0.12f, 0.3f);  // the defaults
    EXPECT_EQ(at(0.01f, 0.01f), a);
    EXPECT_EQ(at(0.01f + 1.0f / 8.0f, 0.01f), b);
    EXPECT_EQ(at(0.01f, 0.01f + 1.0f / 8.0f), b);
    EXPECT_EQ(at(0.01f + 2.0f / 8.0f, 0.01f), a);
    EXPECT_EQ(at(-0.01f, 0.01f), b);
    EXPECT_EQ(at(-0.01f - 1.0f / 8.0f, 0.01f), a);
    const std::vector<UniformSetting> coarse = {setting(*module, "scale", {1.0f})};
    EXPECT_EQ(at(0.3f, 0.01f, coarse), a);
    EXPECT_EQ(at(1.3f, 0.01f, coarse), b);
    // From the object position: its z cell counts too.
    const std::vector<UniformSetting> solid = {setting(*module, "fromPosition", {1.0f})};
    const auto c = shade(*module, u, {0, 0, -3, 0, 0, 1, 0.01f, 0.01f, 0.01f, 0.01f, 0.2f}, solid);
    ASSERT_TRUE(c);
    EXPECT_EQ(vec3(*c), b);
}

// wireframe: on an edge (min λ small) the wire's colour; inside, the lit surface, or nothing when
// hollow. Breaks caught: the interior discarded without `hollow`, or the edges with it; λ not reaching
// the fragment part (every pixel would be the centroid's).
TEST(ExampleShaders, WireframeDrawsEdgesAndDiscardsTheInteriorWhenHollow) {
    const ShaderModule* module = load("wireframe");
    ASSERT_NE(module, nullptr);
    const SceneUniforms u = headLight();
    const std::vector<float> surface = {0, 0, -3, 0, 0, 1};
    const vec3 edge(0.01f, 0.5f, 0.49f), inside(1.0f / 3.0f);
    EXPECT_EQ(shade(*module, u, surface, {}, edge), vec4(0.0f, 0.0f, 0.0f, 1.0f));
    const auto lit = shade(*module, u, surface, {}, inside);
    ASSERT_TRUE(lit);
    EXPECT_EQ(*lit, vec4(1.0f));  // the built-in lighting of a white surface lit head-on
    const std::vector<UniformSetting> hollow = {setting(*module, "hollow", {1.0f})};
    EXPECT_FALSE(shade(*module, u, surface, hollow, inside));
    EXPECT_EQ(shade(*module, u, surface, hollow, edge), vec4(0.0f, 0.0f, 0.0f, 1.0f));
    const std::vector<UniformSetting> red = {setting(*module, "wire", {1.0f, 0.0f, 0.0f})};
    EXPECT_EQ(shade(*module, u, surface, red, edge), vec4(1.0f, 0.0f, 0.0f, 1.0f));
}

// displace: the vertex moves by amplitude·sin(frequency·p.y + phase) along its normal, in clip space and
// in the eye-space varyings, and hands the offset on. Breaks caught: the wave along another axis, the
// phase or amplitude ignored, the clip position left undisplaced.
TEST(ExampleShaders, DisplaceMovesVerticesAlongTheNormal) {
    const ShaderModule* module = load("displace");
    ASSERT_NE(module, nullptr);
    SceneUniforms scene;  // identity matrices: object, eye and clip space agree
    const std::vector<UniformSetting> settings = {setting(*module, "amplitude", {0.1f}),
                                                  setting(*module, "frequency", {4.0f}),
                                                  setting(*module, "phase", {0.5f})};
    ShaderCall call;
    call.scene = &scene;
    call.settings = settings;
    const MeshVertex vertex{vec3(0.3f, 0.5f, 0.2f), normalize(vec3(0.0f, 0.6f, 0.8f)), vec2(0.0f)};
    float varyings[7];
    const vec4 clip = module->shadeVertex(vertex, call, varyings);
    const float offset = 0.1f * std::sin(4.0f * 0.5f + 0.5f);
    const vec3 moved = vertex.position + vertex.normal * offset;
    EXPECT_EQ(clip, vec4(moved, 1.0f));
    EXPECT_EQ(vec3(varyings[0], varyings[1], varyings[2]), moved);
    EXPECT_EQ(vec3(varyings[3], varyings[4], varyings[5]), vertex.normal);
    EXPECT_EQ(varyings[6], offset);
}

// ---- The Phong solution is the built-in Phong -----------------------------------------------------------

SurfaceUniforms threeLights() {
    SurfaceUniforms u = testing_shaders::threeLights();
    u.reflection = ReflectionModel::Phong;
    u.material.shininess = 20.0f;
    return u;
}

// A 2 × 2 texture with translucent texels, for the diffuse map.
Texture translucentChecker() {
    Texture t;
    t.width = t.height = 2;
    t.texels = {vec4(0.9f, 0.9f, 0.9f, 1.0f), vec4(0.3f, 0.6f, 0.2f, 0.25f), vec4(0.5f, 0.1f, 0.7f, 0.8f),
                vec4(1.0f, 1.0f, 1.0f, 0.5f)};
    return t;
}

// The variants the comparison runs: precisions, normalisations, fog and blend, a diffuse map, the clamp.
std::vector<SurfaceUniforms> phongVariants(const Texture& texture) {
    std::vector<SurfaceUniforms> variants;
    for (MathPrecision precision : {MathPrecision::Exact, MathPrecision::Fast})
        for (Normalization normalization : {Normalization::Exact, Normalization::Fast}) {
            SurfaceUniforms u = threeLights();
            u.precision = precision;
            u.normalization = normalization;
            variants.push_back(u);
        }
    SurfaceUniforms u = threeLights();
    u.fog.mode = FogMode::Exponential;
    u.fog.density = 0.3f;
    u.blend = BlendMode::PremultipliedOver;
    u.opacity = 0.6f;
    u.diffuseMap = &texture;
    u.clampColor = true;
    variants.push_back(u);
    u.twoSidedFlip = false;
    u.textureFilter = TextureFilter::Nearest;
    variants.push_back(u);
    return variants;
}

// phong_solution's fragment part gives SurfaceShader<Phong>'s colour bit for bit (no tolerance: it adds
// the same terms, computed by the same functions, in the same order) at random points, normals and uv.
// Breaks caught: a term of the solution computed otherwise than the built-in (R from −l reflected by
// GLSL's reflect, rounding differently; the ambient of lights without one added as zeros, −0 + 0), the
// texture or fog left out.
TEST(ExampleShaders, PhongSolutionShadesAsTheBuiltInPhong) {
    const ShaderModule* module = load("phong_solution");
    ASSERT_NE(module, nullptr);
    const Texture texture = translucentChecker();
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> r(-1.0f, 1.0f);
    for (const SurfaceUniforms& u : phongVariants(texture))
        for (int trial = 0; trial < 200; ++trial) {
            const std::vector<float> v = {r(rng), r(rng), r(rng) - 3.0f, r(rng),
                                          r(rng), r(rng), r(rng) + 1.0f, r(rng)};
            const PerPixelSurface::VaryingsT<float> in{vec3(v[0], v[1], v[2]), vec3(v[3], v[4], v[5]),
                                                       vec2(v[6], v[7])};
            const vec4 builtin = SurfaceShader<ShadingFrequency::Phong>::fragment(in, u);
            const auto mine = shade(*module, u, v);
            ASSERT_TRUE(mine);
            for (int k = 0; k < 4; ++k)
                ASSERT_EQ(bits((*mine)[k]), bits(builtin[k])) << "component " << k << " trial " << trial;
        }
}

// A bumpy grid of triangles in front of the camera, with analytic normals and uv.
std::vector<MeshVertex> bumpyGrid(std::vector<std::uint32_t>& indices) {
    constexpr int kSide = 12;
    std::vector<MeshVertex> vertices;
    for (int j = 0; j <= kSide; ++j)
        for (int i = 0; i <= kSide; ++i) {
            const float x = -1.0f + 2.0f * i / kSide, y = -1.0f + 2.0f * j / kSide;
            const float z = 0.2f * std::sin(3.0f * x) * std::cos(2.0f * y);
            const vec3 n = normalize(vec3(-0.6f * std::cos(3.0f * x) * std::cos(2.0f * y),
                                          0.4f * std::sin(3.0f * x) * std::sin(2.0f * y), 1.0f));
            vertices.push_back({vec3(x, y, z), n, vec2(0.5f * x + 0.5f, 0.5f * y + 0.5f)});
        }
    for (int j = 0; j < kSide; ++j)
        for (int i = 0; i < kSide; ++i) {
            const auto at = [](int a, int b) { return static_cast<std::uint32_t>(b * (kSide + 1) + a); };
            indices.insert(indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            indices.insert(indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return vertices;
}

// The module's own draw (its fragment part eight lanes at a time, inlined into the pipeline's loops)
// writes the built-in Phong's image, every pixel's bits; the assignment does too where the material has
// no specular colour (its missing term is then zero in the built-in image as well) and differs where it
// has one. Breaks caught: the eight-lane body not the one-lane one (a lane function of another
// rounding), the derivatives or the texture lookup of the batch path differing from the built-in's.
TEST(ExampleShaders, PhongSolutionDrawsTheBuiltInImage) {
    const ShaderModule* solution = load("phong_solution");
    const ShaderModule* assignment = load("phong_assignment");
    ASSERT_NE(solution, nullptr);
    ASSERT_NE(assignment, nullptr);
    std::vector<std::uint32_t> indices;
    const std::vector<MeshVertex> vertices = bumpyGrid(indices);
    const Texture texture = translucentChecker();
    DrawState state;
    state.viewport = {0, 0, 80, 60};
    state.raster.cull = CullMode::None;
    DrawContext context;
    auto frame = [&](auto&& drawIt) {
        Framebuffer target(80, 60);
        target.clearColor(vec4(0.1f, 0.2f, 0.3f, 1.0f));
        drawIt(target);
        return target;
    };
    auto sameImage = [](const Framebuffer& a, const Framebuffer& b) {
        for (int y = 0; y < a.height(); ++y)
            for (int x = 0; x < a.width(); ++x)
                for (int k = 0; k < 4; ++k)
                    if (bits(a.color(x, y)[k]) != bits(b.color(x, y)[k])) return false;
        return true;
    };
    for (SurfaceUniforms u : phongVariants(texture)) {
        const mat4 view = glm::lookAt(vec3(0.4f, -0.8f, 2.5f), vec3(0.0f), vec3(0.0f, 1.0f, 0.0f));
        u.viewFromObject = view;
        u.clipFromObject = glm::perspective(glm::radians(50.0f), 80.0f / 60.0f, 0.1f, 10.0f) * view;
        u.normalFromObject = transpose(inverse(mat3(view)));
        const Framebuffer builtin = frame([&](Framebuffer& target) {
            draw<SurfaceShader<ShadingFrequency::Phong>>(state, u, vertices, indices, target, context);
        });
        ShaderCall call{&state, &u, {}, vertices, indices};
        const Framebuffer mine = frame([&](Framebuffer& target) { solution->draw(call, target, context); });
        EXPECT_TRUE(sameImage(mine, builtin)) << "precision " << mathPrecisionName(u.precision);
        const Framebuffer unfinished =
            frame([&](Framebuffer& target) { assignment->draw(call, target, context); });
        EXPECT_FALSE(sameImage(unfinished, builtin)) << "the assignment already has highlights";
        SurfaceUniforms matte = u;
        matte.material.specular = vec3(0.0f);
        const Framebuffer matteBuiltin = frame([&](Framebuffer& target) {
            draw<SurfaceShader<ShadingFrequency::Phong>>(state, matte, vertices, indices, target, context);
        });
        call.scene = &matte;
        const Framebuffer matteAssignment =
            frame([&](Framebuffer& target) { assignment->draw(call, target, context); });
        EXPECT_TRUE(sameImage(matteAssignment, matteBuiltin));
    }
}

}  // namespace
}  // namespace facet
