// A shader without its fragment part (tests/cli/user_shader_cli_test.cpp): shader_module.h's
// checkParts() stops the compile with a static_assert saying what a fragment part looks like.
#include "shaders/shader_module.h"
using namespace facet;

struct Partial {
    struct Uniforms : SceneUniforms {};
    template <class F>
    struct VaryingsT {
        LaneVec3<F> normal;
    };
    static constexpr VaryingName kVaryings[] = {{"N_eye", 3}};
    static VertexOut<VaryingsT<float>> vertex(const MeshVertex& in, const Uniforms& u) {
        return {u.clipFromObject * vec4(in.position, 1.0f), {u.normalFromObject * in.normal}};
    }
};
FACET_SHADER(Partial)
