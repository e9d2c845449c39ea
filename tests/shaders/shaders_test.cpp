// The built-in surface shaders: the eight-lane path computes exactly what the one-fragment path
// computes (one body), for every reflection model, shading frequency and math precision; the precision
// is the uniforms' choice; the term mask, the two-sided flip and the GL clamp at both lane widths.
#include "shaders/shaders.h"

#include "pipeline/pipeline.h"
#include "three_lights.h"

#include <algorithm>
#include <cstring>
#include <iterator>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

namespace facet {
namespace {

using testing_shaders::threeLights;

// A 2 × 2 texture of four colours, for the emission map.
Texture fourColours() {
    Texture t;
    t.width = t.height = 2;
    t.texels = {vec4(0.2f, 0.5f, 1.0f, 1.0f), vec4(1.0f, 0.1f, 0.3f, 1.0f), vec4(0.0f, 0.8f, 0.4f, 1.0f),
                vec4(0.6f, 0.6f, 0.1f, 0.5f)};
    return t;
}

constexpr MathPrecision kPrecisions[] = {MathPrecision::Exact, MathPrecision::Fast};

// A 2 × 2 texture with translucent texels, for the diffuse map.
Texture translucentChecker() {
    Texture t;
    t.width = t.height = 2;
    t.texels = {vec4(0.9f, 0.9f, 0.9f, 1.0f), vec4(0.3f, 0.6f, 0.2f, 0.25f), vec4(0.5f, 0.1f, 0.7f, 0.8f),
                vec4(1.0f, 1.0f, 1.0f, 0.5f)};
    return t;
}

// The fragment shader is one body for one lane and eight: fragment() of a fragment gives exactly lane k
// of fragmentBatch() for the same varyings, bit for bit, under either precision.
template <ShadingFrequency kFrequency>
void expectBatchLanesEqualOneLane(const SurfaceUniforms& uniforms, std::mt19937& rng, const char* what) {
    using S = SurfaceShader<kFrequency>;
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int trial = 0; trial < 40; ++trial) {
        FragmentBatch batch{};
        batch.mask = 0xff;
        typename S::Varyings scalar[8];
        for (int lane = 0; lane < 8; ++lane) {
            float* f = reinterpret_cast<float*>(&scalar[lane]);
            for (int k = 0; k < kVaryingFloatCount<typename S::Varyings>; ++k) {
                f[k] = k < 3 ? u(rng) - (k == 2 ? 3.0f : 0.0f) : u(rng);  // positions in front of the eye
                batch.varyings[k][lane] = f[k];
            }
        }
        const Vec4x8 wide = S::fragmentBatch(batch, uniforms);
        for (int lane = 0; lane < 8; ++lane) {
            const vec4 one = S::fragment(scalar[lane], uniforms);
            EXPECT_EQ(vec4(wide.x[lane], wide.y[lane], wide.z[lane], wide.w[lane]), one)
                << what << ", " << mathPrecisionName(uniforms.precision) << ", lane " << lane;
        }
    }
}

template <ShadingFrequency kFrequency>
void expectBatchLanesEqualOneLaneForEveryModel(SurfaceUniforms uniforms, std::mt19937& rng,
                                               const char* what) {
    for (MathPrecision precision : kPrecisions) {
        uniforms.precision = precision;
        for (ReflectionModel model :
             {ReflectionModel::Phong, ReflectionModel::BlinnPhong, ReflectionModel::CookTorrance}) {
            uniforms.reflection = model;
            for (float shininess : {0.0f, 1.0f, 12.0f, 128.0f}) {
                uniforms.material.shininess = shininess;
                expectBatchLanesEqualOneLane<kFrequency>(uniforms, rng, what);
            }
        }
    }
}

TEST(SurfaceShader, BatchLanesEqualOneLaneForEveryModelFrequencyAndPrecision) {
    std::mt19937 rng(3);
    SurfaceUniforms uniforms = threeLights();
    uniforms.brdf.distribution = NormalDistribution::Beckmann;  // exp in the lighting
    const Texture emission = fourColours(), diffuse = translucentChecker();
    for (int variant = 0; variant < 3; ++variant) {
        if (variant >= 1) {
            uniforms.emissionMap = &emission;
            uniforms.diffuseMap = &diffuse;
        }
        if (variant == 2) {  // exp fog, a premultiplied output, the GL clamp
            uniforms.fog.mode = FogMode::Exponential;
            uniforms.fog.density = 0.3f;
            uniforms.blend = BlendMode::PremultipliedOver;
            uniforms.clampColor = true;
        }
        expectBatchLanesEqualOneLaneForEveryModel<ShadingFrequency::Phong>(uniforms, rng, "per pixel");
        expectBatchLanesEqualOneLaneForEveryModel<ShadingFrequency::Gouraud>(uniforms, rng, "per vertex");
        expectBatchLanesEqualOneLaneForEveryModel<ShadingFrequency::Flat>(uniforms, rng, "flat");
    }
}

// The fast maths stay within 2e−5 of the exact ones: the two precisions draw the same picture.
TEST(SurfaceShader, FastPrecisionIsWithinToleranceOfExact) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    SurfaceUniforms exact = threeLights();
    exact.fog.mode = FogMode::ExponentialSquared;
    exact.fog.density = 0.2f;
    exact.material.shininess = 24.0f;
    using S = SurfaceShader<ShadingFrequency::Phong>;
    int differing = 0;
    for (ReflectionModel model :
         {ReflectionModel::Phong, ReflectionModel::BlinnPhong, ReflectionModel::CookTorrance}) {
        for (NormalDistribution distribution : {NormalDistribution::GGX, NormalDistribution::Beckmann}) {
            exact.reflection = model;
            exact.brdf.distribution = distribution;
            exact.precision = MathPrecision::Exact;
            SurfaceUniforms fast = exact;
            fast.precision = MathPrecision::Fast;
            for (int trial = 0; trial < 200; ++trial) {
                const S::Varyings in{vec3(u(rng), u(rng), u(rng) - 3.0f), vec3(u(rng), u(rng), u(rng)),
                                     vec2(u(rng), u(rng))};
                const vec4 a = S::fragment(in, exact), b = S::fragment(in, fast);
                differing += a != b;
                for (int k = 0; k < 3; ++k)
                    EXPECT_NEAR(b[k], a[k], 2e-5f * (1.0f + std::abs(a[k])));
            }
        }
    }
    EXPECT_GT(differing, 0) << "the two precisions give the same bits: the choice is not honoured";
}

