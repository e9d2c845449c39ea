// The camera and the scene's numbers at their extremes: every documented bound accepted at the bound
// (as the float the scene keeps), a camera for a model of 1e-30 units, a scene too small for floats
// said for what it is, an eye at the point it looks at, and the default near plane of a huge scene
// seen from inside it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "scene/camera.h"
#include "scene/knobs.h"
#include "scene/limits.h"
#include "scene/scene.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

constexpr float kImageAspect = 4.0f / 3.0f;

std::string framingError(const CameraSpec& spec, const Bounds& bounds,
                         DepthBufferFormat depth = DepthBufferFormat::Float) {
    try {
        frameCamera(spec, bounds, kImageAspect, depth);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// A number as JSON writes it back to the same double (the user's "0.01" or "1e30").
std::string exactText(double value) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", value);
    return text;
}

class CameraExtremesTest : public testing_support::TempFolderTest {
  protected:
    // A scene of one model (m.obj, beside it) with `keys` (JSON members) added.
    fs::path sceneWith(const std::string& keys) const {
        touch("m.obj");
        return write("scene.json", R"({"model": "m.obj", )" + keys + "}");
    }
    // What loading the scene says: "" when it loads.
    std::string loadError(const std::string& keys) const {
        try {
            loadScene(sceneWith(keys));
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    }
};

// Catches: a documented field-of-view bound refused at the bound because the float the user's 0.01
// becomes (0.0099999998) is compared with the double 0.01, in a scene file or on the command line.
TEST_F(CameraExtremesTest, FieldOfViewIsAcceptedAtItsDocumentedBounds) {
    for (const double bound : {kMinFovyDegrees, kMaxFovyDegrees}) {
        EXPECT_TRUE(fovyAllowed(static_cast<float>(bound))) << bound;
        EXPECT_EQ(loadError(R"("camera": {"fovy": )" + exactText(bound) + "}"), "") << bound;
    }
    // Just outside, as floats, stays refused.
    EXPECT_FALSE(fovyAllowed(std::nextafter(static_cast<float>(kMinFovyDegrees), 0.0f)));
    EXPECT_FALSE(fovyAllowed(std::nextafter(static_cast<float>(kMaxFovyDegrees), 1000.0f)));
    EXPECT_NE(loadError(R"("camera": {"fovy": 179.01})"), "");
}

// Every number knob of the scene file and the command line (scene/knobs.h), at each end of the range
// its help and the docs give, is accepted in both places.
// Catches: a bound like fog's 1e30, which the scene file reads as the float 1.0000000150e30, refused
// in a scene file though the same number is accepted by its flag.
TEST_F(CameraExtremesTest, EveryNumberKnobIsAcceptedAtItsBounds) {
    int checked = 0;
    for (const SceneKnob& knob : sceneKnobs()) {
        if (knob.kind == KnobKind::Names) continue;
        for (const double bound : {knob.lowest, knob.highest}) {
            if (!knob.only.empty() &&
                std::find(knob.only.begin(), knob.only.end(), int(bound)) == knob.only.end())
                continue;
            const std::string text = exactText(bound);
            if (!knob.flag.empty()) {
                EXPECT_EQ(knob.commandLineProblem(text).value_or(""), "") << knob.flag << " " << text;
            }
            if (knob.section.empty()) continue;
            // Fog needs its mode: given beside the bound.
            std::string members = "\"" + knob.key + "\": " + text;
            if (knob.section == "fog")
                members += knob.key == "density" ? R"(, "mode": "exp")" : R"(, "mode": "linear")";
            EXPECT_EQ(loadError("\"" + knob.section + "\": {" + members + "}"), "")
                << knob.scenePath() << " " << text;
            ++checked;
        }
    }
    EXPECT_GT(checked, 10);  // the walk met the table
}

// A model of 1e-40 units (subnormal float coordinates) cannot be transformed in float: the scale
// that brings it to unit size is beyond the largest float, and every position would be NaN.
// Catches: such a model reported as "outside the view" (a blank image, exit 0) instead of too small.
TEST(CameraExtremes, SceneBelowTheSmallestNormalFloatIsTooSmallToDraw) {
    const Bounds tiny{vec3(0.0f), vec3(1e-40f, 1e-40f, 0.0f)};
    const std::string error = framingError({}, tiny);
    EXPECT_NE(error.find("too small to draw"), std::string::npos) << error;
    // The smallest normal size still frames, with finite matrices.
    const float smallest = std::numeric_limits<float>::min();
    const Bounds small{vec3(0.0f), vec3(2.0f * smallest)};
    EXPECT_EQ(framingError({}, small), "");
}

// A camera for a model of 1e-30 units: eye and target 2.4e-30 apart are not the same point.
// Catches: the camera comparing eye and target by a float length (its square underflows to 0 at
// this scale), refusing the view or building it from NaN.
TEST(CameraExtremes, EyeAndTargetOfATinyModelFrameIt) {
    CameraSpec spec;
    spec.eye = vec3(0.5e-30f, 0.6e-30f, 2.6e-30f);
    spec.target = vec3(0.0f, 0.1e-30f, 0.0f);
    const Bounds box{vec3(-1e-30f), vec3(1e-30f)};
    const Camera camera = frameCamera(spec, box, kImageAspect);
    // The target lands mid-image and in front of the near plane.
    const glm::dvec4 clip =
        camera.clipFromViewExact * camera.viewFromWorldExact * glm::dvec4(glm::dvec3(*spec.target), 1.0);
    EXPECT_NEAR(clip.x / clip.w, 0.0, 1e-6);
    EXPECT_NEAR(clip.y / clip.w, 0.0, 1e-6);
    EXPECT_GT(clip.w, 0.0);
    EXPECT_LT(clip.z / clip.w, 1.0);
}

// Catches: an eye at the point it looks at (the scene's centre, when no target is given) building
// the camera from normalize(0) = NaN instead of being refused.
TEST(CameraExtremes, EyeAtThePointItLooksAtIsRefused) {
    CameraSpec spec;
    spec.eye = vec3(0.0f);  // the centre of the box below, looked at by default
    const std::string error = framingError(spec, {vec3(-1.0f), vec3(1.0f)});
    EXPECT_NE(error.find("the point it looks at"), std::string::npos) << error;
}

// A ground of ±1e6 units with the eye 5 units from its target: the near plane a thousandth of the
// scene's size (1414) would clip away everything the camera looks at, and the frame would be blank.
// The default near plane keeps the target drawn, in every depth format.
// Catches: the default near plane of a huge scene seen from inside clipping the target away.
TEST(CameraExtremes, DefaultNearPlaneInsideAHugeSceneKeepsTheTarget) {
    CameraSpec spec;
    spec.eye = vec3(0.0f, 2.0f, 5.0f);
    spec.target = vec3(0.0f);
    const Bounds ground{vec3(-1e6f, 0.0f, -1e6f), vec3(1e6f, 1.0f, 1e6f)};
    for (const DepthBufferFormat depth : {DepthBufferFormat::Float, DepthBufferFormat::Unorm16,
                                          DepthBufferFormat::Unorm24, DepthBufferFormat::ReversedFloat}) {
        const Camera camera = frameCamera(spec, ground, kImageAspect, depth);
        const double toTarget = glm::length(glm::dvec3(*spec.target) - glm::dvec3(*spec.eye));
        EXPECT_LT(camera.near, toTarget) << nameOf(depth);
        // Its window depth is below the far plane's (1) by more than a step of a 16-bit buffer.
        const double n = camera.near, f = camera.far;
        const double windowDepth = f * (toTarget - n) / (toTarget * (f - n));
        EXPECT_LT(windowDepth, 1.0 - 1.0 / 65535.0) << nameOf(depth);
    }
}

}  // namespace
}  // namespace facet
