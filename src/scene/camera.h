// The camera: view and projection matrices from a CameraSpec, framing the scene's bounding box where
// the scene leaves eye, target, near or far unset.
#pragma once

#include <string>
#include <vector>

#include "pipeline/glsl.h"
#include "scene/scene.h"

namespace facet {

struct Bounds {
    vec3 min{0.0f};
    vec3 max{0.0f};
    vec3 centre() const { return 0.5f * (min + max); }
    float radius() const { return 0.5f * length(max - min); }  // of the bounding sphere around the box
};

struct Camera {
    vec3 eye{0.0f};
    vec3 target{0.0f, 0.0f, -1.0f};
    vec3 up{0.0f, 1.0f, 0.0f};  // as used: replaced when the spec's up is along the view direction
    float fovyDegrees = 40.0f;
    float near = 0.1f;
    float far = 100.0f;  // +∞ for an infinite far plane (CameraSpec::infiniteFar)
    // The depth buffer's format (PipelineOptions::depth): reversed Z draws with a remapped projection
    // (drawnClipFromView).
    // Eye space is world space scaled by this power of two (1 for scenes of ordinary size), so that
    // eye-space coordinates stay near 1 for models of 1e30 or 1e-30 units: the shaders' float
    // lengths and dot products would overflow or underflow there. Lengths in eye space are world
    // lengths times viewScale (the renderer scales attenuation and fog to match).
    double viewScale = 1.0;
    // Computed in double, as a model far from the origin or of extreme size needs: compose other
    // matrices with these, then round to float once.
    glm::dmat4 viewFromWorldExact{1.0};
    glm::dmat4 clipFromViewExact{1.0};
    mat4 viewFromWorld{1.0f};  // the same, in float
    mat4 clipFromView{1.0f};
    std::vector<std::string> warnings;  // one line each: a replaced up vector, poor depth precision
    DepthBufferFormat depthFormat = DepthBufferFormat::Float;
};

// The projection the rasterizer draws with. clipFromViewExact is OpenGL's (near at z_c = −w_c, far at
// z_c = w_c), which the reference renderer and the step mode undo; reversed Z remaps its depth to
// z' = (w − z)/2, so near lands at z' = w' (window depth 1) and far at z' = 0 (glClipControl
// GL_ZERO_TO_ONE). That is z' = n(f + z_e)/(f − n), and z' = n for an infinite far plane, w' = −z_e.
// The other formats draw with clipFromViewExact itself.
glm::dmat4 drawnClipFromView(const Camera& camera);

// How `clipFromView`'s z_c follows its w_c (pipeline/state.h, DepthFromW): known when w_c = P[2][3]·z_e +
// P[3][3] depends on z_e alone (a perspective projection, P[2][3] ≠ 0) and z_c on z_e alone, so that
// z_e = (w_c − P[3][3])/P[2][3] and z_c = P[2][2]·z_e + P[3][2]. Not for an orthographic projection
// (w_c = 1 whatever the depth).
DepthFromW clipDepthFromW(const glm::dmat4& clipFromView);

// Fills in what `spec` leaves unset: the eye looks at the box's centre from the front (+z), a little from
// above and to the right, just far enough for the whole box to fit the view with a 10% margin; the near
// and far planes hug the box's bounding sphere (a tight near/far ratio keeps depth precision).
// Throws InputError (without a file name) when no image could show the scene: a box of no size to
// frame, a scene wholly before the near plane or beyond the far one, or a near plane so small for the
// scene's distance that every depth rounds to the far plane.
// The depth-precision checks and warnings are those of `depthFormat`'s buffer (none for reversed Z,
// whose precision is relative at every distance).
Camera frameCamera(const CameraSpec& spec, const Bounds& bounds, float aspect,
                   DepthBufferFormat depthFormat = DepthBufferFormat::Float);

}  // namespace facet