// The per-vertex shaders' eight-lane vertexBatch gives exactly what vertex() gives, lane by lane, for
// every model and precision, with and without the GL clamp and an emission map.
TEST(SurfaceShader, VertexBatchLanesEqualVertex) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    SurfaceUniforms uniforms = threeLights();
    uniforms.viewFromObject = glm::translate(mat4(1.0f), vec3(0.1f, -0.2f, -3.0f));
    uniforms.clipFromObject = glm::perspective(1.0f, 1.3f, 0.1f, 10.0f) * uniforms.viewFromObject;
    uniforms.brdf.distribution = NormalDistribution::Beckmann;
    const Texture map = fourColours();
    using Gouraud = SurfaceShader<ShadingFrequency::Gouraud>;
    static_assert(BatchVertexShader<Gouraud> && BatchVertexShader<SurfaceShader<ShadingFrequency::Flat>>);
    for (MathPrecision precision : kPrecisions)
        for (ReflectionModel model :
             {ReflectionModel::Phong, ReflectionModel::BlinnPhong, ReflectionModel::CookTorrance}) {
            for (bool clamp : {false, true}) {
                uniforms.precision = precision;
                uniforms.reflection = model;
                uniforms.clampColor = clamp;
                uniforms.emissionMap = clamp ? &map : nullptr;
                MeshVertex in[kVertexBatch];
                for (MeshVertex& v : in)
                    v = {vec3(u(rng), u(rng), u(rng)), normalize(vec3(u(rng), u(rng), 1.0f)),
                         vec2(u(rng), u(rng))};
                VertexOut<Gouraud::Varyings> out[kVertexBatch];
                Gouraud::vertexBatch(in, uniforms, out);
                for (int lane = 0; lane < kVertexBatch; ++lane) {
                    const VertexOut<Gouraud::Varyings> one = Gouraud::vertex(in[lane], uniforms);
                    EXPECT_EQ(out[lane].position, one.position);
                    const float* a = reinterpret_cast<const float*>(&out[lane].varyings);
                    const float* b = reinterpret_cast<const float*>(&one.varyings);
                    for (int k = 0; k < kVaryingFloatCount<Gouraud::Varyings>; ++k)
                        EXPECT_EQ(a[k], b[k])
                            << "float " << k << ", lane " << lane << ", " << mathPrecisionName(precision);
                }
            }
        }
}

