// A discarding shader of one's own for the step mode's tests (tests/step/user_shader_step_test.cpp):
// the left half of the view (eye-space x below `cut`) is discarded, the rest is white. Compiled by the
// tests at run time (not part of the build).
#include "shaders/shader_module.h"
using namespace facet;

struct CutoutStep {
    struct Uniforms : SceneUniforms {
        float cut = 0.0f;
    };
    static constexpr std::tuple kUniforms{
        uniform("cut", &Uniforms::cut, "eye-space x below this is discarded")};
    template <class F>
    struct VaryingsT {
        LaneVec3<F> position;
    };
    static constexpr VaryingName kVaryings[] = {{"P_eye", 3}};

    static VertexOut<VaryingsT<float>> vertex(const MeshVertex& in, const Uniforms& u) {
        return {u.clipFromObject * vec4(in.position, 1.0f),
                {vec3(u.viewFromObject * vec4(in.position, 1.0f))}};
    }
    template <class F>
    static FragmentOut<F> fragment(const VaryingsT<F>& in, const Uniforms& u, Fragment<F>& gl) {
        gl.record("x", in.position.x);
        const F one = lanes<F>(1.0f);
        return {LaneVec4<F>{one, one, one, one}, in.position.x < lanes<F>(u.cut)};
    }
};
FACET_SHADER(CutoutStep)
