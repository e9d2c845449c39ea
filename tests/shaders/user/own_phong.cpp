// A test shader of one's own that is the built-in per-pixel surface shader written with its formula
// functions (shaders/shaders.h: surfaceTerms, surfaceOutput): the same image, bit for bit, as the
// built-in per-pixel shading of the scene's reflection model. --uniform specular=false leaves the
// specular term out. Used by facet compare --against's tests.
#include "shaders/shader_module.h"
using namespace facet;

struct OwnPhong {
    struct Uniforms : SceneUniforms {
        bool specular = true;
    };
    static constexpr std::tuple kUniforms{uniform("specular", &Uniforms::specular, "add the specular term")};
    template <class F>
    struct VaryingsT {
        LaneVec3<F> position;  // eye space
        LaneVec3<F> normal;    // eye space
        LaneVec2<F> uv;
    };
    static constexpr VaryingName kVaryings[] = {{"P_eye", 3}, {"N_eye", 3}, {"uv", 2}};
    static constexpr bool kSixteenLanes = true;  // as the built-in shader: two batches a call with AVX-512
    static constexpr int kDerivativeVarying = 6;

    static VertexOut<VaryingsT<float>> vertex(const MeshVertex& in, const Uniforms& u) {
        return {u.clipFromObject * vec4(in.position, 1.0f),
                {vec3(u.viewFromObject * vec4(in.position, 1.0f)), u.normalFromObject * in.normal, in.uv}};
    }
    template <class F>
    static LaneVec4<F> fragment(const VaryingsT<F>& in, const Uniforms& u, Fragment<F>& gl) {
        using V3 = LaneVec3<F>;
        V3 albedo(u.albedo());
        F alpha = lanes<F>(u.opacity);
        if (u.diffuseMap) {
            const LaneVec4<F> texel = gl.texture(u.diffuseMap, in.uv, u);
            albedo = albedo * rgb(texel);
            alpha = alpha * texel.w;
        }
        LightingTerms<V3> t = surfaceTerms<F>(in.position, in.normal, albedo, u);
        if (u.emissionMap) t.emission = t.emission * rgb(gl.texture(u.emissionMap, in.uv, u));
        if (!u.specular) t.specular = V3(vec3(0.0f));
        V3 c = t.sum();
        if (u.clampColor) c = detail::clamp01(c);
        return withAlpha(surfaceOutput<F>(c, alpha, in.position, u), alpha);
    }
};
FACET_SHADER(OwnPhong)
