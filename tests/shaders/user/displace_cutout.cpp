// A test shader of one's own that moves its vertices and discards fragments: each vertex pushed
// `displacement` (object-space units) along its normal, and every fragment whose eye-space normal has a
// y above `cut` discarded (the holes show what lies behind). Lit by a headlight: the diffuse colour
// times N·V, plus a little ambient. Used by the reference's, the trade's and the bench's tests.
#include "shaders/shader_module.h"
using namespace facet;

struct DisplaceCutout {
    struct Uniforms : SceneUniforms {
        float displacement = 0.0f;
        float cut = 2.0f;  // above 1: nothing discarded
    };
    static constexpr std::tuple kUniforms{
        uniform("displacement", &Uniforms::displacement, "object-space distance along the normal"),
        uniform("cut", &Uniforms::cut, "fragments whose eye-space normal's y is above this are discarded")};
    template <class F>
    struct VaryingsT {
        LaneVec3<F> position;  // eye space
        LaneVec3<F> normal;    // eye space
    };
    static constexpr VaryingName kVaryings[] = {{"P_eye", 3}, {"N_eye", 3}};

    static VertexOut<VaryingsT<float>> vertex(const MeshVertex& in, const Uniforms& u) {
        const vec3 p = in.position + u.displacement * in.normal;
        return {u.clipFromObject * vec4(p, 1.0f),
                {vec3(u.viewFromObject * vec4(p, 1.0f)), u.normalFromObject * in.normal}};
    }
    template <class F>
    static FragmentOut<F> fragment(const VaryingsT<F>& in, const Uniforms& u, Fragment<F>&) {
        using V3 = LaneVec3<F>;
        const V3 N = normalize(in.normal);
        const V3 V = normalize(-in.position);
        const F lit = max(dot(N, V), lanes<F>(0.0f)) * lanes<F>(0.8f) + lanes<F>(0.2f);
        const V3 c = V3(u.material.diffuse) * lit;
        return {withAlpha(c, lanes<F>(1.0f)), N.y > lanes<F>(u.cut)};
    }
};
FACET_SHADER(DisplaceCutout)
