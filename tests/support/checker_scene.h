// A textured test scene: a floor plane under a black-and-white checkerboard texture, seen at a grazing
// angle so that its far half shrinks many texels into each pixel (where nearest and bilinear filtering
// alias into moiré and trilinear averages). Written into a folder as checker.png, plane.obj/.mtl and
// scene.json; `texturesKey` is the scene's "textures" section, if any.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include "io/image_io.h"

namespace facet::testing_support {

inline std::filesystem::path writeCheckerScene(const std::filesystem::path& folder,
                                               const std::string& texturesKey = "") {
    // 64×64 texels, cells of 8: 0 and 1 encode to codes 0 and 255 exactly.
    LinearImage checker;
    checker.width = checker.height = 64;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            checker.pixels.push_back(glm::vec4(glm::vec3(((x / 8 + y / 8) % 2) ? 1.0f : 0.0f), 1.0f));
    writeImage(folder / "checker.png", checker);
    // The floor y = 0 from z = 2 to −40, uv = (x, −z)/2: the texture repeats 4 times across, 21 deep.
    std::ofstream(folder / "plane.obj") << "mtllib plane.mtl\nusemtl checker\n"
                                           "v -4 0 2\nv 4 0 2\nv 4 0 -40\nv -4 0 -40\n"
                                           "vt -2 -1\nvt 2 -1\nvt 2 20\nvt -2 20\nvn 0 1 0\n"
                                           "f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n";
    std::ofstream(folder / "plane.mtl")
        << "newmtl checker\nKa 0 0 0\nKd 1 1 1\nKs 0 0 0\nmap_Kd checker.png\n";
    std::string scene = R"({"model": "plane.obj", "width": 96, "height": 64, "ambient": [0, 0, 0],
        "camera": {"eye": [0, 1, 2.5], "target": [0, 0.1, -10], "fovy": 40},
        "lights": [{"type": "directional", "direction": [0, -1, 0]}])";
    if (!texturesKey.empty()) {
        scene += ", \"textures\": ";
        scene += texturesKey;
    }
    scene += "}";
    std::ofstream(folder / "scene.json") << scene;
    return folder / "scene.json";
}

}  // namespace facet::testing_support
