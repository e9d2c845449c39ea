// checker.cpp: a procedural checkerboard, computed per pixel from the texture coordinates (or from the
// object-space position, a "solid" checker that needs no uv), lit by the built-in diffuse term.
//
//   facet render MODEL --shader examples/shaders/checker.cpp --uniform scale=16
//
// A procedural texture is a function of a position instead of an image: here the cells of a grid of
// side 1/scale. With q = ⌊scale·uv⌋ (whole cell numbers), the cell is dark where q.x + q.y is odd,
// which alternates along both axes; in 3D, q.x + q.y + q.z. mod(s, 2) is GLSL's s − 2⌊s/2⌋, 0 or 1 for
// whole s, negative ones included. The chosen colour is the material's diffuse colour m_diff in the
// lighting equation's ambient and diffuse terms:
//   i = m_diff ⊗ a_global + Σ_j att_j · spot_j · m_diff ⊗ s_diff,j · max(n·l_j, 0).
#include "shaders/shader_module.h"

using namespace facet;
using namespace facet::glsl;  // GLSL's functions for one lane (float, vec3), beside the eight-lane ones

struct Checker {
    struct Uniforms : SceneUniforms {
        float scale = 8.0f;
        vec3 colorA{0.85f, 0.85f, 0.8f};
        vec3 colorB{0.1f, 0.12f, 0.3f};
        bool fromPosition = false;
    };
    static constexpr std::tuple kUniforms{
        uniform("scale", &Uniforms::scale, "cells per unit of uv (or of object space)"),
        uniform("colorA", &Uniforms::colorA, "the even cells' colour, linear RGB"),
        uniform("colorB", &Uniforms::colorB, "the odd cells' colour, linear RGB"),
        uniform("fromPosition", &Uniforms::fromPosition, "cells of object-space position instead of uv")};

    template <class F>
    struct VaryingsT {
        LaneVec3<F> position;  // eye space, for the lighting
        LaneVec3<F> normal;    // eye space
        LaneVec2<F> uv;
        LaneVec3<F> objectPosition;  // object space: the solid checker stays on the surface as it moves
    };
    static constexpr VaryingName kVaryings[] = {{"P_eye", 3}, {"N_eye", 3}, {"uv", 2}, {"P_obj", 3}};
    // The fragment part is written over any lane type F: the AVX-512 copy may shade sixteen at once.
    static constexpr bool kSixteenLanes = true;

    static VertexOut<VaryingsT<float>> vertex(const MeshVertex& in, const Uniforms& u) {
        return {u.clipFromObject * vec4(in.position, 1.0f),
                {vec3(u.viewFromObject * vec4(in.position, 1.0f)), u.normalFromObject * in.normal, in.uv,
                 in.position}};
    }

    template <class F>
    static LaneVec4<F> fragment(const VaryingsT<F>& in, const Uniforms& u, Fragment<F>& gl) {
        using V3 = LaneVec3<F>;
        // The sum of the cell numbers: its parity picks the colour.
        F cells;
        if (u.fromPosition) {
            const V3 q = floor(in.objectPosition * u.scale);
            cells = q.x + q.y + q.z;
        } else {
            const LaneVec2<F> q = floor(in.uv * u.scale);
            cells = q.x + q.y;
        }
        const auto odd = mod(cells, 2.0f) >= 1.0f;  // a mask: bool in one lane, all-ones lanes in eight
        const V3 albedo = select(odd, lanes<F>(u.colorB), lanes<F>(u.colorA));
        gl.record("cells", cells);
        gl.record("albedo", albedo);

        // Lit with the built-in diffuse (Lambert) term, per light, and an ambient floor.
        const V3 P = in.position;
        const V3 N = unitVector<F>(facingNormal<F>(in.normal, P, u), u);
        V3 color = albedo * u.globalAmbient;
        for (const LightParams& light : u.activeLights()) {
            const LightVector<F, V3> toLight = lightVectorAt<F>(light, P, u);
            const F reach = lightReach<F>(light, toLight, u);  // att · spot
            color += lambertTerm(albedo, light.diffuse, reach, dot(N, toLight.L));
        }
        gl.record("lit", color);
        return builtinOutput<F>(color, lanes<F>(u.opacity), P, u);  // the scene's fog and blend
    }
};

FACET_SHADER(Checker)
