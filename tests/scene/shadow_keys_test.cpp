// The scene file's shadow keys: a light's "shadows" (a method's name, or true and false) and the
// top-level "shadow_map"; each wrong value is refused in one line naming the file, the key and what is
// allowed.
#include <string>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "scene/scene.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

class ShadowKeysTest : public testing_support::TempFolderTest {
  protected:
    // `keys` (JSON members) added to a scene of one model (m.obj, beside it).
    fs::path sceneWith(const std::string& keys) const {
        touch("m.obj");
        std::string text = R"({"model": "m.obj", )";
        text += keys;
        text += "}";
        return write("scene.json", text);
    }
    ShadowMethod lightShadows(const std::string& value) const {
        const Scene scene =
            loadScene(sceneWith(R"("lights": [{"type": "directional", "shadows": )" + value + "}]"));
        EXPECT_EQ(scene.lights.size(), 1u);
        return scene.lights.at(0).shadows;
    }
    // The one-line InputError message of loading the scene with `keys`.
    std::string errorOf(const std::string& keys) const {
        const fs::path scene = sceneWith(keys);
        try {
            loadScene(scene);
        } catch (const InputError& e) {
            const std::string message = e.what();
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
            EXPECT_NE(message.find("scene.json"), std::string::npos) << message;
            return message;
        }
        ADD_FAILURE() << "no error for: " << keys;
        return {};
    }
};

#define EXPECT_MENTIONS(message, part) EXPECT_NE((message).find(part), std::string::npos) << (message)

// Every name and both booleans: true is the exact test (a ray), false none. Absent: none. Breaks if
// a boolean is read as a name (refused) or true is taken as a shadow map.
TEST_F(ShadowKeysTest, LightShadowsTakeEveryNameAndBooleans) {
    EXPECT_EQ(lightShadows("\"none\""), ShadowMethod::None);
    EXPECT_EQ(lightShadows("\"ray\""), ShadowMethod::Ray);
    EXPECT_EQ(lightShadows("\"map\""), ShadowMethod::Map);
    EXPECT_EQ(lightShadows("true"), ShadowMethod::Ray);
    EXPECT_EQ(lightShadows("false"), ShadowMethod::None);
    const Scene scene = loadScene(sceneWith(R"("lights": [{"type": "directional"}])"));
    EXPECT_EQ(scene.lights.at(0).shadows, ShadowMethod::None);
    EXPECT_FALSE(scene.shadows.has_value());  // the command line's, not the file's
}

// A wrong "shadows" names the light's key and every allowed value, the booleans too. Breaks if a number
// or an unknown name falls back to a default silently, or the message leaves out a name or the booleans
// (a number used to get only "must be a string").
TEST_F(ShadowKeysTest, WrongLightShadowsAreRefusedNamingTheKey) {
    for (const std::string value : {"\"yes\"", "3", "null", "[\"ray\"]"}) {
        SCOPED_TRACE(value);
        const std::string message =
            errorOf(R"("lights": [{"type": "point", "position": [0, 2, 0]}, {"shadows": )" + value + "}]");
        EXPECT_MENTIONS(message,
                        "\"lights[1].shadows\" must be \"none\", \"ray\", \"map\", true (a ray) or false");
    }
    EXPECT_MENTIONS(errorOf(R"("lights": [{"shadows": "rey"}])"), "did you mean \"ray\"");
}

// "shadow_map" sets every option; absent, the defaults. Breaks if a key is read into the wrong field.
TEST_F(ShadowKeysTest, ShadowMapKeysReachTheScene) {
    const Scene defaults = loadScene(sceneWith(R"("width": 8)"));
    EXPECT_EQ(defaults.shadowMap.size, ShadowMapOptions{}.size);
    EXPECT_EQ(defaults.shadowMap.filterTaps, ShadowMapOptions{}.filterTaps);
    const Scene scene = loadScene(
        sceneWith(R"("shadow_map": {"size": 1024, "bias": 2.5, "slope_bias": 0.25, "filter": 16})"));
    EXPECT_EQ(scene.shadowMap.size, 1024);
    EXPECT_EQ(scene.shadowMap.constantBias, 2.5f);
    EXPECT_EQ(scene.shadowMap.slopeBias, 0.25f);
    EXPECT_EQ(scene.shadowMap.filterTaps, 16);
    EXPECT_EQ(loadScene(sceneWith(R"("shadow_map": {"filter": 1, "size": 16})")).shadowMap.filterTaps, 1);
    EXPECT_EQ(loadScene(sceneWith(R"("shadow_map": {"size": 8192})")).shadowMap.size, kMaxShadowMapSize);
}

// Each wrong "shadow_map" value names its key and what is allowed. Breaks if the filter's taps are only
// range-checked (3 let through), the size's bounds are dropped, or an unknown key is ignored.
TEST_F(ShadowKeysTest, WrongShadowMapValuesAreRefusedNamingTheKey) {
    std::string message = errorOf(R"("shadow_map": {"filter": 3})");
    EXPECT_MENTIONS(message, "shadow_map.filter");
    EXPECT_MENTIONS(message, "1, 4 or 16");
    message = errorOf(R"("shadow_map": {"filter": 2.5})");
    EXPECT_MENTIONS(message, "shadow_map.filter");
    for (const std::string size : {"5", "15", "8193", "1e9", "-2048"}) {
        SCOPED_TRACE(size);
        message = errorOf(R"("shadow_map": {"size": )" + size + "}");
        EXPECT_MENTIONS(message, "shadow_map.size");
        EXPECT_MENTIONS(message, "16");
        EXPECT_MENTIONS(message, "8192");
    }
    EXPECT_MENTIONS(errorOf(R"("shadow_map": {"size": "big"})"),
                    "\"shadow_map.size\" must be a whole number");
    message = errorOf(R"("shadow_map": {"bias": -1})");
    EXPECT_MENTIONS(message, "shadow_map.bias");
    message = errorOf(R"("shadow_map": {"slope_bias": "steep"})");
    EXPECT_MENTIONS(message, "shadow_map.slope_bias");
    message = errorOf(R"("shadow_map": {"sise": 2048})");
    EXPECT_MENTIONS(message, "shadow_map.sise");
    EXPECT_MENTIONS(message, "unknown key");
    message = errorOf(R"("shadow_map": 2048)");
    EXPECT_MENTIONS(message, "shadow_map");
    EXPECT_MENTIONS(message, "an object");
}

}  // namespace
}  // namespace facet
