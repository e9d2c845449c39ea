// The camera: framing the bounding box, the up vector, near and far planes, and models of extreme
// size, each checked against what the image would show.
#include "scene/camera.h"

#include <cmath>
#include <cstdint>
#include <string>

#include <gtest/gtest.h>

#include "base/errors.h"

namespace facet {
namespace {

constexpr float kAspect = 4.0f / 3.0f;

Bounds cube(float half, vec3 centre = vec3(0.0f)) {
    return {centre - vec3(half), centre + vec3(half)};
}

// Where a world point lands: normalised device coordinates, and the window depth in [0, 1] as float.
vec3 project(const Camera& camera, vec3 world) {
    const glm::dvec4 clip =
        camera.clipFromViewExact * camera.viewFromWorldExact * glm::dvec4(glm::dvec3(world), 1.0);
    const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
    return vec3(float(ndc.x), float(ndc.y), float(0.5 * ndc.z + 0.5));
}

bool allFinite(const mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

std::string errorOf(const CameraSpec& spec, const Bounds& bounds) {
    try {
        frameCamera(spec, bounds, kAspect);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// Straight above the target with the default up (+y): lookAt alone would divide 0 by 0 and draw
// nothing. The camera turns the image's top to −z, says so, and the target lands mid-image.
TEST(Camera, EyeStraightAboveTheTargetGetsAnotherUpAndAWarning) {
    CameraSpec spec;
    spec.eye = vec3(0.0f, 5.0f, 0.0f);
    spec.target = vec3(0.0f);
    const Camera camera = frameCamera(spec, cube(1.0f), kAspect);
    EXPECT_EQ(camera.up, vec3(0.0f, 0.0f, -1.0f));
    ASSERT_EQ(camera.warnings.size(), 1u);
    EXPECT_NE(camera.warnings[0].find("looks straight down along its up vector (0, 1, 0)"), std::string::npos)
        << camera.warnings[0];
    EXPECT_NE(camera.warnings[0].find("(0, 0, -1)"), std::string::npos) << camera.warnings[0];
    EXPECT_TRUE(allFinite(camera.viewFromWorld));
    const vec3 centre = project(camera, vec3(0.0f));
    EXPECT_NEAR(centre.x, 0.0f, 1e-6f);
    EXPECT_NEAR(centre.y, 0.0f, 1e-6f);
    // −z is up in the image: the far edge of the cube (z = −1) is above the centre.
    EXPECT_GT(project(camera, vec3(0.0f, 1.0f, -1.0f)).y, 0.1f);

    spec.eye = vec3(0.0f, -5.0f, 0.0f);  // straight below, looking up: +z at the top
    EXPECT_EQ(frameCamera(spec, cube(1.0f), kAspect).up, vec3(0.0f, 0.0f, 1.0f));
}

TEST(Camera, OrdinaryViewKeepsItsUpWithoutWarning) {
    CameraSpec spec;
    spec.eye = vec3(0.0f, 1.0f, 5.0f);
    const Camera camera = frameCamera(spec, cube(1.0f), kAspect);
    EXPECT_EQ(camera.up, vec3(0.0f, 1.0f, 0.0f));
    EXPECT_TRUE(camera.warnings.empty());
    EXPECT_EQ(camera.viewScale, 1.0);
}

// A near plane of 1e-10 for a scene 5 units away puts every depth at 1 - 2e-11: 1.0 in float, the
// cleared depth, and nothing passes the depth test. Refused, with a near plane that works.
TEST(Camera, NearPlaneTooSmallForTheSceneIsRefused) {
    CameraSpec spec;
    spec.eye = vec3(0.0f, 0.0f, 5.0f);
    spec.near = 1e-10f;
    const std::string error = errorOf(spec, cube(1.0f));
    EXPECT_NE(error.find("near plane (1e-10) is too small"), std::string::npos) << error;
    EXPECT_NE(error.find("nothing would be drawn"), std::string::npos) << error;
}

// A far plane of 3e38 is extreme but drawable: the projection, in double, stays finite, and the
// scene's depths stay below 1.
TEST(Camera, FarPlaneNearTheLargestFloatStillDraws) {
    CameraSpec spec;
    spec.eye = vec3(0.0f, 0.0f, 5.0f);
    spec.near = 1.0f;
    spec.far = 3e38f;
    const Camera camera = frameCamera(spec, cube(1.0f), kAspect);
    EXPECT_TRUE(allFinite(camera.clipFromView));
    EXPECT_LT(project(camera, vec3(0.0f, 0.0f, 1.0f)).z, project(camera, vec3(0.0f, 0.0f, -1.0f)).z);
    EXPECT_LT(project(camera, vec3(0.0f, 0.0f, -1.0f)).z, 1.0f);
}

TEST(Camera, SceneOutsideNearAndFarIsRefused) {
    CameraSpec spec;
    spec.eye = vec3(0.0f, 0.0f, 5.0f);
    spec.far = 3.0f;  // the cube spans 4..6 from the eye
    EXPECT_NE(errorOf(spec, cube(1.0f)).find("beyond the camera's far plane (3"), std::string::npos);
    spec.far.reset();
    spec.near = 7.0f;
    EXPECT_NE(errorOf(spec, cube(1.0f)).find("nearer than the camera's near plane (7"), std::string::npos);
}

// Near 1e-4 and far 1e4 for a cube 4 to 6 units away: the whole cube shares about 80 depth values.
TEST(Camera, PoorDepthPrecisionIsWarnedAbout) {
    CameraSpec spec;
    spec.eye = vec3(0.0f, 0.0f, 5.0f);
    spec.near = 1e-4f;
    spec.far = 1e4f;
    const Camera camera = frameCamera(spec, cube(1.0f), kAspect);
    ASSERT_EQ(camera.warnings.size(), 1u);
    EXPECT_NE(camera.warnings[0].find("steps of the 32-bit depth buffer"), std::string::npos)
        << camera.warnings[0];
    spec.near = 1.0f;
    EXPECT_TRUE(frameCamera(spec, cube(1.0f), kAspect).warnings.empty());
}

// The eye inside the unit cube (half size 1, bounding radius √3), 0.5 from its centre, looking down −z:
// the cube's far wall is 1.5 away. With the far plane the camera chooses, 1.05·(0.5 + √3) ≈ 2.34, a
// near plane of 1e-5 under a 16-bit unorm buffer sends every depth past about 0.84 to the far plane's
// code, 65535, which no fragment passes; the cube's near side is behind the eye, so the check from
// outside (scene front to back) has nothing in front of the near plane to judge.
CameraSpec insideTheCube(float near) {
    CameraSpec spec;
    spec.eye = vec3(0.0f, 0.0f, 0.5f);
    spec.target = vec3(0.0f, 0.0f, -1.0f);
    spec.near = near;
    return spec;
}

std::uint32_t unorm16Code(const Camera& camera, vec3 world) {
    return std::uint32_t(std::nearbyint(double(project(camera, world).z) * 65535.0));
}

// Catches: the depth check skipped (or judging from the sphere's front, behind the eye) when the eye is
// inside the scene's bounds, so a near plane that loses the far wall goes unsaid.
TEST(Camera, EyeInsideTheSceneWithATinyNearPlaneIsWarned) {
    const Camera camera = frameCamera(insideTheCube(1e-5f), cube(1.0f), kAspect, DepthBufferFormat::Unorm16);
    // What the warning claims, through the camera's own projection: the far wall (z = −1) rounds to the
    // far plane's code, a point 0.3 from the eye does not.
    EXPECT_EQ(unorm16Code(camera, vec3(0.0f, 0.0f, -1.0f)), 65535u);
    EXPECT_LT(unorm16Code(camera, vec3(0.0f, 0.0f, 0.2f)), 65535u);
    ASSERT_EQ(camera.warnings.size(), 1u);
    EXPECT_NE(camera.warnings[0].find("near plane (1e-05) is small for the 16-bit unorm depth buffer: every "
                                      "depth farther than 0.8"),
              std::string::npos)
        << camera.warnings[0];
    EXPECT_NE(camera.warnings[0].find("the scene reaches 1.5 "), std::string::npos) << camera.warnings[0];
}

// A near plane of 1e-8 leaves 16-bit codes for depths up to about 0.0013 only, less than the
// thousandth of the radius (0.0017) a camera inside the scene clips anyway: refused. The 32-bit buffer,
// 256 times finer, still draws to about 0.3: warned, not refused.
// Catches: an interior view that can draw nothing accepted silently, or refused for every buffer alike.
TEST(Camera, EyeInsideTheSceneWithANearPlaneFarTooSmallIsRefused) {
    const std::string error = [] {
        try {
            frameCamera(insideTheCube(1e-8f), cube(1.0f), kAspect, DepthBufferFormat::Unorm16);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    }();
    EXPECT_NE(error.find("near plane (1e-08) is too small for the 16-bit unorm depth buffer with the camera "
                         "inside the scene"),
              std::string::npos)
        << error;
    EXPECT_NE(error.find("nothing would be drawn"), std::string::npos) << error;
    const Camera camera = frameCamera(insideTheCube(1e-8f), cube(1.0f), kAspect);
    ASSERT_EQ(camera.warnings.size(), 1u);
    EXPECT_NE(camera.warnings[0].find("rounds to the far plane"), std::string::npos) << camera.warnings[0];
}

// Inside the cube with the near plane it gets when none is given (a thousandth of the radius, 0.0017)
// or a sensible one: quiet, in the 32-bit buffer and in the 16-bit one, where the default near plane
// keeps codes to about 2·0.0017·65535 ≈ 2.1 (less with the far plane at 2.34), past the far wall at 1.5.
// Catches: false alarms on ordinary interior views (the bundled scenes render inside their bounds).
TEST(Camera, EyeInsideTheSceneWithASensibleNearPlaneIsQuiet) {
    CameraSpec spec = insideTheCube(0.0f);
    spec.near.reset();
    EXPECT_TRUE(frameCamera(spec, cube(1.0f), kAspect).warnings.empty());
    EXPECT_TRUE(
        frameCamera(insideTheCube(0.1f), cube(1.0f), kAspect, DepthBufferFormat::Unorm16).warnings.empty());
    const Camera coarse = frameCamera(spec, cube(1.0f), kAspect, DepthBufferFormat::Unorm16);
    EXPECT_TRUE(coarse.warnings.empty()) << coarse.warnings[0];
    EXPECT_LT(unorm16Code(coarse, vec3(0.0f, 0.0f, -1.0f)), 65535u);  // the far wall is drawn
}

// The framing is the same at every scale: a box of 1e-7, 1e-30 or 1e30 lands where the unit box does
// (the radius used to be clamped at 1e-6, framing a 1e-7 model five times too small).
TEST(Camera, FramingDoesNotDependOnTheScale) {
    const Camera unit = frameCamera({}, cube(1.0f), kAspect);
    const vec3 corner(1.0f, 1.0f, 1.0f);
    for (const float scale : {1e-7f, 1e-30f, 1e30f}) {
        const Camera scaled = frameCamera({}, cube(scale), kAspect);
        EXPECT_TRUE(allFinite(scaled.viewFromWorld) && allFinite(scaled.clipFromView)) << scale;
        const vec3 a = project(unit, corner), b = project(scaled, corner * scale);
        EXPECT_NEAR(b.x, a.x, 1e-5f) << scale;
        EXPECT_NEAR(b.y, a.y, 1e-5f) << scale;
        EXPECT_NEAR(b.z, a.z, 1e-5f) << scale;
        EXPECT_NEAR(glm::length(glm::dvec3(scaled.eye)) / scale, glm::length(glm::dvec3(unit.eye)),
                    1e-4 * glm::length(glm::dvec3(unit.eye)))
            << scale;
    }
}

// A box of no size (one point) leaves no distance to frame it from: the camera asks for an eye.
TEST(Camera, BoxOfNoSizeAsksForAnEye) {
    const std::string error = errorOf({}, cube(0.0f, vec3(1.0f, 2.0f, 3.0f)));
    EXPECT_NE(error.find("no size to frame (every vertex is at (1, 2, 3))"), std::string::npos) << error;
    CameraSpec spec;
    spec.eye = vec3(1.0f, 2.0f, 8.0f);
    EXPECT_EQ(frameCamera(spec, cube(0.0f, vec3(1.0f, 2.0f, 3.0f)), kAspect).target, vec3(1.0f, 2.0f, 3.0f));
}

// NDC depth of an eye-space point at distance `distance` straight ahead, with the projection the
// rasterizer draws with (drawnClipFromView).
double drawnNdcDepth(const Camera& camera, double distance) {
    const glm::dvec4 clip = drawnClipFromView(camera) * glm::dvec4(0.0, 0.0, -distance, 1.0);
    return clip.z / clip.w;
}

// Reversed Z draws near at NDC z 1 and far at 0 (OpenGL's projection keeps −1 and 1), and the infinite
// far plane is the projection's limit: NDC z at z_e = −near is 1 (reversed) or −1 (OpenGL), and tends to
// 0 (reversed: exactly near/d) or 1 as the distance grows. Breaks if the reversed remap is left out, or
// the infinite projection keeps a finite far plane (NDC z past 1 beyond it).
TEST(Camera, ReversedZAndTheInfiniteFarPlane) {
    CameraSpec spec;
    spec.eye = vec3(0, 0, 5);
    spec.target = vec3(0.0f);
    spec.near = 0.5f;
    spec.far = 50.0f;
    const Camera reversed = frameCamera(spec, cube(1.0f), kAspect, DepthBufferFormat::ReversedFloat);
    EXPECT_NEAR(drawnNdcDepth(reversed, 0.5), 1.0, 1e-12);
    EXPECT_NEAR(drawnNdcDepth(reversed, 50.0), 0.0, 1e-12);
    const Camera standard = frameCamera(spec, cube(1.0f), kAspect);
    EXPECT_NEAR(drawnNdcDepth(standard, 0.5), -1.0, 1e-12);
    EXPECT_EQ(drawnClipFromView(standard), standard.clipFromViewExact);

    spec.far.reset();
    spec.infiniteFar = true;
    const Camera infinite = frameCamera(spec, cube(1.0f), kAspect, DepthBufferFormat::ReversedFloat);
    EXPECT_TRUE(std::isinf(infinite.far));
    EXPECT_NEAR(drawnNdcDepth(infinite, 0.5), 1.0, 1e-12);
    for (double d : {1.0, 1e3, 1e9, 1e30})
        EXPECT_NEAR(drawnNdcDepth(infinite, d), 0.5 / d, 1e-15 / d) << d;  // z_c = near, w_c = d
    const Camera infiniteStandard = frameCamera(spec, cube(1.0f), kAspect);
    EXPECT_NEAR(drawnNdcDepth(infiniteStandard, 0.5), -1.0, 1e-12);
    EXPECT_NEAR(drawnNdcDepth(infiniteStandard, 1e9), 1.0, 1e-8);
    EXPECT_LT(drawnNdcDepth(infiniteStandard, 1e9), 1.0);
}

}  // namespace
}  // namespace facet
