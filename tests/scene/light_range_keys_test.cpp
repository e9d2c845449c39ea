// The scene file's keys for a light's range ("range", "window"), Cook-Torrance's attenuation (whether
// "attenuation" was given) and area lights ("rect", "disk": "width", "height", "radius", "up",
// "samples"); each wrong value is refused in one line naming the file and the key.
#include <string>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "scene/scene.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

class LightRangeKeysTest : public testing_support::TempFolderTest {
  protected:
    fs::path sceneWithLight(const std::string& light) const {
        touch("m.obj");
        return write("scene.json", R"({"model": "m.obj", "lights": [)" + light + "]}");
    }
    LightSpec light(const std::string& text) const {
        const Scene scene = loadScene(sceneWithLight(text));
        EXPECT_EQ(scene.lights.size(), 1u);
        return scene.lights.at(0);
    }
    std::string errorOf(const std::string& light) const {
        const fs::path scene = sceneWithLight(light);
        try {
            loadScene(scene);
        } catch (const InputError& e) {
            const std::string message = e.what();
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
            EXPECT_NE(message.find("scene.json"), std::string::npos) << message;
            return message;
        }
        ADD_FAILURE() << "no error for: " << light;
        return {};
    }
};

#define EXPECT_MENTIONS(message, part) EXPECT_NE((message).find(part), std::string::npos) << (message)

// "range" and "window" reach the LightSpec; absent, no range and UE4's window. Breaks if either key is
// dropped or the default window changes.
TEST_F(LightRangeKeysTest, RangeAndWindowAreRead) {
    const LightSpec none = light(R"({"type": "point"})");
    EXPECT_FALSE(none.range);
    EXPECT_FALSE(none.attenuationGiven);
    const LightSpec ranged = light(R"({"type": "spot", "range": 4.5, "window": "jc2"})");
    ASSERT_TRUE(ranged.range);
    EXPECT_EQ(*ranged.range, 4.5f);
    EXPECT_EQ(ranged.window, RangeWindow::Jc2);
    EXPECT_EQ(light(R"({"type": "point", "range": 2})").window, RangeWindow::Ue4);
    EXPECT_TRUE(light(R"({"type": "point", "attenuation": [1, 0, 0]})").attenuationGiven);
}

// Breaks if a range of 0 or below, a range on a directional light, or a window without a range is
// accepted.
TEST_F(LightRangeKeysTest, BadRangesAreRefused) {
    std::string e = errorOf(R"({"type": "point", "range": -2})");
    EXPECT_MENTIONS(e, "\"lights[0].range\" must be greater than 0 (got -2)");
    e = errorOf(R"({"type": "point", "range": 0})");
    EXPECT_MENTIONS(e, "\"lights[0].range\" must be greater than 0");
    e = errorOf(R"({"type": "directional", "range": 3})");
    EXPECT_MENTIONS(e, "\"lights[0].range\" is only for point, spot and area lights");
    e = errorOf(R"({"type": "point", "window": "ue4"})");
    EXPECT_MENTIONS(e, "\"lights[0].window\" needs \"lights[0].range\"");
    e = errorOf(R"({"type": "point", "range": 3, "window": "unreal"})");
    EXPECT_MENTIONS(e, "lights[0].window");
}

// A rectangle and a disk with their sizes, orientation and samples; the defaults where absent.
// Breaks if a key is dropped or a default changes.
TEST_F(LightRangeKeysTest, AreaLightsAreRead) {
    const LightSpec rect = light(
        R"({"type": "rect", "position": [0, 3, 0], "direction": [0, -1, 0], "width": 2, "height": 0.5,
            "up": [1, 0, 0], "samples": 64, "shadows": "ray"})");
    EXPECT_EQ(rect.type, LightKind::Rect);
    EXPECT_EQ(rect.width, 2.0f);
    EXPECT_EQ(rect.height, 0.5f);
    ASSERT_TRUE(rect.up);
    EXPECT_EQ(*rect.up, glm::vec3(1, 0, 0));
    EXPECT_EQ(rect.samples, 64);
    EXPECT_EQ(rect.shadows, ShadowMethod::Ray);
    const LightSpec disk = light(R"({"type": "disk", "position": [0, 3, 0], "radius": 0.25})");
    EXPECT_EQ(disk.type, LightKind::Disk);
    EXPECT_EQ(disk.radius, 0.25f);
    EXPECT_EQ(disk.direction, glm::vec3(0, -1, 0));  // facing down unless told
    EXPECT_EQ(disk.samples, 16);
}

// Breaks if a zero or negative size, an unknown shape, a non-square sample count, a key of the other
// shape, an area key on a point light, a shadow map or an "up" along the facing is accepted.
TEST_F(LightRangeKeysTest, BadAreaLightsAreRefused) {
    std::string e = errorOf(R"({"type": "rect", "width": 0})");
    EXPECT_MENTIONS(e, "\"lights[0].width\" must be greater than 0 (got 0)");
    e = errorOf(R"({"type": "rect", "height": -1})");
    EXPECT_MENTIONS(e, "\"lights[0].height\" must be greater than 0");
    e = errorOf(R"({"type": "disk", "radius": 0})");
    EXPECT_MENTIONS(e, "\"lights[0].radius\" must be greater than 0");
    e = errorOf(R"({"type": "triangle"})");
    EXPECT_MENTIONS(e, "lights[0].type");
    EXPECT_MENTIONS(e, "rect");
    e = errorOf(R"({"type": "rect", "samples": 10})");
    EXPECT_MENTIONS(e, "\"lights[0].samples\" must be a square number");
    e = errorOf(R"({"type": "rect", "samples": 0})");
    EXPECT_MENTIONS(e, "lights[0].samples");
    e = errorOf(R"({"type": "disk", "width": 1})");
    EXPECT_MENTIONS(e, "\"lights[0].width\" is only for \"rect\" lights");
    e = errorOf(R"({"type": "rect", "radius": 1})");
    EXPECT_MENTIONS(e, "\"lights[0].radius\" is only for \"disk\" lights");
    e = errorOf(R"({"type": "point", "samples": 16})");
    EXPECT_MENTIONS(e, "\"lights[0].samples\" is only for area lights");
    e = errorOf(R"({"type": "rect", "shadows": "map"})");
    EXPECT_MENTIONS(e, "\"lights[0].shadows\" cannot be \"map\" for an area light");
    e = errorOf(R"({"type": "rect", "direction": [0, -1, 0], "up": [0, 2, 0]})");
    EXPECT_MENTIONS(e, "\"lights[0].up\" is parallel to \"lights[0].direction\"");
}

}  // namespace
}  // namespace facet
