// A shader with a mistake on line 14 (tests/cli/user_shader_cli_test.cpp checks the compiler's message
// names "compile_error.cpp:14:"): `undeclared_colour` is declared nowhere.
#include "shaders/shader_module.h"
using namespace facet;

struct Broken {
    struct Uniforms : SceneUniforms {};
    template <class F>
    struct VaryingsT {
        LaneVec3<F> normal;
    };
    static constexpr VaryingName kVaryings[] = {{"N_eye", 3}};
    static VertexOut<VaryingsT<float>> vertex(const MeshVertex& in, const Uniforms& u) {
        return {u.clipFromObject * vec4(in.position, 1.0f), {undeclared_colour}};
    }
    template <class F>
    static LaneVec4<F> fragment(const VaryingsT<F>& in, const Uniforms&, Fragment<F>&) {
        return withAlpha(in.normal, lanes<F>(1.0f));
    }
};
FACET_SHADER(Broken)
