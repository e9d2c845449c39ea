#include "scene/camera.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "base/errors.h"

namespace facet {

namespace {

using glm::dvec3;

// One message from its parts; numbers as %g prints them. (A stream, not chains of std::string +,
// which GCC 12 reports with a false -Wrestrict.)
template <class... Parts>
std::string text(const Parts&... parts) {
    std::ostringstream out;
    (out << ... << parts);
    return out.str();
}

std::string describe(dvec3 v) {
    return text("(", v.x, ", ", v.y, ", ", v.z, ")");
}

// `up` when it lies across the unit view direction `forward`. Looking straight along it leaves the
// image's rotation undefined (lookAt would divide 0 by 0 and draw nothing); the top of the image then
// faces the world axis least aligned with up (z first), on the side a camera tilted down (or up) from
// the default front view would see there: −z looking down along +y, +z looking up.
dvec3 upAcross(dvec3 forward, dvec3 up, std::vector<std::string>& warnings) {
    const dvec3 unitUp = glm::normalize(up);
    if (glm::length(glm::cross(forward, unitUp)) >= 1e-6) return up;
    dvec3 axis(0.0, 0.0, 1.0);
    if (std::abs(unitUp.z) > 0.5)
        axis = std::abs(unitUp.y) < std::abs(unitUp.x) ? dvec3(0, 1, 0) : dvec3(1, 0, 0);
    const bool lookingUp = glm::dot(forward, unitUp) > 0.0;
    const dvec3 chosen = (lookingUp ? axis : -axis) + dvec3(0.0);  // + 0: no "-0" in the message
    warnings.push_back(text("the camera looks straight ", lookingUp ? "up" : "down", " along its up vector ",
                            describe(up),
                            ", which leaves the image's rotation open: the top of the image faces ",
                            describe(chosen), " (a scene file's \"camera.up\" chooses another)"));
    return chosen;
}

// A power of two near 1/radius for scenes far from unit size, else 1 (ordinary scenes keep eye space
// in world units): eye-space coordinates then stay near 1 (Camera::viewScale).
double viewScaleFor(double radius) {
    if (!(radius > 0.0) || (radius >= 0x1p-16 && radius <= 0x1p16)) return 1.0;
    return std::exp2(-std::round(std::log2(radius)));
}

// Depth precision for a scene that reaches nearer than the near plane (an eye inside its bounding
// sphere, or a near plane cutting into it): what is seen can start at the near plane itself, where the
// window depth f(z − n)/(z(f − n)) is 0, so the nearest depths have codes to spare; the codes run out at
// the far end, where the window depth crowds towards 1. From half a step below 1 on, 1 − ε with
// ε = 1/(2·codes), a depth rounds to the far plane, the value the buffer is cleared to, which no
// fragment passes (the test is "nearer"). Solving f(z − n)/(z(f − n)) = 1 − ε: every point farther than
// zLost = f·n/(n + ε(f − n)) (n/ε with an infinite far plane) is not drawn. The scene reaches
// zEnd = min(zBack, far), zBack the depth of the bounding box's farthest corner (from inside, the
// bounding sphere reaches well past the box). Nearer than zLost, one step of the buffer spans
// 1/(codes·d'(z)) in depth, d'(z) = f·n/(z²(f − n)): coarsest at zEnd.
void checkDepthFromInside(double near, double far, dvec3 eye, dvec3 forward, dvec3 boxMin, dvec3 boxMax,
                          double radius, double codes, const std::string& buffer,
                          std::vector<std::string>& warnings) {
    double zBack = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        const dvec3 p((corner & 1) ? boxMax.x : boxMin.x, (corner & 2) ? boxMax.y : boxMin.y,
                      (corner & 4) ? boxMax.z : boxMin.z);
        zBack = std::max(zBack, glm::dot(p - eye, forward));
    }
    if (!(zBack > near)) return;  // the box lies behind the near plane: the sphere reached past it
    const double epsilon = 0.5 / codes;
    const double zLost = std::isfinite(far) ? far * near / (near + epsilon * (far - near)) : near / epsilon;
    const double zEnd = std::min(zBack, far);
    // The near plane whose step at zEnd is 1/1024 of the scene's size 2r, as a scene seen from outside
    // is asked to have 1024 steps across it: step ≈ z²/(n·codes) when f ≫ n, so n = z²·1024/(codes·2r);
    // and at least the near plane that moves zLost beyond zEnd.
    const double enoughNear = std::max(zEnd * zEnd * 1024.0 / (codes * 2.0 * radius), zEnd / codes);
    // Nothing farther than zLost is drawn. Nearer than a thousandth of the scene's radius (the near plane a
    // camera inside the scene gets when none is given: what is closer is clipped as touching the eye),
    // nothing that matters is left to draw.
    if (zLost < 1e-3 * radius)
        throw InputError(text("the camera's near plane (", near, ") is too small for the ", buffer,
                              " depth buffer with the camera inside the scene: every depth farther than ",
                              zLost, " from the eye rounds to the far plane, and the scene reaches ", zEnd,
                              ": nothing would be drawn (a near plane of ", enoughNear, " or more works)"));
    // Nearer than zLost the buffer's steps are finest at the near plane and coarsest at zEnd; a warning
    // on the far end's steps alone would fire for the default near plane of every interior view under
    // 16 bits, so only the depths lost outright are said.
    if (zLost < zEnd)
        warnings.push_back(
            text("the camera's near plane (", near, ") is small for the ", buffer,
                 " depth buffer: every depth farther than ", zLost,
                 " from the eye rounds to the far plane and is not drawn, and the scene reaches ", zEnd,
                 " (a near plane of ", enoughNear, " or more draws all of it)"));
}

}  // namespace

