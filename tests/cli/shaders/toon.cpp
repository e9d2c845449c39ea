// The toon shader of the tests (tests/cli/user_shader_cli_test.cpp, tests/install/shader_module_test.sh):
// bands of light and an ink outline, three uniforms of its own (int, float, vec3).
#include "shaders/shader_module.h"
using namespace facet;

struct Toon {
    struct Uniforms : SceneUniforms {
        int bands = 4;
        float outline = 0.3f;
        vec3 ink{0.0f};
    };
    static constexpr std::tuple kUniforms{uniform("bands", &Uniforms::bands, "steps of light"),
                                          uniform("outline", &Uniforms::outline, "N.V below this is ink"),
                                          uniform("ink", &Uniforms::ink, "outline colour")};
    template <class F>
    struct VaryingsT {
        LaneVec3<F> position;
        LaneVec3<F> normal;
    };
    static constexpr VaryingName kVaryings[] = {{"P_eye", 3}, {"N_eye", 3}};

    static VertexOut<VaryingsT<float>> vertex(const MeshVertex& in, const Uniforms& u) {
        return {u.clipFromObject * vec4(in.position, 1.0f),
                {vec3(u.viewFromObject * vec4(in.position, 1.0f)), u.normalFromObject * in.normal}};
    }
    template <class F>
    static LaneVec4<F> fragment(const VaryingsT<F>& in, const Uniforms& u, Fragment<F>& gl) {
        using V3 = LaneVec3<F>;
        const V3 N = normalize(in.normal);
        const V3 V = normalize(-in.position);
        F ndotv = dot(N, V);
        gl.record("N.V", ndotv);
        V3 c = V3(u.material.diffuse) * (ndotv * lanes<F>(0.8f) + lanes<F>(0.2f));
        c = select(ndotv < lanes<F>(u.outline), V3(u.ink), c);
        return withAlpha(c, lanes<F>(1.0f));
    }
};
FACET_SHADER(Toon)
