// toon.cpp: cel ("toon") shading: the light on a surface falls into a few flat bands instead of a smooth
// ramp, and silhouettes are drawn in ink.
//
//   facet render MODEL --shader examples/shaders/toon.cpp --uniform bands=3 --uniform outline=0.3
//
// The diffuse part of the lighting equation, summed over the scene's lights j,
//   I = Σ_j att_j · spot_j · max(n·l_j, 0),
// is what a Lambertian surface reflects (the lectures' i_diff without the colours). Toon shading
// quantises it: with B bands, band k = min(⌊I·B⌋, B − 1) and the surface shows the level k/(B − 1), so
// B distinct shades from dark to fully lit. The outline uses the view vector v: where n·v is small the
// surface turns away from the eye, which happens at the silhouette; there the shader paints the ink.
#include <algorithm>

#include "shaders/shader_module.h"

using namespace facet;
using namespace facet::glsl;  // GLSL's functions for one lane (float, vec3), beside the eight-lane ones

struct Toon {
    // The scene's uniforms, and ours with their defaults (the scene file or --uniform override them).
    struct Uniforms : SceneUniforms {
        int bands = 4;
        float outline = 0.25f;
        vec3 ink{0.02f, 0.02f, 0.05f};
    };
    static constexpr std::tuple kUniforms{
        uniform("bands", &Uniforms::bands, "how many flat shades the light falls into (2 or more)"),
        uniform("outline", &Uniforms::outline, "n·v below this is drawn in ink (0 turns outlines off)"),
        uniform("ink", &Uniforms::ink, "the outline's colour, linear RGB")};

    template <class F>
    struct VaryingsT {
        LaneVec3<F> position;  // eye space: the eye at the origin, looking down −z
        LaneVec3<F> normal;    // eye space
        LaneVec2<F> uv;        // texture coordinates, for the material's diffuse map
    };
    static constexpr VaryingName kVaryings[] = {{"P_eye", 3}, {"N_eye", 3}, {"uv", 2}};
    // The fragment part is written over any lane type F: the AVX-512 copy may shade sixteen at once.
    static constexpr bool kSixteenLanes = true;

    static VertexOut<VaryingsT<float>> vertex(const MeshVertex& in, const Uniforms& u) {
        return {u.clipFromObject * vec4(in.position, 1.0f),
                {vec3(u.viewFromObject * vec4(in.position, 1.0f)), u.normalFromObject * in.normal, in.uv}};
    }

    template <class F>
    static LaneVec4<F> fragment(const VaryingsT<F>& in, const Uniforms& u, Fragment<F>& gl) {
        using V3 = LaneVec3<F>;
        const V3 P = in.position;
        // n, turned towards the eye when the scene lights both sides, and v, both unit length, made as
        // the built-in shaders make them (shaders/formulas.h).
        const V3 N = unitVector<F>(facingNormal<F>(in.normal, P, u), u);
        const V3 V = viewVector<F>(P, u);

        // I = Σ att·spot·max(n·l, 0): how much light arrives, each light's colour left out.
        F light = lanes<F>(0.0f);
        for (const LightParams& source : u.activeLights()) {
            const LightVector<F, V3> toLight = lightVectorAt<F>(source, P, u);  // l and the distance
            light = light + lightReach<F>(source, toLight, u) * max(dot(N, toLight.L), 0.0f);
        }
        gl.record("I", light);

        // The band: ⌊I·B⌋, at most B − 1 (I = 1 and above is the brightest band), as a level in [0, 1].
        const float bands = static_cast<float>(std::max(u.bands, 2));
        const F band = min(floor(min(light, 1.0f) * bands), bands - 1.0f);
        const F level = band * (1.0f / (bands - 1.0f));
        gl.record("band", band);

        // The flat colour: the ambient term m_amb ⊗ a_global, plus the material's diffuse colour (times
        // its texture, white without one) at the band's level.
        const V3 albedo = V3(u.material.diffuse) * rgb(gl.texture(u.diffuseMap, in.uv, u));
        const V3 shade = globalAmbientTerm<F>(u) + albedo * level;

        // The outline: n·v is near 0 where the surface turns away from the eye.
        const F NdotV = dot(N, V);
        gl.record("n.v", NdotV);
        const V3 color = select(NdotV < u.outline, lanes<F>(u.ink), shade);
        return withAlpha(color, lanes<F>(1.0f));
    }
};

FACET_SHADER(Toon)