// Per-pixel shading's vertexBatch (the matrices eight vertices at a time) gives vertex()'s bits, lane by
// lane, under a perspective projection with a rotated, scaled view and a non-uniform normal matrix.
// Breaks caught: a matrix read by row instead of column (m[r][c] for m[c][r]); M·v's sums grouped
// otherwise than GLM's ((x + y) + (z + w)); the normal transformed by the view matrix; the uv or a
// lane's outputs crossed with another lane's.
TEST(SurfaceShader, PerPixelVertexBatchLanesEqualVertex) {
    using Phong = SurfaceShader<ShadingFrequency::Phong>;
    static_assert(BatchVertexShader<Phong>);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    SurfaceUniforms uniforms;
    for (int trial = 0; trial < 50; ++trial) {
        const mat4 model = glm::scale(glm::rotate(mat4(1.0f), 3.0f * u(rng), vec3(u(rng), u(rng), 0.5f)),
                                      vec3(1.0f + u(rng) * 0.5f, 2.0f, 0.7f));
        uniforms.viewFromObject = glm::translate(mat4(1.0f), vec3(u(rng), u(rng), -3.0f + u(rng))) * model;
        uniforms.clipFromObject = glm::perspective(1.0f, 1.3f, 0.1f, 10.0f) * uniforms.viewFromObject;
        uniforms.normalFromObject = glm::transpose(glm::inverse(mat3(uniforms.viewFromObject)));
        MeshVertex in[kVertexBatch];
        for (MeshVertex& v : in)
            v = {vec3(u(rng), u(rng), u(rng)) * 10.0f, normalize(vec3(u(rng), u(rng), u(rng) + 2.0f)),
                 vec2(u(rng), u(rng))};
        VertexOut<Phong::Varyings> out[kVertexBatch];
        Phong::vertexBatch(in, uniforms, out);
        for (int lane = 0; lane < kVertexBatch; ++lane) {
            const VertexOut<Phong::Varyings> one = Phong::vertex(in[lane], uniforms);
            ASSERT_EQ(std::memcmp(&out[lane].position, &one.position, sizeof one.position), 0)
                << "trial " << trial << ", lane " << lane;
            ASSERT_EQ(std::memcmp(&out[lane].varyings, &one.varyings, sizeof one.varyings), 0)
                << "trial " << trial << ", lane " << lane;
        }
    }
}

// The precision is the uniforms' choice, at both lane widths: under each, the shader's colour is the
// lighting and fog formulas' of that precision, bit for bit.
TEST(SurfaceShader, PrecisionIsTheUniformsChoiceAtBothLaneWidths) {
    SurfaceUniforms u = threeLights();
    u.reflection = ReflectionModel::BlinnPhong;
    u.material.shininess = 7.0f;
    u.fog.mode = FogMode::Exponential;
    u.fog.density = 0.35f;
    using S = SurfaceShader<ShadingFrequency::Phong>;
    int differing = 0;
    for (int point = 0; point < 16; ++point) {
        const vec3 P(0.1f * point - 0.7f, 0.2f, -2.0f - 0.1f * point);
        const vec3 N = normalize(vec3(-0.2f, 0.4f - 0.05f * point, 1.0f));
        const auto expected = [&]<MathPrecision kPrecision>() {
            const vec3 lit = standardLighting<float, vec3, kPrecision>(
                                 P, N, vec3(0.0f), u.material, u.material.diffuse, u.globalAmbient,
                                 u.activeLights(), SpecularModel::BlinnPhong)
                                 .sum();
            return applyFog<float, vec3, kPrecision>(u.fog, lit, P);
        };
        const vec3 exact = expected.template operator()<MathPrecision::Exact>();
        const vec3 fast = expected.template operator()<MathPrecision::Fast>();
        differing += exact != fast;
        const S::Varyings in{P, N, vec2(0.0f)};
        FragmentBatch batch{};
        batch.mask = 0xff;
        const float* f = reinterpret_cast<const float*>(&in);
        for (int k = 0; k < kVaryingFloatCount<S::Varyings>; ++k)
            for (int lane = 0; lane < 8; ++lane)
                batch.varyings[k][lane] = f[k];
        for (MathPrecision precision : kPrecisions) {
            u.precision = precision;
            const vec3 want = precision == MathPrecision::Exact ? exact : fast;
            EXPECT_EQ(vec3(S::fragment(in, u)), want) << mathPrecisionName(precision) << ", one lane";
            const Vec4x8 wide = S::fragmentBatch(batch, u);
            EXPECT_EQ(vec3(wide.x[5], wide.y[5], wide.z[5]), want)
                << mathPrecisionName(precision) << ", eight lanes";
        }
    }
    EXPECT_GT(differing, 4) << "the points hardly tell the two precisions apart";
}

