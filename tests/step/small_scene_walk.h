// Shared by the step tests that check a screen's numbers against the same thing worked out in the test:
// a small scene of one OBJ text, the walk of a triangle at the pixel where a world point is seen, and
// reading numbers back from a screen's text.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "render/renderer.h"
#include "step/screens.h"
#include "step/walk.h"
#include "support/temp_folder.h"

namespace facet::step::testing_walk {

// Every line of the walk's screens within 80 columns, the titles too; with `ids`, only those screens.
inline void expectWithin80Columns(const StepTrace& trace, const std::vector<std::string>& ids = {}) {
    for (const Screen& s : trace.walk.screens) {
        if (!ids.empty() && std::find(ids.begin(), ids.end(), s.id) == ids.end()) continue;
        EXPECT_LE(columnsOf(s.title), kScreenColumns) << s.title;
        for (const std::string_view line : linesOf(s.text))
            EXPECT_LE(columnsOf(line), kScreenColumns) << s.id << ": " << line;
    }
}

// The numbers after `label` on the first line holding it (from `from`): "(1, 2, 3)", "1.5" or a row
// of numbers separated by blanks (or by " = ").
inline std::vector<double> numbersAfter(const std::string& text, const std::string& label,
                                        std::size_t from = 0) {
    const std::size_t at = text.find(label, from);
    if (at == std::string::npos) return {};
    const std::size_t end = text.find('\n', at);
    const std::string rest = text.substr(at + label.size(), end - at - label.size());
    std::vector<double> values;
    const char* p = rest.c_str();
    while (*p == ' ' || *p == '(' || *p == '=')
        ++p;
    while (*p) {
        char* next = nullptr;
        const double v = std::strtod(p, &next);
        if (next == p) break;
        values.push_back(v);
        p = next;
        if (*p == ')') break;
        while (*p == ',' || *p == ' ' || *p == '=')
            ++p;
    }
    return values;
}

inline void expectVector(const std::vector<double>& got, const glm::dvec3& want, double tolerance,
                         const std::string& what) {
    ASSERT_EQ(got.size(), 3u) << what;
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(got[i], want[i], tolerance) << what << " [" << i << "]";
}

// A fixture of a 64×48 scene of one OBJ, seen from (0, 0, 5) looking down −z, near 1, far 10, fovy
// 60°, one point light at (0.5, 1, 3).
class SmallSceneWalkTest : public ::testing::Test {
  protected:
    testing_support::TempFolder folder_;

    Scene sceneOf(const std::string& obj) const {
        Scene scene;
        scene.source = folder_.path() / "scene.json";
        scene.width = 64;
        scene.height = 48;
        scene.camera.eye = vec3(0.0f, 0.0f, 5.0f);
        scene.camera.target = vec3(0.0f, 0.0f, 0.0f);
        scene.camera.near = 1.0f;
        scene.camera.far = 10.0f;
        scene.camera.fovyDegrees = 60.0f;
        ObjectSpec object;
        object.model = folder_.write("model.obj", obj);
        scene.objects.push_back(object);
        LightSpec light;
        light.type = LightKind::Point;
        light.position = vec3(0.5f, 1.0f, 3.0f);
        scene.lights = {light};
        return scene;
    }

    // The walk of `triangle` at the pixel where the world point `at` is seen.
    static StepTrace walkAt(const PreparedScene& prepared, vec3 at, std::uint32_t triangle) {
        const vec4 clip = prepared.camera.clipFromView * prepared.camera.viewFromWorld * vec4(at, 1.0f);
        const int px = int((clip.x / clip.w + 1) * 0.5f * float(prepared.scene.width));
        const int py = int((1 - clip.y / clip.w) * 0.5f * float(prepared.scene.height));
        DrawContext context(1);
        StepRequest request;
        request.pixel = std::pair(px, py);
        request.triangle = triangle;
        return traceStep(prepared, context, request);
    }
};

}  // namespace facet::step::testing_walk
