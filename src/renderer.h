// Renders a Scene with the pipeline: loads its models once (prepareScene), then draws frames
// (renderFrame) with the built-in Blinn-Phong shader, one draw per object part (material).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "camera.h"
#include "image_io.h"
#include "mesh.h"
#include "pipeline.h"
#include "scene.h"
#include "shaders.h"

namespace facet {

// One draw: the triangles of one material of one object, with their own compact vertex array.
struct PreparedDraw {
    std::vector<MeshVertex> vertices;
    std::vector<std::uint32_t> indices;
    BlinnPhongShader::Uniforms uniforms;
};

struct PreparedScene {
    Scene scene;
    Camera camera;
    DrawState state;
    vec4 clearColor{0.0f};  // linear
    std::vector<PreparedDraw> draws;
    std::vector<std::unique_ptr<Texture>> textures;
    std::vector<std::string> warnings;  // from the importer, one line each
    std::size_t triangleCount = 0;
    std::size_t degenerateSkipped = 0;
};

// Loads every model and texture the scene names and computes camera, lights and materials.
// Every colour a user writes (MTL Ka/Kd/Ks/Ke, scene materials, lights, background, ambient) is taken
// as an sRGB-encoded value, as a colour picker shows it, and decoded to linear light here; lighting and
// blending then happen in linear space. Throws InputError for unusable input.
PreparedScene prepareScene(const Scene& scene);

// Clears `target` to the scene's background and draws every object. `target` must be scene-sized.
DrawStats renderFrame(const PreparedScene& prepared, Framebuffer& target, DrawContext& context);

// The framebuffer's colour as an image (same linear values).
LinearImage toImage(const Framebuffer& framebuffer);

}  // namespace facet