TEST(MathPrecision, NamesByValueAndTheDrawDefault) {
    EXPECT_EQ(mathPrecisionName(MathPrecision::Exact), "exact");
    EXPECT_EQ(mathPrecisionName(MathPrecision::Fast), "fast");
    EXPECT_EQ(SurfaceUniforms{}.precision, MathPrecision::Fast);  // what every image has been drawn with
}

// The vertex shader of the per-vertex shaders lights the vertex; the fragment shader only adds up.
TEST(SurfaceShader, PerVertexColourIsTheLightingAtTheVertex) {
    SurfaceUniforms u = threeLights();
    const MeshVertex v{vec3(0.2f, -0.1f, -3.0f), normalize(vec3(0.1f, 0.3f, 1.0f)), vec2(0.0f)};
    const auto out = SurfaceShader<ShadingFrequency::Gouraud>::vertex(v, u);
    const vec4 color = SurfaceShader<ShadingFrequency::Gouraud>::fragment(out.varyings, u);
    const vec3 expected = surfaceTerms<float, vec3>(v.position, v.normal, u.material.diffuse, u).sum();
    EXPECT_NEAR(color.r, expected.r, 1e-6f);
    EXPECT_NEAR(color.g, expected.g, 1e-6f);
    EXPECT_NEAR(color.b, expected.b, 1e-6f);
    // And per pixel at the same point with the same normal gives the same colour.
    const SurfaceShader<ShadingFrequency::Phong>::Varyings pixel{v.position, v.normal, v.uv};
    const vec4 perPixel = SurfaceShader<ShadingFrequency::Phong>::fragment(pixel, u);
    EXPECT_NEAR(perPixel.r, expected.r, 1e-6f);
    EXPECT_NEAR(perPixel.g, expected.g, 1e-6f);
}

// The colour of one shader at one surface point, through its one-lane path or its eight-lane path
// (vertexBatch and fragmentBatch, the point in every lane).
template <ShadingFrequency kFrequency>
vec3 shadeOnce(const MeshVertex& v, const SurfaceUniforms& u, bool batch) {
    using S = SurfaceShader<kFrequency>;
    VertexOut<typename S::Varyings> out = S::vertex(v, u);
    if (!batch) return vec3(S::fragment(out.varyings, u));
    if constexpr (BatchVertexShader<S>) {
        MeshVertex in[kVertexBatch];
        std::fill(std::begin(in), std::end(in), v);
        VertexOut<typename S::Varyings> outs[kVertexBatch];
        S::vertexBatch(in, u, outs);
        out = outs[6];
    }
    FragmentBatch in{};
    in.mask = 0xff;
    const float* f = reinterpret_cast<const float*>(&out.varyings);
    for (int k = 0; k < kVaryingFloatCount<typename S::Varyings>; ++k)
        for (int lane = 0; lane < 8; ++lane)
            in.varyings[k][lane] = f[k];
    const Vec4x8 c = S::fragmentBatch(in, u);
    return vec3(c.x[3], c.y[3], c.z[3]);
}

