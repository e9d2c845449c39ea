// The surface shaders with a record (shading/record.h): recording is watching, the shaders' outputs are
// the very bits they are without a record, for every reflection model, shading frequency, precision,
// texture, clamp, fog and blend; and the record holds what the shader used.
#include <cstring>
#include <random>

#include <gtest/gtest.h>

#include "shaders/shaders.h"

namespace facet {
namespace {

SurfaceUniforms twoLights() {
    SurfaceUniforms u;
    u.globalAmbient = vec3(0.1f, 0.12f, 0.08f);
    u.lightCount = 2;
    u.lights[0].kind = LightKind::Point;
    u.lights[0].position = vec3(2.0f, 1.0f, 1.5f);
    u.lights[0].c1 = 0.3f;
    u.lights[0].ambient = vec3(0.05f);
    u.lights[1].kind = LightKind::Spot;
    u.lights[1].position = vec3(-2.0f, -1.0f, 0.5f);
    u.lights[1].spotDirection = normalize(vec3(1.0f, 0.5f, -1.0f));
    u.lights[1].spotCutoffDegrees = 50.0f;
    u.lights[1].spotExponent = 4.0f;
    u.material.ambient = vec3(0.3f);
    u.material.diffuse = vec3(0.6f, 0.4f, 0.2f);
    u.material.specular = vec3(0.5f);
    u.material.emission = vec3(0.01f, 0.02f, 0.0f);
    u.pbr.metalness = 0.3f;
    u.fog.density = 0.3f;
    return u;
}

Texture checker() {
    Texture t;
    t.width = t.height = 2;
    t.texels = {vec4(0.9f, 0.9f, 0.9f, 1.0f), vec4(0.3f, 0.6f, 0.2f, 0.25f), vec4(0.5f, 0.1f, 0.7f, 0.8f),
                vec4(1.0f, 1.0f, 1.0f, 0.5f)};
    return t;
}

bool sameBits(const vec4& a, const vec4& b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

// Random varyings of a shader's layout, positions in front of the eye.
template <class Varyings>
Varyings randomVaryings(std::mt19937& rng) {
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    float floats[kVaryingFloatCount<Varyings>];
    for (float& f : floats)
        f = u(rng);
    Varyings in;
    std::memcpy(&in, floats, sizeof in);
    return in;
}

TEST(SurfaceRecord, RecordingChangesNoBitOfAnyShaderOutput) {
    std::mt19937 rng(7);
    SurfaceUniforms u = twoLights();
    const Texture map = checker();
    int cases = 0;
    for (const ReflectionModel model :
         {ReflectionModel::Phong, ReflectionModel::BlinnPhong, ReflectionModel::CookTorrance})
        for (const MathPrecision precision : {MathPrecision::Exact, MathPrecision::Fast})
            for (int variant = 0; variant < 4; ++variant) {
                u.reflection = model;
                u.precision = precision;
                u.diffuseMap = variant >= 1 ? &map : nullptr;
                u.emissionMap = variant >= 2 ? &map : nullptr;
                u.clampColor = variant == 3;
                u.fog.mode = static_cast<FogMode>(variant);
                u.blend = variant == 2 ? BlendMode::Multiply : BlendMode::PremultipliedOver;
                u.brdf.fresnel = variant == 3 ? FresnelModel::Exact : FresnelModel::Schlick;
                for (int trial = 0; trial < 20; ++trial, ++cases) {
                    auto pixel = randomVaryings<PerPixelSurface::VaryingsT<float>>(rng);
                    pixel.position.z -= 3.0f;
                    FragmentRecord pixelRecord;
                    const vec4 recorded = PerPixelSurface::shade<float>(pixel, u, 1u, {}, &pixelRecord);
                    EXPECT_TRUE(
                        sameBits(recorded, SurfaceShader<ShadingFrequency::Phong>::fragment(pixel, u)));
                    EXPECT_TRUE(sameBits(vec4(pixelRecord.output.output, 0.0f), vec4(vec3(recorded), 0.0f)));
                    // The recorded fogged colour is the one the output form was made of.
                    SurfaceUniforms noFog = u;
                    noFog.fog.mode = FogMode::None;
                    const vec3 output = surfaceOutput<float>(pixelRecord.output.fog.fogged, pixelRecord.alpha,
                                                             pixel.position, noFog);
                    EXPECT_TRUE(sameBits(vec4(output, 0.0f), vec4(vec3(recorded), 0.0f)));

                    using PerVertex = PerVertexSurface<ShadingFrequency::Gouraud>;
                    auto inputs = randomVaryings<PerVertex::VertexInputsT<float>>(rng);
                    inputs.position.z -= 3.0f;
                    VertexLightingRecord vertexRecord;
                    const PerVertex::VaryingsT<float> lit =
                        PerVertex::lightVertex<float>(inputs, u, &vertexRecord);
                    const PerVertex::VaryingsT<float> plain = PerVertex::lightVertex<float>(inputs, u);
                    EXPECT_EQ(std::memcmp(&lit, &plain, sizeof lit), 0);
                    FragmentRecord fragmentRecord;
                    const vec4 shaded = PerVertex::shade<float>(lit, u, 1u, {}, &fragmentRecord);
                    EXPECT_TRUE(sameBits(shaded, SurfaceShader<ShadingFrequency::Gouraud>::fragment(lit, u)));
                    EXPECT_EQ(fragmentRecord.diffuseMapped, u.diffuseMap != nullptr);
                }
            }
    EXPECT_EQ(cases, 3 * 2 * 4 * 20);
}

}  // namespace
}  // namespace facet
