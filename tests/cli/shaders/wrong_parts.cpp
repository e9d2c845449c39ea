// A shader whose parts are wrong (tests/cli/user_shader_cli_test.cpp): its vertex part returns a bare
// position, not VertexOut<VaryingsT<float>>, and it has no fragment part. shader_module.h's
// checkParts() stops the compile with a static_assert for each, saying how the part is written.
#include "shaders/shader_module.h"
using namespace facet;

struct WrongParts {
    struct Uniforms : SceneUniforms {};
    template <class F>
    struct VaryingsT {
        LaneVec3<F> normal;
    };
    static constexpr VaryingName kVaryings[] = {{"N_eye", 3}};
    static vec4 vertex(const MeshVertex& in, const Uniforms& u) {
        return u.clipFromObject * vec4(in.position, 1.0f);
    }
};
FACET_SHADER(WrongParts)