// An emission map multiplies the emission term by its texel, at every shading frequency and on both
// paths; the other terms are what they are without it (so the emission is counted once, textured).
template <ShadingFrequency kFrequency>
void expectEmissionTextured(const char* what) {
    const Texture map = fourColours();
    SurfaceUniforms plain = threeLights();
    plain.material.emission = vec3(0.3f, 0.2f, 0.1f);
    SurfaceUniforms mapped = plain;
    mapped.emissionMap = &map;
    const MeshVertex v{vec3(0.2f, -0.1f, -3.0f), normalize(vec3(0.1f, 0.3f, 1.0f)), vec2(0.3f, 0.8f)};
    const vec3 texel(sampleBilinear(map, v.uv));
    for (bool batch : {false, true}) {
        const vec3 expected = shadeOnce<kFrequency>(v, plain, batch) - plain.material.emission +
                              plain.material.emission * texel;
        const vec3 got = shadeOnce<kFrequency>(v, mapped, batch);
        EXPECT_NEAR(got.r, expected.r, 1e-5f) << what << (batch ? ", eight lanes" : ", one fragment");
        EXPECT_NEAR(got.g, expected.g, 1e-5f) << what << (batch ? ", eight lanes" : ", one fragment");
        EXPECT_NEAR(got.b, expected.b, 1e-5f) << what << (batch ? ", eight lanes" : ", one fragment");
    }
    // The emission image alone is m_emission ⊗ texel.
    mapped.terms = kEmissionTerm;
    const vec3 alone = shadeOnce<kFrequency>(v, mapped, false);
    EXPECT_NEAR(alone.r, 0.3f * texel.r, 1e-6f) << what;
    EXPECT_NEAR(alone.g, 0.2f * texel.g, 1e-6f) << what;
    EXPECT_NEAR(alone.b, 0.1f * texel.b, 1e-6f) << what;
}

TEST(SurfaceShader, EmissionMapMultipliesTheEmissionAtEveryFrequency) {
    expectEmissionTextured<ShadingFrequency::Phong>("per pixel");
    expectEmissionTextured<ShadingFrequency::Gouraud>("per vertex");
    expectEmissionTextured<ShadingFrequency::Flat>("flat");
}

// Each term bit selects one term; the four component images add up to the full image.
TEST(SurfaceShader, TermMaskSelectsComponentsThatSumToTheWhole) {
    SurfaceUniforms u = threeLights();
    const vec3 P(0.3f, 0.2f, -2.0f), N = normalize(vec3(-0.2f, 0.4f, 1.0f));
    for (ReflectionModel model :
         {ReflectionModel::Phong, ReflectionModel::BlinnPhong, ReflectionModel::CookTorrance}) {
        u.reflection = model;
        u.terms = kAllTerms;
        const LightingTerms<vec3> all = surfaceTerms<float, vec3>(P, N, u.albedo(), u);
        vec3 sum(0.0f);
        for (std::uint8_t bit : {kEmissionTerm, kAmbientTerm, kDiffuseTerm, kSpecularTerm}) {
            u.terms = bit;
            const LightingTerms<vec3> one = surfaceTerms<float, vec3>(P, N, u.albedo(), u);
            sum += one.sum();
            const vec3 expected = bit == kEmissionTerm  ? all.emission
                                  : bit == kAmbientTerm ? all.ambient
                                  : bit == kDiffuseTerm ? all.diffuse
                                                        : all.specular;
            EXPECT_EQ(one.sum(), expected) << int(bit);
        }
        EXPECT_NEAR(sum.r, all.sum().r, 1e-6f);
        EXPECT_NEAR(sum.g, all.sum().g, 1e-6f);
        EXPECT_GT(all.diffuse.r, 0.0f);
        EXPECT_GT(all.specular.r, 0.0f);
    }
}

// Facet lights the side facing the viewer; OpenGL 1.x (one-sided) leaves a back-facing normal unlit.
TEST(SurfaceShader, TwoSidedFlipLightsTheSideFacingTheViewer) {
    SurfaceUniforms u;
    u.lightCount = 1;
    u.lights[0].kind = LightKind::Directional;
    u.lights[0].direction = vec3(0.0f, 0.0f, -1.0f);  // travelling away from the eye, like the view
    u.material.diffuse = vec3(0.5f);
    u.material.specular = vec3(0.0f);
    const vec3 P(0.0f, 0.0f, -5.0f), awayFromViewer(0.0f, 0.0f, -1.0f);
    const auto diffuse = [&] {
        return surfaceTerms<float, vec3>(P, awayFromViewer, u.albedo(), u).diffuse.r;
    };
    u.twoSidedFlip = true;
    EXPECT_FLOAT_EQ(diffuse(), 0.5f);
    u.twoSidedFlip = false;
    EXPECT_FLOAT_EQ(diffuse(), 0.0f);
}

