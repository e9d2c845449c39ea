// The built-in shader of `facet render`: per-pixel Lambert diffuse and Blinn-Phong specular over the
// scene's lights, with the material's emission and the global ambient term.
#pragma once

#include <array>

#include "mesh.h"
#include "shader.h"
#include "texture.h"

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
    static vec4 fragment(const Varyings& in, const Uniforms& u) {
        const ShaderMaterial& m = u.material;
        vec3 N = normalize(in.normal);
        const vec3 V = normalize(u.eyeWorld - in.worldPosition);
        // Seen from behind (an open mesh with culling off): light the side facing the viewer.
        if (dot(N, V) < 0.0f) N = -N;
        vec3 kd = m.diffuse;
        if (m.diffuseMap) kd *= vec3(sampleBilinear(*m.diffuseMap, in.uv));

        vec3 color = m.emission + u.globalAmbient * m.ambient;
        for (int i = 0; i < u.lightCount; ++i) {
            const ShaderLight& light = u.lights[i];
            const vec3 L = light.positionOrDirection.w == 0.0f
                               ? -vec3(light.positionOrDirection)
                               : normalize(vec3(light.positionOrDirection) - in.worldPosition);
            const float NdotL = dot(N, L);
            if (NdotL <= 0.0f) continue;
            const vec3 H = normalize(L + V);
            const float specular = m.shininess > 0.0f ? pow(max(dot(N, H), 0.0f), m.shininess) : 1.0f;
            color += light.color * (kd * NdotL + m.specular * specular);
        }
        // Drawn opaque: blending transparent surfaces needs them sorted, which the renderer does not do
        // yet, so the material's opacity is carried but not applied.
        return vec4(color, 1.0f);
    }
};

}  // namespace facet
