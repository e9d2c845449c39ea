// A shader of one's own for the step mode's tests (tests/step/user_shader_step_test.cpp), after the toon
// shader of docs/shaders.md: banded N·V with an ink outline. normal_scale multiplies the normal before
// it is normalized: --uniform normal_scale=0 normalizes a zero vector, which makes NaN (the tests'
// non-finite values). Compiled by the tests at run time (not part of the build).
#include "shaders/shader_module.h"
using namespace facet;

struct ToonStep {
    struct Uniforms : SceneUniforms {
        int bands = 4;
        float outline = 0.3f;
        vec3 ink{0.0f};
        float normalScale = 1.0f;
    };
    static constexpr std::tuple kUniforms{uniform("bands", &Uniforms::bands, "steps of light"),
                                          uniform("outline", &Uniforms::outline, "N.V below this is ink"),
                                          uniform("ink", &Uniforms::ink, "outline colour"),
                                          uniform("normal_scale", &Uniforms::normalScale, "scales N")};
    template <class F>
    struct VaryingsT {
        LaneVec3<F> position;
        LaneVec3<F> normal;
    };
    static constexpr VaryingName kVaryings[] = {{"P_eye", 3}, {"N_eye", 3}};
    // Sixteen lanes where the copy has them: the trace (one lane) must still match the pixel drawn.
    static constexpr bool kSixteenLanes = true;

    static VertexOut<VaryingsT<float>> vertex(const MeshVertex& in, const Uniforms& u) {
        return {u.clipFromObject * vec4(in.position, 1.0f),
                {vec3(u.viewFromObject * vec4(in.position, 1.0f)), u.normalFromObject * in.normal}};
    }
    template <class F>
    static LaneVec4<F> fragment(const VaryingsT<F>& in, const Uniforms& u, Fragment<F>& gl) {
        using V3 = LaneVec3<F>;
        const V3 N = normalize(in.normal * lanes<F>(u.normalScale));
        const V3 V = normalize(-in.position);
        const F ndotv = dot(N, V);
        gl.record("N", N);
        gl.record("N.V", ndotv);
        V3 c = V3(u.material.diffuse) * (ndotv * lanes<F>(0.8f) + lanes<F>(0.2f));
        c = select(ndotv < lanes<F>(u.outline), V3(u.ink), c);
        gl.record("c", c);
        return withAlpha(c, lanes<F>(1.0f));
    }
};
FACET_SHADER(ToonStep)