// The same through each shader, in one lane and in eight: the flip is in the one body they share.
template <ShadingFrequency kFrequency>
void expectTwoSidedFlip(const char* what) {
    SurfaceUniforms u;
    u.lightCount = 1;
    u.lights[0].kind = LightKind::Directional;
    u.lights[0].direction = vec3(0.0f, 0.0f, -1.0f);
    u.material.diffuse = vec3(0.5f);
    u.material.specular = vec3(0.0f);
    const MeshVertex v{vec3(0.0f, 0.0f, -5.0f), vec3(0.0f, 0.0f, -1.0f), vec2(0.0f)};  // facing away
    for (bool batch : {false, true}) {
        u.twoSidedFlip = true;
        EXPECT_FLOAT_EQ(shadeOnce<kFrequency>(v, u, batch).r, 0.5f) << what << (batch ? ", eight lanes" : "");
        u.twoSidedFlip = false;
        EXPECT_FLOAT_EQ(shadeOnce<kFrequency>(v, u, batch).r, 0.0f) << what << (batch ? ", eight lanes" : "");
    }
}

TEST(SurfaceShader, TwoSidedFlipAtEveryFrequencyAndLaneWidth) {
    expectTwoSidedFlip<ShadingFrequency::Phong>("per pixel");
    expectTwoSidedFlip<ShadingFrequency::Gouraud>("per vertex");
    expectTwoSidedFlip<ShadingFrequency::Flat>("flat");
}

// lighting-deck-A.txt clamps N·V to 0 where the viewer sees the underside, where Facet flips N and the gl
// preset leaves it: with a normal facing away, a light on the viewer's side lights it under the flip
// only, a light behind it under "as given" only, and clamping gives 0 for both; a normal facing the viewer
// is lit as before. At every frequency and lane width. Catches: the clamp not applied (lit), applied to
// front faces, or applied before the flip's test in one path only.
template <ShadingFrequency kFrequency>
void expectClampNdotV(const char* what) {
    SurfaceUniforms u;
    u.lightCount = 1;
    u.lights[0].kind = LightKind::Directional;
    u.material.diffuse = vec3(0.5f);
    u.material.specular = vec3(0.0f);
    const MeshVertex away{vec3(0.0f, 0.0f, -5.0f), vec3(0.0f, 0.0f, -1.0f), vec2(0.0f)};
    const MeshVertex facing{vec3(0.0f, 0.0f, -5.0f), vec3(0.0f, 0.0f, 1.0f), vec2(0.0f)};
    const vec3 fromViewerSide(0.0f, 0.0f, -1.0f), fromBehind(0.0f, 0.0f, 1.0f);  // the way the light travels
    struct Case {
        bool flip, clamp;
        vec3 direction;
        const MeshVertex* vertex;
        float expected;
    };
    for (const Case& c :
         {Case{true, false, fromViewerSide, &away, 0.5f}, Case{false, true, fromViewerSide, &away, 0.0f},
          Case{false, false, fromBehind, &away, 0.5f}, Case{false, true, fromBehind, &away, 0.0f},
          Case{false, true, fromViewerSide, &facing, 0.5f}}) {
        u.twoSidedFlip = c.flip;
        u.clampNdotV = c.clamp;
        u.lights[0].direction = c.direction;
        for (bool batch : {false, true})
            EXPECT_FLOAT_EQ(shadeOnce<kFrequency>(*c.vertex, u, batch).r, c.expected)
                << what << (batch ? ", eight lanes" : "") << ", flip " << c.flip << ", clamp " << c.clamp
                << ", facing " << (c.vertex == &facing);
    }
}

TEST(SurfaceShader, ClampNdotVDarkensTheUndersideAtEveryFrequencyAndLaneWidth) {
    expectClampNdotV<ShadingFrequency::Phong>("per pixel");
    expectClampNdotV<ShadingFrequency::Gouraud>("per vertex");
    expectClampNdotV<ShadingFrequency::Flat>("flat");
}

