// Scenes the render and oracle tests share: a square seen head-on, and many interleaved see-through
// quads whose sorted frame makes one run per quad.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "render/renderer.h"
#include "support/temp_folder.h"

namespace facet::testing_support {

// A 2×2 square in the z = 0 plane facing +z, seen head-on.
inline constexpr const char* kSquareObj =
    "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\n";

inline Scene headOnScene(const std::filesystem::path& model) {
    Scene scene = sceneForModel(model);
    scene.width = 64;
    scene.height = 48;
    scene.camera.eye = vec3(0, 0, 5);
    scene.camera.target = vec3(0, 0, 0);
    scene.ambientLight = vec3(0);
    LightSpec light;
    light.type = LightKind::Directional;
    light.direction = vec3(0, 0, -1);  // travelling into the screen: straight onto the square
    scene.lights = {light};
    return scene;
}

// Many small see-through quads of three materials, one behind the other with the materials taking
// turns, so that back to front they make one run per quad; a fourth see-through material with a single
// quad at the back (a run with all of its part), and an opaque quad behind everything. The quads are
// scattered and tilted, some across the image's edge (clipped). Draws of the transparent pass: quadCount + 1.
inline std::filesystem::path writeInterleavedQuads(TempFolder& dir, int quadCount) {
    dir.write(
        "quads.mtl",
        "newmtl red\nKd 1 0.2 0.2\nd 0.5\nnewmtl green\nKd 0.2 1 0.2\nd 0.4\nnewmtl blue\nKd 0.2 0.2 1\n"
        "d 0.6\nnewmtl alone\nKd 1 1 0.2\nd 0.3\nnewmtl wall\nKd 0.5 0.5 0.5\n");
    std::string obj = "mtllib quads.mtl\n";
    std::uint32_t seed = 12345;
    const auto random = [&seed] {  // [0, 1)
        seed = seed * 1664525u + 1013904223u;
        return static_cast<float>(seed >> 8) / 16777216.0f;
    };
    int vertexCount = 0;
    const auto quad = [&](const char* material, float x, float y, float z, float size, float tilt) {
        obj += std::string("usemtl ") + material + "\n";
        for (const vec2 corner : {vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, 1)})
            obj += "v " + std::to_string(x + size * corner.x) + " " + std::to_string(y + size * corner.y) +
                   " " + std::to_string(z + tilt * corner.x) + "\n";
        obj += "f " + std::to_string(vertexCount + 1) + " " + std::to_string(vertexCount + 2) + " " +
               std::to_string(vertexCount + 3) + " " + std::to_string(vertexCount + 4) + "\n";
        vertexCount += 4;
    };
    quad("wall", 0.0f, 0.0f, -4.0f, 3.0f, 0.0f);
    quad("alone", 0.0f, 0.0f, -3.0f, 1.5f, 0.0f);
    const char* const materials[3] = {"red", "green", "blue"};
    for (int q = 0; q < quadCount; ++q)
        quad(materials[q % 3], 3.0f * random() - 1.5f, 3.0f * random() - 1.5f, -2.0f + 0.04f * q,
             0.3f + 0.6f * random(), 0.01f * (random() - 0.5f));
    return dir.write("quads.obj", obj);
}

inline Scene interleavedQuadsScene(const std::filesystem::path& obj) {
    Scene scene = headOnScene(obj);
    scene.width = 96;
    scene.height = 72;
    scene.camera.near = 0.5f;
    scene.camera.far = 20.0f;
    scene.pipeline.cull = CullMode::None;
    return scene;
}

inline std::size_t opaqueVertexCount(const PreparedScene& prepared) {
    std::size_t count = 0;
    for (const PreparedDraw& d : prepared.draws)
        if (!d.transparent) count += d.vertices.size();
    return count;
}

}  // namespace facet::testing_support
