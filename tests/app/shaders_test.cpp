// The built-in shader's eight-lane path computes what its one-fragment path computes.
#include "shaders.h"

#include <random>

#include <gtest/gtest.h>

namespace facet {
namespace {

TEST(BlinnPhongShader, BatchMatchesScalarOnRandomFragments) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), unit(0.0f, 1.0f);
    BlinnPhongShader::Uniforms uniforms;
    uniforms.eyeWorld = vec3(0.3f, 0.5f, 4.0f);
    uniforms.globalAmbient = vec3(0.1f, 0.12f, 0.08f);
    uniforms.lightCount = 3;
    uniforms.lights[0] = {vec4(normalize(vec3(-0.3f, -1.0f, -0.5f)), 0.0f), vec3(1.0f, 0.9f, 0.8f)};
    uniforms.lights[1] = {vec4(2.0f, 1.0f, 1.5f, 1.0f), vec3(0.4f, 0.5f, 1.2f)};
    uniforms.lights[2] = {vec4(-2.0f, -1.0f, 0.5f, 1.0f), vec3(0.7f, 0.2f, 0.1f)};
    uniforms.material.ambient = vec3(0.3f);
    uniforms.material.diffuse = vec3(0.6f, 0.4f, 0.2f);
    uniforms.material.specular = vec3(0.5f);
    uniforms.material.emission = vec3(0.01f, 0.02f, 0.0f);
    for (float shininess : {0.0f, 1.0f, 12.0f, 128.0f}) {
        uniforms.material.shininess = shininess;
        for (int trial = 0; trial < 200; ++trial) {
            FragmentBatch batch;
            batch.mask = 0xff;
            BlinnPhongShader::Varyings scalar[8];
            for (int lane = 0; lane < 8; ++lane) {
                scalar[lane] = {vec3(u(rng), u(rng), u(rng)), vec3(u(rng), u(rng), u(rng)),
                                vec2(unit(rng), unit(rng))};
                const float* f = reinterpret_cast<const float*>(&scalar[lane]);
                for (int k = 0; k < kVaryingFloatCount<BlinnPhongShader::Varyings>; ++k)
                    batch.varyings[k][lane] = f[k];
            }
            const Vec4x8 wide = BlinnPhongShader::fragmentBatch(batch, uniforms);
            for (int lane = 0; lane < 8; ++lane) {
                const vec4 one = BlinnPhongShader::fragment(scalar[lane], uniforms);
                const float tolerance = 2e-5f * (1.0f + one.r + one.g + one.b);
                EXPECT_NEAR(wide.x[lane], one.r, tolerance) << "shininess " << shininess;
                EXPECT_NEAR(wide.y[lane], one.g, tolerance);
                EXPECT_NEAR(wide.z[lane], one.b, tolerance);
                EXPECT_EQ(wide.w[lane], one.a);
            }
        }
    }
}

}  // namespace
}  // namespace facet