glm::dmat4 drawnClipFromView(const Camera& camera) {
    if (camera.depthFormat != DepthBufferFormat::ReversedFloat) return camera.clipFromViewExact;
    glm::dmat4 reversedFromClip(1.0);  // column-major: [column][row]
    reversedFromClip[2][2] = -0.5;     // z' = −z/2 + w/2
    reversedFromClip[3][2] = 0.5;
    return reversedFromClip * camera.clipFromViewExact;
}

DepthFromW clipDepthFromW(const glm::dmat4& p) {  // column-major: p[column][row]
    DepthFromW fromW;
    const bool wFromDepthAlone = p[0][3] == 0.0 && p[1][3] == 0.0 && p[2][3] != 0.0;
    const bool zFromDepthAlone = p[0][2] == 0.0 && p[1][2] == 0.0;
    if (!wFromDepthAlone || !zFromDepthAlone) return fromW;
    // z_c = P[2][2]·(w_c − P[3][3])/P[2][3] + P[3][2] = slope·w_c + offset.
    fromW.slope = p[2][2] / p[2][3];
    fromW.offset = p[3][2] - fromW.slope * p[3][3];
    fromW.known = std::isfinite(fromW.slope) && std::isfinite(fromW.offset);
    return fromW;
}

Camera frameCamera(const CameraSpec& spec, const Bounds& bounds, float aspect,
                   DepthBufferFormat depthFormat) {
    Camera camera;
    camera.depthFormat = depthFormat;
    camera.fovyDegrees = spec.fovyDegrees;
    // Double throughout: squared lengths of a 1e30 model overflow float, those of a 1e-30 one underflow.
    const dvec3 boxMin(bounds.min), boxMax(bounds.max);
    const dvec3 centre = 0.5 * (boxMin + boxMax);
    const double radius = 0.5 * glm::length(boxMax - boxMin);
    const dvec3 target = spec.target ? dvec3(*spec.target) : centre;
    dvec3 up(spec.up);

    // Below the smallest normal float a model's coordinates keep fewer digits than the rasterizer
    // needs, and the power of two that would bring eye space to unit size (viewScaleFor) is beyond
    // the largest float: every position would be infinite or NaN, and the model reported as outside
    // the view. Said for what it is.
    if (radius > 0.0 && radius < double(std::numeric_limits<float>::min()))
        throw InputError(text("the scene is too small to draw: its size (", 2.0 * radius,
                              ") is below the smallest normal 32-bit float (",
                              std::numeric_limits<float>::min(),
                              "), where coordinates lose their precision; scale it up (a scene file's "
                              "object \"scale\")"));

    dvec3 eye;
    if (spec.eye) {
        eye = dvec3(*spec.eye);
        // Exactly: a distance in float would underflow to 0 for a model of 1e-30 units.
        if (eye == target)
            throw InputError(
                text("the camera's eye is the point it looks at, ", describe(eye),
                     spec.target ? "" : " (the centre of the scene, looked at when no target is given)",
                     ": give another eye or target"));
    } else {
        if (!(radius > 0.0))
            throw InputError(text("the scene has no size to frame (every vertex is at ", describe(centre),
                                  "): give the camera an eye and a target"));
        // Look from the front, a little from above and to the right, at the distance where all eight
        // corners of the box fit the view: a corner at (x, y) across and z towards the eye from the
        // target is inside when |x| ≤ tan(fovx/2)·(d − z) and |y| ≤ tan(fovy/2)·(d − z).
        const dvec3 towardsEye = glm::normalize(dvec3(0.3, 0.3, 1.0));
        up = upAcross(-towardsEye, up, camera.warnings);
        const dvec3 right = glm::normalize(glm::cross(up, towardsEye));
        const dvec3 screenUp = glm::cross(towardsEye, right);
        const double tanHalfFovy = std::tan(glm::radians(double(spec.fovyDegrees)) * 0.5);
        const double tanHalfFovx = tanHalfFovy * aspect;
        double distance = 0.0;
        for (int corner = 0; corner < 8; ++corner) {
            const dvec3 p((corner & 1) ? boxMax.x : boxMin.x, (corner & 2) ? boxMax.y : boxMin.y,
                          (corner & 4) ? boxMax.z : boxMin.z);
            const dvec3 d = p - target;
            const double z = glm::dot(d, towardsEye);
            distance = std::max({distance, z + std::abs(glm::dot(d, right)) / tanHalfFovx,
                                 z + std::abs(glm::dot(d, screenUp)) / tanHalfFovy});
        }
        // A small margin, and never inside the bounding sphere.
        eye = target + std::max(1.1 * distance, 1.05 * radius) * towardsEye;
    }
    const dvec3 forward = glm::normalize(target - eye);
    up = upAcross(forward, up, camera.warnings);

    // Near and far hug the bounding sphere as seen from the eye; an eye inside the sphere keeps a near
    // plane at a thousandth of the scene's size, or a hundredth of the distance to the target when that
    // is nearer: in a huge scene (a ground of a million units) the eye a few units from what it looks at
    // would otherwise clip it away and draw nothing. A hundredth keeps the target within what every
    // depth buffer can draw (a 16-bit one draws out to about 1300 times the target's distance, see
    // checkDepthFromInside).
    const double toCentre = glm::length(centre - eye);
    const double insideNear = std::min(1e-3 * radius, 1e-2 * glm::length(target - eye));
    const double near = spec.near ? double(*spec.near) : std::max(0.95 * (toCentre - radius), insideNear);
    const double far = spec.infiniteFar ? std::numeric_limits<double>::infinity()
                       : spec.far       ? double(*spec.far)
                                        : std::max(1.05 * (toCentre + radius), near * 2.0);

    // What the depth buffer can tell apart. The scene's bounding sphere spans depths zFront..zBack
    // along the view; a point at depth z lands at window depth f(z − n)/(z(f − n)) in [0, 1], stored
    // as a 32-bit float, whose steps just below 1 are 2^-24.
    const double zCentre = glm::dot(centre - eye, forward);
    const double zFront = zCentre - radius, zBack = zCentre + radius;
    if (zBack > 0.0 && zBack < near)
        throw InputError(text("the whole scene is nearer than the camera's near plane (", near,
                              "; the scene ends ", zBack, " from the eye): nothing would be drawn"));
    if (zFront > far)
        throw InputError(text("the whole scene is beyond the camera's far plane (", far,
                              "; the scene starts ", zFront, " from the eye): nothing would be drawn"));
    if (!(near > 0.0 && far > near && (std::isfinite(far) || spec.infiniteFar)))
        throw InputError(
            text("the camera's near and far planes (", near, ", ", far, ") must satisfy 0 < near < far"));
    // Unorm buffers: the same with codes, 2^N − 1 of them. Reversed Z: nothing to check, the float's
    // relative precision holds at every distance.
    const int unormBits = depthFormat == DepthBufferFormat::Unorm16   ? 16
                          : depthFormat == DepthBufferFormat::Unorm24 ? 24
                                                                      : 0;
    if (zBack > 0.0 && depthFormat != DepthBufferFormat::ReversedFloat) {
        // f(z − n)/(z(f − n)), and its limit 1 − n/z for an infinite far plane.
        const auto windowDepth = [&](double z) {
            return std::isfinite(far) ? float(far * (z - near) / (z * (far - near))) : float(1.0 - near / z);
        };
        const double codes = unormBits ? std::ldexp(1.0, unormBits) - 1.0 : 0x1p24;
        const std::string buffer = unormBits ? text(unormBits, "-bit unorm") : std::string("32-bit");
        if (zFront >= near) {
            // The whole scene in front of the near plane: it spans zFront..zBack.
            const double z0 = zFront, z1 = std::min(zBack, far);
            const float d0 = windowDepth(z0), d1 = windowDepth(z1);
            const bool allFar = unormBits ? std::nearbyint(double(d0) * codes) >= codes : d0 >= 1.0f;
            if (allFar)
                throw InputError(text("the camera's near plane (", near, ") is too small for a scene ", z0,
                                      " away: every depth rounds to the far plane in the ", buffer,
                                      " depth buffer and nothing would be drawn (a near plane of ",
                                      z0 * (unormBits ? 1024.0 / codes : 1e-3), " or more works)"));
            const double steps = double(d1 - d0) * codes;
            if (steps < 1024.0)
                camera.warnings.push_back(text("the camera's near and far planes (", near, ", ", far,
                                               ") leave about ", std::floor(steps), " steps of the ", buffer,
                                               " depth buffer across the scene: surfaces close together may "
                                               "show through each other (move the near plane towards the "
                                               "scene)"));
        } else {
            checkDepthFromInside(near, far, eye, forward, boxMin, boxMax, radius, codes, buffer,
                                 camera.warnings);
        }
    }

    camera.eye = vec3(eye);
    camera.target = vec3(target);
    camera.up = vec3(up);
    camera.near = float(near);
    camera.far = float(far);
    if (!std::isfinite(camera.eye.x) || !std::isfinite(camera.eye.y) || !std::isfinite(camera.eye.z) ||
        (!std::isfinite(camera.far) && !spec.infiniteFar))
        throw InputError(text("the camera is too far out for 32-bit floats (eye at ", describe(eye),
                              ", far plane ", far, ")"));

    camera.viewScale = viewScaleFor(radius);
    const double s = camera.viewScale;
    camera.viewFromWorldExact = glm::scale(glm::dmat4(1.0), dvec3(s)) * glm::lookAt(eye, target, up);
    if (spec.infiniteFar) {
        // The limit of glm::perspective as far → ∞ (x and y as for any far plane): z_c = −z_e − 2n,
        // w_c = −z_e, so NDC z = 1 − 2n/d at distance d, −1 at the near plane and 1 at infinity.
        camera.clipFromViewExact = glm::perspective(glm::radians(double(camera.fovyDegrees)), double(aspect),
                                                    near * s, 2.0 * near * s);
        camera.clipFromViewExact[2][2] = -1.0;
        camera.clipFromViewExact[3][2] = -2.0 * near * s;
    } else {
        camera.clipFromViewExact =
            glm::perspective(glm::radians(double(camera.fovyDegrees)), double(aspect), near * s, far * s);
    }
    camera.viewFromWorld = mat4(camera.viewFromWorldExact);
    camera.clipFromView = mat4(camera.clipFromViewExact);
    return camera;
}

}  // namespace facet
