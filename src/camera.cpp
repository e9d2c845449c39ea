#include "camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace facet {

Camera frameCamera(const CameraSpec& spec, const Bounds& bounds, float aspect) {
    Camera camera;
    camera.fovyDegrees = spec.fovyDegrees;
    camera.up = spec.up;
    const vec3 centre = bounds.centre();
    const float radius = std::max(bounds.radius(), 1e-6f);
    camera.target = spec.target.value_or(centre);

    if (spec.eye) {
        camera.eye = *spec.eye;
    } else {
        // Look from the front, a little from above and to the right, at the distance where all eight
        // corners of the box fit the view: a corner at (x, y) across and z towards the eye from the
        // target is inside when |x| ≤ tan(fovx/2)·(d − z) and |y| ≤ tan(fovy/2)·(d − z).
        const vec3 towardsEye = normalize(vec3(0.3f, 0.3f, 1.0f));
        const vec3 right = normalize(cross(camera.up, towardsEye));
        const vec3 up = cross(towardsEye, right);
        const float tanHalfFovy = std::tan(glm::radians(spec.fovyDegrees) * 0.5f);
        const float tanHalfFovx = tanHalfFovy * aspect;
        float distance = 0.0f;
        for (int corner = 0; corner < 8; ++corner) {
            const vec3 p((corner & 1) ? bounds.max.x : bounds.min.x,
                         (corner & 2) ? bounds.max.y : bounds.min.y,
                         (corner & 4) ? bounds.max.z : bounds.min.z);
            const vec3 d = p - camera.target;
            const float z = dot(d, towardsEye);
            distance = std::max({distance, z + std::abs(dot(d, right)) / tanHalfFovx,
                                 z + std::abs(dot(d, up)) / tanHalfFovy});
        }
        // A small margin, and never inside the bounding sphere.
        camera.eye = camera.target + std::max(1.1f * distance, 1.05f * radius) * towardsEye;
    }

    // Near and far hug the bounding sphere as seen from the eye; an eye inside the sphere keeps a near
    // plane at a thousandth of the scene's size.
    const float toCentre = length(centre - camera.eye);
    camera.near = spec.near.value_or(std::max(0.95f * (toCentre - radius), 1e-3f * radius));
    camera.far = spec.far.value_or(std::max(1.05f * (toCentre + radius), camera.near * 2.0f));

    camera.viewFromWorld = glm::lookAt(camera.eye, camera.target, camera.up);
    camera.clipFromView = glm::perspective(glm::radians(camera.fovyDegrees), aspect, camera.near, camera.far);
    return camera;
}

}  // namespace facet
