// Scene files: reads the JSON scene format (docs/scene-format.md) into a Scene, checking every key.
// Strict on purpose: an unknown key, a wrong type or an absurd value is a one-line error naming the file
// and the key path (`scene.json: unknown key "camera.fvoy" (did you mean "fovy"?)`), never a silent default.
// The JSON reading (typed key readers, duplicate keys) is in json_reader, the sections in scene_sections.
#include "scene/scene.h"

#include <string>

#include "scene/json_reader.h"
#include "scene/scene_sections.h"

namespace facet {

using namespace scene_file;  // the scene reader's own modules

Scene loadScene(const fs::path& path) {
    const SceneReader reader(path);
    const Json document = parseJson(reader, readText(reader, path));
    if (!document.is_object()) {
        reader.fail("a scene file must hold a JSON object like {\"model\": \"bunny.obj\"} (got " +
                    describe(document) + ")");
    }
    reader.checkKeys(document, "", kTopLevelKeys);

    Scene scene;
    scene.source = path;
    if (const Json* v = reader.find(document, "width"))
        scene.width = reader.wholeNumber(*v, "width", 1, kMaxImageSide);
    if (const Json* v = reader.find(document, "height"))
        scene.height = reader.wholeNumber(*v, "height", 1, kMaxImageSide);
    if (static_cast<long long>(scene.width) * scene.height > kMaxPixels) {
        reader.fail("\"width\" and \"height\" make an image of " + std::to_string(scene.width) + "x" +
                    std::to_string(scene.height) + " = " +
                    std::to_string(static_cast<long long>(scene.width) * scene.height) +
                    " pixels, larger than the limit of " + std::to_string(kMaxPixels) +
                    " (64 Mpixel, e.g. 8192x8192)");
    }
    if (const Json* v = reader.find(document, "background")) scene.background = readBackground(reader, *v);
    if (const Json* v = reader.find(document, "ambient")) scene.ambientLight = reader.color(*v, "ambient");
    if (const Json* v = reader.find(document, "camera")) scene.camera = readCamera(reader, *v);
    // The knobs' sections (scene/knobs.h), before the objects: "lighting"'s model and shading are the
    // scene's, which an object's own "lighting" overrides.
    if (const Json* v = reader.find(document, "pipeline"))
        readKnobSection(reader, *v, "pipeline", "an object like {\"cull\": \"back\"}", scene);
    if (const Json* v = reader.find(document, "textures"))
        readKnobSection(reader, *v, "textures", "an object like {\"filter\": \"trilinear\"}", scene);
    if (const Json* v = reader.find(document, "lighting")) readLighting(reader, *v, scene);
    if (const Json* v = reader.find(document, "transparency"))
        readKnobSection(reader, *v, "transparency", "an object like {\"mode\": \"exact\"}", scene);
    if (const Json* v = reader.find(document, "fog")) scene.fog = readFog(reader, *v);
    if (const Json* v = reader.find(document, "environment"))
        scene.environment = readEnvironment(reader, *v, path.parent_path());
    if (const Json* v = reader.find(document, "shadow_map"))
        readKnobSection(reader, *v, "shadow_map",
                        "an object like {\"size\": 2048, \"bias\": 1, \"slope_bias\": 1.5, \"filter\": 4}",
                        scene);
    if (const Json* v = reader.find(document, "gamma")) {
        // The gl preset neither decodes nor encodes; a "gamma" beside it would silently do nothing.
        if (scene.lighting.preset == LightingPreset::GL) {
            reader.fail(
                "\"gamma\" cannot be used with the gl lighting preset: the gl preset writes colours as "
                "OpenGL "
                "1.x does, without decoding or encoding; remove \"gamma\"");
        }
        // The lecture preset fixes the output curve (a pure 2.2 power); only the inputs' decoding is open.
        if (scene.lighting.preset == LightingPreset::Lecture &&
            (v->contains("encode") || v->contains("exponent")))
            reader.fail(
                "\"gamma.encode\" and \"gamma.exponent\" cannot be used with the lecture lighting preset: it "
                "encodes with the pure 2.2 power of the lecture notes; remove them");
        scene.gamma = readGamma(reader, *v);
    }

    if (const Json* lights = reader.find(document, "lights")) {
        if (!lights->is_array())
            reader.fail("\"lights\" must be an array of lights (got " + describe(*lights) + ")");
        // Here, before any light is read and long before any model is loaded.
        if (lights->size() > static_cast<std::size_t>(kMaxLights)) {
            reader.fail("\"lights\" has " + std::to_string(lights->size()) + " lights, at most " +
                        std::to_string(kMaxLights) + " are supported (as in OpenGL 1.x)");
        }
        for (std::size_t i = 0; i < lights->size(); ++i) {
            scene.lights.push_back(readLight(reader, (*lights)[i], elementPath("lights", i)));
        }
    }

    // Objects: the "model" shorthand or the "objects" array, exactly one of them.
    const fs::path folder = path.parent_path();
    if (const Json* v = reader.find(document, "shader"))
        scene.shader = readShader(reader, *v, "shader", folder);
    const Json* model = reader.find(document, "model");
    const Json* objects = reader.find(document, "objects");
    if (model && objects) reader.fail("give either \"model\" or \"objects\", not both");
    if (model) {
        ObjectSpec object;
        object.model = readModel(reader, *model, "model", folder);
        scene.objects.push_back(object);
    } else if (objects) {
        if (!objects->is_array())
            reader.fail("\"objects\" must be an array of objects (got " + describe(*objects) + ")");
        if (objects->size() > kMaxObjects) {
            reader.fail("\"objects\" has " + std::to_string(objects->size()) + " objects, at most " +
                        std::to_string(kMaxObjects) + " are supported in one scene");
        }
        for (std::size_t i = 0; i < objects->size(); ++i) {
            scene.objects.push_back(readObject(reader, (*objects)[i], elementPath("objects", i), folder));
        }
    }
    if (scene.objects.empty()) {
        reader.fail("the scene has no objects: add \"model\": \"file.obj\" or an \"objects\" array");
    }
    return scene;
}

Scene loadSceneOrModel(const fs::path& path) {
    return path.extension() == ".json" ? loadScene(path) : sceneForModel(path);
}

Scene sceneForModel(const fs::path& objPath) {
    Scene scene;
    scene.source = objPath;
    ObjectSpec object;
    object.model = objPath;
    scene.objects.push_back(object);
    return scene;
}

}  // namespace facet
