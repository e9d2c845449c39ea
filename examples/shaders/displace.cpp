// displace.cpp: vertex displacement: each vertex moved along its normal by a sine wave, so the surface
// ripples. The one example whose work is in the vertex part.
//
//   facet render MODEL --shader examples/shaders/displace.cpp --uniform amplitude=0.05 --uniform frequency=20
//
// A vertex at object-space position p with unit normal n moves to
//   p' = p + n · a · sin(f · p.y + φ),
// a ripple running along the model's y axis, of amplitude a (object-space units), frequency f (radians
// per unit) and phase φ (step φ from frame to frame to animate it). Only the positions move: the normals
// are the undisplaced ones (recomputing them would need the derivative of the displacement along the
// surface), so the lighting shows the original shape's shading on the rippled silhouette. The offset
// travels to the fragment part as a varying, where the step mode shows it.
#include "shaders/shader_module.h"

using namespace facet;
using namespace facet::glsl;  // GLSL's functions for one lane (float, vec3), beside the eight-lane ones

struct Displace {
    struct Uniforms : SceneUniforms {
        float amplitude = 0.03f;
        float frequency = 12.0f;
        float phase = 0.0f;
    };
    static constexpr std::tuple kUniforms{
        uniform("amplitude", &Uniforms::amplitude, "how far vertices move along the normal, object units"),
        uniform("frequency", &Uniforms::frequency, "the ripple's frequency along y, radians per unit"),
        uniform("phase", &Uniforms::phase, "the ripple's phase, radians (animate it)")};

    template <class F>
    struct VaryingsT {
        LaneVec3<F> position;  // eye space, displaced
        LaneVec3<F> normal;    // eye space, not recomputed
        F offset;              // a · sin(f · p.y + φ), this vertex's move along n
    };
    static constexpr VaryingName kVaryings[] = {{"P_eye", 3}, {"N_eye", 3}, {"offset", 1}};
    // The fragment part is written over any lane type F: the AVX-512 copy may shade sixteen at once.
    static constexpr bool kSixteenLanes = true;

    static VertexOut<VaryingsT<float>> vertex(const MeshVertex& in, const Uniforms& u) {
        const float offset = u.amplitude * sin(u.frequency * in.position.y + u.phase);
        const vec3 moved = in.position + in.normal * offset;  // p' = p + n · offset
        return {u.clipFromObject * vec4(moved, 1.0f),
                {vec3(u.viewFromObject * vec4(moved, 1.0f)), u.normalFromObject * in.normal, offset}};
    }

    template <class F>
    static LaneVec4<F> fragment(const VaryingsT<F>& in, const Uniforms& u, Fragment<F>& gl) {
        gl.record("offset", in.offset);
        // The built-in lighting at the displaced point (the scene's model, terms, fog and blend).
        const LaneVec3<F> color =
            builtinTerms<F>(in.position, in.normal, lanes<F>(u.material.diffuse), u).sum();
        gl.record("lit", color);
        return builtinOutput<F>(color, lanes<F>(u.opacity), in.position, u);
    }
};

FACET_SHADER(Displace)