// OpenGL 1.x clamps each vertex's colour to [0, 1] before interpolating it.
TEST(SurfaceShader, ClampColorClampsPerVertexBeforeInterpolation) {
    SurfaceUniforms u;
    u.lightCount = 1;
    u.lights[0].kind = LightKind::Directional;
    u.lights[0].direction = vec3(0.0f, 0.0f, -1.0f);
    u.lights[0].diffuse = vec3(4.0f, 0.5f, 0.0f);
    u.material.diffuse = vec3(1.0f);
    u.material.specular = vec3(0.0f);
    const MeshVertex v{vec3(0.0f, 0.0f, -5.0f), vec3(0.0f, 0.0f, 1.0f), vec2(0.0f)};
    using Gouraud = SurfaceShader<ShadingFrequency::Gouraud>;
    EXPECT_FLOAT_EQ(Gouraud::fragment(Gouraud::vertex(v, u).varyings, u).r, 4.0f);
    u.clampColor = true;
    const vec4 clamped = Gouraud::fragment(Gouraud::vertex(v, u).varyings, u);
    EXPECT_FLOAT_EQ(clamped.r, 1.0f);
    EXPECT_FLOAT_EQ(clamped.g, 0.5f);
}

}  // namespace
}  // namespace facet

namespace facet {
namespace {

// The lecture's argument for Phong shading, as a test: a highlight that falls between the vertices of a
// coarse mesh is lost by Gouraud shading (the vertices see almost no specular light, and interpolating
// their colours cannot make a peak), while Phong shading, lighting every pixel with the interpolated
// normal, keeps it. Two triangles, a quad 2 × 2 units at 3 units from the eye; a point light one unit
// in front of its centre, so the mirror direction hits the eye only at the centre.
template <ShadingFrequency kFrequency>
float brightestSpecular(const SurfaceUniforms& uniforms) {
    const std::vector<MeshVertex> quad = {{vec3(-1, -1, -3), vec3(0, 0, 1), vec2(0)},
                                          {vec3(1, -1, -3), vec3(0, 0, 1), vec2(0)},
                                          {vec3(1, 1, -3), vec3(0, 0, 1), vec2(0)},
                                          {vec3(-1, 1, -3), vec3(0, 0, 1), vec2(0)}};
    const std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3};
    Framebuffer fb(64, 64);
    DrawContext context(1);
    fb.clear(vec4(0.0f), 1.0f, context.pool);
    DrawState state;
    state.viewport = {0, 0, 64, 64};
    draw<SurfaceShader<kFrequency>>(state, uniforms, std::span<const MeshVertex>(quad),
                                    std::span<const std::uint32_t>(indices), fb, context);
    float brightest = 0.0f;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            brightest = std::max(brightest, fb.color(x, y).r);
    return brightest;
}

TEST(ShadingFrequency, GouraudLosesAHighlightBetweenVerticesThatPhongShadingKeeps) {
    SurfaceUniforms u;
    u.clipFromObject = glm::perspective(glm::radians(50.0f), 1.0f, 0.1f, 10.0f);  // the eye at the origin
    u.lightCount = 1;
    u.lights[0].kind = LightKind::Point;
    u.lights[0].position = vec3(0.0f, 0.0f, -2.0f);
    u.material.diffuse = vec3(0.0f);
    u.material.specular = vec3(1.0f);
    u.material.shininess = 64.0f;
    u.terms = kSpecularTerm;
    for (ReflectionModel model : {ReflectionModel::Phong, ReflectionModel::BlinnPhong}) {
        u.reflection = model;
        // At a corner, e.g. (1, 1, −3): N·H ≈ 0.79 (Blinn) or R·V ≈ 0.35 (Phong), and 0.79^64 ≈ 3·10⁻⁷.
        const float perVertex = brightestSpecular<ShadingFrequency::Gouraud>(u);
        const float perPixel = brightestSpecular<ShadingFrequency::Phong>(u);
        EXPECT_LT(perVertex, 1e-3f) << "Gouraud: the corners see no highlight, so no pixel does";
        EXPECT_GT(perPixel, 0.9f) << "Phong shading: the pixels near the centre see the light's mirror image";
    }
}

}  // namespace
}  // namespace facet
