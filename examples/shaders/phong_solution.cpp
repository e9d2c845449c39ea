// phong_solution.cpp: the Phong reflection model written out term by term, the solution of
// phong_assignment.cpp. It draws what `facet render` draws with "reflection": "phong" (per-pixel
// lighting): the same numbers, bit for bit (tests/shaders/examples_test.cpp checks it), because each term
// calls the very formula the renderer runs (shaders/formulas.h) and adds the terms up in its order.
//
//   facet render MODEL --shader examples/shaders/phong_solution.cpp
//
// The lighting equation, in the lecture notes' notation (lights j; unit vectors n to the viewer's side,
// l_j towards light j, v towards the eye; ⊗ multiplies colours channel by channel):
//   i = i_em + m_amb ⊗ a_global + Σ_j att_j · spot_j · (i_amb,j + i_diff,j + i_spec,j)
//   i_amb,j  = m_amb ⊗ s_amb,j                       (ambient: light from everywhere)
//   i_diff,j = m_diff ⊗ s_diff,j · max(n·l_j, 0)      (Lambert's cosine law)
//   i_spec,j = m_spec ⊗ s_spec,j · max(r_j·v, 0)^m_shi,  r_j = 2(n·l_j)n − l_j   (Phong)
// and no specular light from a light behind the surface (n·l_j ≤ 0). att_j = 1/(c0 + c1·d + c2·d²) with
// d the distance to a point or spot light, spot_j the spot light's cone; both 1 for a directional light.
#include "shaders/shader_module.h"

using namespace facet;
using namespace facet::glsl;  // GLSL's functions for one lane (float, vec3), beside the eight-lane ones

struct PhongSolution {
    struct Uniforms : SceneUniforms {};  // the material and lights come from the scene

    template <class F>
    struct VaryingsT {
        LaneVec3<F> position;  // eye space: the eye at the origin
        LaneVec3<F> normal;    // eye space, interpolated (Phong shading: renormalised per pixel)
        LaneVec2<F> uv;        // for the material's textures
    };
    static constexpr VaryingName kVaryings[] = {{"P_eye", 3}, {"N_eye", 3}, {"uv", 2}};
    // The fragment part is written over any lane type F: the AVX-512 copy may shade sixteen at once.
    static constexpr bool kSixteenLanes = true;
    static constexpr int kDerivativeVarying = 6;  // uv's screen derivatives, for trilinear filtering

    static VertexOut<VaryingsT<float>> vertex(const MeshVertex& in, const Uniforms& u) {
        return {u.clipFromObject * vec4(in.position, 1.0f),
                {vec3(u.viewFromObject * vec4(in.position, 1.0f)), u.normalFromObject * in.normal, in.uv}};
    }

    template <class F>
    static LaneVec4<F> fragment(const VaryingsT<F>& in, const Uniforms& u, Fragment<F>& gl) {
        using V3 = LaneVec3<F>;
        const V3 P = in.position;

        // The material's colours; a diffuse texture tints m_diff and its alpha the opacity (without a
        // texture, texture() gives white and changes nothing).
        const LaneVec4<F> texel = gl.texture(u.diffuseMap, in.uv, u);
        const V3 mDiff = V3(u.material.diffuse) * rgb(texel);
        const F alpha = lanes<F>(u.opacity) * texel.w;

        // n turned towards the viewer (two-sided lighting), then n and v made unit length.
        const V3 N = unitVector<F>(facingNormal<F>(in.normal, P, u), u);
        const V3 V = viewVector<F>(P, u);
        gl.record("n", N);
        gl.record("v", V);

        // Shadows, when the scene casts them: per light, the share of it that reaches P.
        F visibility[kMaxLights];
        if (u.shadows)
            lightVisibilities<F, V3>(*u.shadows, u.activeLights(), P, facingNormal<F>(in.normal, P, u),
                                     visibility);

        V3 ambient = globalAmbientTerm<F>(u);  // m_amb ⊗ a_global
        V3 diffuse(vec3(0.0f)), specular(vec3(0.0f));
        int j = 0;
        for (const LightParams& light : u.activeLights()) {
            const LightVector<F, V3> toLight = lightVectorAt<F>(light, P, u);  // l_j and d
            const V3& L = toLight.L;
            const F reach = lightReach<F>(light, toLight, u);  // att_j · spot_j
            const F lit = u.shadows ? reach * visibility[j] : reach;
            const F NdotL = dot(N, L);
            gl.record("n.l", NdotL);

            if (light.ambient != vec3(0.0f)) ambient += ambientTerm(light.ambient, u.material.ambient, reach);
            diffuse += lambertTerm(mDiff, light.diffuse, lit, NdotL);

            // Phong's specular term: r = 2(n·l)n − l, spec = max(r·v, 0)^m_shi (0 where n·l ≤ 0).
            const V3 R = phongReflected(N, L, NdotL);
            const F RdotV = dot(R, V);
            const F spec = specularPowerOf<F>(NdotL, RdotV, u.material.shininess, u);
            gl.record("r.v", RdotV);
            gl.record("spec", spec);
            specular += specularTerm(light.specular, u.material.specular, lit, spec);
            ++j;
        }

        // i_em (an emission texture tints it), then the sum in the built-in order.
        const V3 emission = V3(u.emissionTerm()) * rgb(gl.texture(u.emissionMap, in.uv, u));
        V3 color = emission + ambient + diffuse + specular;
        if (u.clampColor) color = V3(saturate(color.x), saturate(color.y), saturate(color.z));  // OpenGL 1.x
        gl.record("ambient", ambient);
        gl.record("diffuse", diffuse);
        gl.record("specular", specular);
        gl.record("i", color);
        return builtinOutput<F>(color, alpha, P, u);  // the scene's fog, then its blend's form
    }
};

FACET_SHADER(PhongSolution)
