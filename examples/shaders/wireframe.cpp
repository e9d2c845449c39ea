// wireframe.cpp: the triangles' edges drawn over the lit surface, from the barycentric coordinates
// (GLSL's gl_BaryCoordEXT), and optionally only the edges: the interior discarded.
//
//   facet render MODEL --shader examples/shaders/wireframe.cpp --uniform width=0.03 --uniform hollow=true
//
// A pixel inside a triangle has barycentrics λ0, λ1, λ2 ≥ 0, summing to 1, with λk = 0 on the edge
// opposite vertex k. So d = min(λ0, λ1, λ2) is 0 on an edge and grows towards the middle: the pixel is
// on the wire where d < width. The width is in barycentric units, a fraction of each triangle's size
// (its height over the edge), so big triangles get thicker lines than small ones; a smoothstep over
// the last half of it softens the line's inner border. The interior, d ≥ width, is lit as the built-in
// shader lights it, or discarded (no colour, no depth) when `hollow` is set: the fragment part then
// returns FragmentOut, whose `discard` mask drops those fragments.
#include "shaders/shader_module.h"

using namespace facet;
using namespace facet::glsl;  // GLSL's functions for one lane (float, vec3), beside the eight-lane ones

struct Wireframe {
    struct Uniforms : SceneUniforms {
        float width = 0.04f;
        vec3 wire{0.0f, 0.0f, 0.0f};
        bool hollow = false;
    };
    static constexpr std::tuple kUniforms{
        uniform("width", &Uniforms::width, "the line's width, in barycentric units (0.01 to 0.1)"),
        uniform("wire", &Uniforms::wire, "the line's colour, linear RGB"),
        uniform("hollow", &Uniforms::hollow, "discard the triangles' interiors: edges only")};

    // Ask the pipeline for the barycentrics (Fragment::barycentric); shaders that do not ask pay nothing.
    static constexpr bool kBarycentrics = true;

    template <class F>
    struct VaryingsT {
        LaneVec3<F> position;  // eye space
        LaneVec3<F> normal;    // eye space
    };
    static constexpr VaryingName kVaryings[] = {{"P_eye", 3}, {"N_eye", 3}};
    // The fragment part is written over any lane type F: the AVX-512 copy may shade sixteen at once.
    static constexpr bool kSixteenLanes = true;

    static VertexOut<VaryingsT<float>> vertex(const MeshVertex& in, const Uniforms& u) {
        return {u.clipFromObject * vec4(in.position, 1.0f),
                {vec3(u.viewFromObject * vec4(in.position, 1.0f)), u.normalFromObject * in.normal}};
    }

    template <class F>
    static FragmentOut<F> fragment(const VaryingsT<F>& in, const Uniforms& u, Fragment<F>& gl) {
        using V3 = LaneVec3<F>;
        // d = min(λ0, λ1, λ2): the distance to the nearest edge, in barycentric units.
        const V3& lambda = gl.barycentric;
        const F d = min(min(lambda.x, lambda.y), lambda.z);
        gl.record("lambda", lambda);
        gl.record("d", d);

        // The surface as the built-in shader lights it (the scene's reflection model, all its terms).
        const LightingTerms<V3> terms =
            builtinTerms<F>(in.position, in.normal, lanes<F>(u.material.diffuse), u);
        // 0 on the wire, rising to 1 over the inner half of the line: mix(wire, surface, t).
        const F t = smoothstep(0.5f * u.width, u.width, d);
        gl.record("t", t);
        const V3 color = mix(lanes<F>(u.wire), terms.sum(), t);

        // The interior is d ≥ width; hollow: discard it.
        LaneMask<F> discard = d >= u.width;
        if (!u.hollow) discard = LaneMask<F>{};  // no lane discards
        return {builtinOutput<F>(color, lanes<F>(u.opacity), in.position, u), discard};
    }
};

FACET_SHADER(Wireframe)
