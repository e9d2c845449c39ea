// The built-in shader of `facet render`: per-pixel Lambert diffuse and Blinn-Phong specular over the
// scene's lights, with the material's emission and the global ambient term.
#pragma once

#include <array>
#include <cstddef>

#include "mesh.h"
#include "shader.h"
#include "texture.h"
#include "wide.h"

namespace facet {

inline constexpr int kMaxLights = 8;

struct ShaderLight {
    vec4 positionOrDirection{0.0f};  // world space; w = 0: direction the light travels, w = 1: a point light
    vec3 color{1.0f};                // linear RGB, intensity included
};

// Material colours here are linear (decoded from the file's sRGB values by the renderer).
struct ShaderMaterial {
    vec3 ambient{0.0f};                   // k_a
    vec3 diffuse{0.8f};                   // k_d
    vec3 specular{0.0f};                  // k_s
    vec3 emission{0.0f};                  // k_e
    float shininess = 32.0f;              // n
    float opacity = 1.0f;                 // d, or 1 − Tr (not applied yet: see fragment())
    const Texture* diffuseMap = nullptr;  // multiplies k_d when set
};

struct BlinnPhongShader {
    using Attributes = MeshVertex;
    struct Varyings {
        vec3 worldPosition;
        vec3 normal;  // world space, not normalised after interpolation
        vec2 uv;
    };
    struct Uniforms {
        mat4 clipFromObject{1.0f};
        mat4 worldFromObject{1.0f};
        mat3 normalFromObject{1.0f};  // transpose(inverse(mat3(worldFromObject)))
        vec3 eyeWorld{0.0f};
        vec3 globalAmbient{0.0f};
        int lightCount = 0;
        std::array<ShaderLight, kMaxLights> lights{};
        ShaderMaterial material;
    };

    static VertexOut<Varyings> vertex(const Attributes& in, const Uniforms& u) {
        const vec4 worldPosition = u.worldFromObject * vec4(in.position, 1.0f);
        return {u.clipFromObject * vec4(in.position, 1.0f),
                {vec3(worldPosition), u.normalFromObject * in.normal, in.uv}};
    }

    // c = k_e + a_global ⊗ k_a + Σ_lights c_light ⊗ (k_d·max(N·L, 0) + k_s·max(N·H, 0)^n),
    // H = normalize(L + V), the specular term only where N·L > 0 (Blinn 1977).
    // Written once for both lane types: F, V3 = float, vec3 (one fragment) or Float8, Vec3x8 (eight).
    template <class F, class V3>
    static V3 lighting(const V3& worldPosition, const V3& normal, const V3& kd, const Uniforms& u) {
        const ShaderMaterial& m = u.material;
        V3 N = normalize(normal);
        const V3 V = normalize(u.eyeWorld - worldPosition);
        // Seen from behind (an open mesh with culling off): light the side facing the viewer.
        N = select(dot(N, V) < 0.0f, -N, N);

        V3 color(m.emission + u.globalAmbient * m.ambient);
        for (int i = 0; i < u.lightCount; ++i) {
            const ShaderLight& light = u.lights[i];
            const V3 L = light.positionOrDirection.w == 0.0f
                             ? V3(-vec3(light.positionOrDirection))
                             : normalize(vec3(light.positionOrDirection) - worldPosition);
            const F NdotL = dot(N, L);
            const V3 H = normalize(L + V);
            const F lit = select(NdotL > 0.0f, 1.0f, 0.0f);
            const F specular = pow(max(dot(N, H), 0.0f), m.shininess) * lit;
            color += light.color * (kd * max(NdotL, 0.0f) + m.specular * specular);
        }
        return color;
    }

    static vec4 fragment(const Varyings& in, const Uniforms& u) {
        const ShaderMaterial& m = u.material;
        vec3 kd = m.diffuse;
        if (m.diffuseMap) kd *= vec3(sampleBilinear(*m.diffuseMap, in.uv));
        // Drawn opaque: blending transparent surfaces needs them sorted, which the renderer does not do
        // yet, so the material's opacity is carried but not applied.
        return vec4(lighting<float, vec3>(in.worldPosition, in.normal, kd, u), 1.0f);
    }

    // The same for eight fragments at once (the pipeline prefers this when a shader has it).
    static Vec4x8 fragmentBatch(const FragmentBatch& in, const Uniforms& u) {
        constexpr int kPosition = offsetof(Varyings, worldPosition) / sizeof(float);
        constexpr int kNormal = offsetof(Varyings, normal) / sizeof(float);
        constexpr int kUv = offsetof(Varyings, uv) / sizeof(float);
        const ShaderMaterial& m = u.material;
        Vec3x8 kd(m.diffuse);
        if (m.diffuseMap) {
            const Vec2x8 uv = in.vec2At(kUv);
            for (int lane = 0; lane < 8; ++lane) {
                if (!((in.mask >> lane) & 1)) continue;
                const vec4 texel = sampleBilinear(*m.diffuseMap, vec2(uv.x[lane], uv.y[lane]));
                kd.x[lane] *= texel.r;
                kd.y[lane] *= texel.g;
                kd.z[lane] *= texel.b;
            }
        }
        const Vec3x8 c = lighting<Float8, Vec3x8>(in.vec3At(kPosition), in.vec3At(kNormal), kd, u);
        return {c.x, c.y, c.z, splat(1.0f)};
    }
};

}  // namespace facet
