// `facet compare --shader mine.cpp --against phong`: a shader of one's own against a built-in reflection
// model on the same scene, both shaded per pixel, for a student checking their shader against the
// formula it should compute. The images are compared by the 8-bit codes their files store: how many
// pixels differ, by how much at most, and the first differing pixel in reading order (the command then
// traces that pixel under both).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/image_io.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace facet {

// The two scenes: `scene` with every object's reflection model set to `model` and per-pixel shading,
// once with its shaders of one's own (`mine`) and once with none (`builtIn`, the same uniforms given to
// no shader). A shader of one's own sees the model in its uniforms (SceneUniforms::reflection), so a
// shader written with surfaceTerms follows it.
struct ShaderAgainstScenes {
    Scene mine, builtIn;
};
ShaderAgainstScenes shaderAgainstScenes(Scene scene, ReflectionModel model);

struct ShaderComparison {
    int width = 0, height = 0;
    ColorEncoding encoding = kSrgbEncoding;
    LinearImage mine, builtIn;
    std::vector<std::string> warnings;  // the scene's loading warnings (PreparedScene::warnings)
    std::size_t differing = 0;          // pixels whose 8-bit codes differ in some channel (R, G or B)
    int largest = 0;                    // the largest difference of a channel, in 8-bit codes
    // The first differing pixel in reading order (rows from the top, each from the left).
    std::optional<std::pair<int, int>> first;
    bool identical() const { return differing == 0; }
};

// Draws both scenes (prepared from the same assets) with the rasterizer on `threads` threads (0: one
// per hardware thread) and compares them. Throws InputError for a scene that cannot be drawn.
ShaderComparison compareShaderWithBuiltIn(const ShaderAgainstScenes& scenes, int threads,
                                          PreparedScene* preparedMine = nullptr,
                                          PreparedScene* preparedBuiltIn = nullptr);

}  // namespace facet
