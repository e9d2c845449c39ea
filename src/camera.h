// The camera: view and projection matrices from a CameraSpec, framing the scene's bounding box where
// the scene leaves eye, target, near or far unset.
#pragma once

#include "glsl.h"
#include "scene.h"

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
    vec3 up{0.0f, 1.0f, 0.0f};
    float fovyDegrees = 40.0f;
    float near = 0.1f;
    float far = 100.0f;
    mat4 viewFromWorld{1.0f};
    mat4 clipFromView{1.0f};
};

// Fills in what `spec` leaves unset: the eye looks at the box's centre from the front (+z), a little from
// above and to the right, just far enough for the whole box to fit the view with a 10% margin; the near
// and far planes hug the box's bounding sphere (a tight near/far ratio keeps depth precision).
Camera frameCamera(const CameraSpec& spec, const Bounds& bounds, float aspect);

}  // namespace facet
