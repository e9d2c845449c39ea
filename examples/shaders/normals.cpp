// normals.cpp: the eye-space normal as a colour, the classic first shader of one's own.
//
//   facet render MODEL --shader examples/shaders/normals.cpp
//
// Each component of a unit normal n lies in [−1, 1] and a colour channel in [0, 1], so the shader maps
// c = 0.5·n + 0.5: a surface facing the camera (n = (0, 0, 1) in eye space, z towards the eye) is
// (0.5, 0.5, 1), lavender blue; one facing right is pinkish (1, 0.5, 0.5), one facing up green-ish.
// Nothing is lit: the picture shows only the geometry, which makes it a good check of a model's normals.
#include "shaders/shader_module.h"

using namespace facet;
using namespace facet::glsl;  // GLSL's functions for one lane (float, vec3), beside the eight-lane ones

struct Normals {
    // No uniforms of our own: the scene's (matrices, lights, material) are all there is.
    struct Uniforms : SceneUniforms {};

    // What the vertex part hands to the fragment part, interpolated across each triangle. Written once
    // for F = float (one fragment) and F = Float8 (eight at once).
    template <class F>
    struct VaryingsT {
        LaneVec3<F> normal;  // eye space
    };
    static constexpr VaryingName kVaryings[] = {{"N_eye", 3}};
    // The fragment part is written over any lane type F: the AVX-512 copy may shade sixteen at once.
    static constexpr bool kSixteenLanes = true;

    // The vertex part: gl_Position = clipFromObject·p, and the normal taken to eye space by the normal
    // matrix (the inverse transpose of the model-view matrix, so non-uniform scaling keeps it normal).
    static VertexOut<VaryingsT<float>> vertex(const MeshVertex& in, const Uniforms& u) {
        return {u.clipFromObject * vec4(in.position, 1.0f), {u.normalFromObject * in.normal}};
    }

    template <class F>
    static LaneVec4<F> fragment(const VaryingsT<F>& in, const Uniforms&, Fragment<F>& gl) {
        // Interpolating unit normals across a triangle shortens them (the average of two unit vectors
        // is shorter than one), so the fragment normalises again.
        const LaneVec3<F> N = normalize(in.normal);
        gl.record("N", N);  // shown by the step mode for the traced pixel
        const LaneVec3<F> color = N * 0.5f + vec3(0.5f);
        gl.record("0.5 N + 0.5", color);
        return withAlpha(color, lanes<F>(1.0f));
    }
};

FACET_SHADER(Normals)
