// Renders a Scene with the pipeline: loads its models once (prepareScene), then draws frames
// (renderFrame) with the built-in surface shaders (shaders.h), one draw per object part (material).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "camera.h"
#include "gl_scene.h"
#include "image_io.h"
#include "mesh.h"
#include "pipeline.h"
#include "scene.h"
#include "shaders.h"

namespace facet {

// One draw: the triangles of one material of one object, with their own compact vertex array.
struct PreparedDraw {
    std::vector<MeshVertex> vertices;  // flat shading (Facet preset): one vertex per corner, face normals
    std::vector<std::uint32_t> indices;
    SurfaceUniforms uniforms;
    ShadingFrequency frequency = ShadingFrequency::Phong;
};

struct PreparedScene {
    Scene scene;
    Camera camera;
    DrawState state;
    vec4 clearColor{0.0f};                         // linear (Facet preset) or as given (GL preset)
    ColorEncoding encoding = kSrgbEncoding;  // how 8-bit image files encode the colour buffer
    std::vector<PreparedDraw> draws;
    std::vector<std::unique_ptr<Texture>> textures;
    std::vector<std::string> warnings;  // from the importer, one line each
    std::size_t triangleCount = 0;
    std::size_t degenerateSkipped = 0;
};

// Loads every model and texture the scene names and computes camera, lights and materials.
// Facet preset: every colour a user writes (MTL Ka/Kd/Ks/Ke, scene materials, lights, background,
// ambient) is taken as an sRGB-encoded value, as a colour picker shows it, and decoded to linear light
// here; lighting and blending then happen in linear space. GL preset: colours are used as given and
// written without encoding (docs/lighting.md). Lights end up in eye space. Throws InputError for
// unusable input.
PreparedScene prepareScene(const Scene& scene);

// Clears `target` to the scene's background and draws every object. `target` must be scene-sized.
// `terms` (LightingTerm bits) selects the lighting terms drawn: all of them, or one for a component image.
DrawStats renderFrame(const PreparedScene& prepared, Framebuffer& target, DrawContext& context,
                      std::uint8_t terms = kAllTerms);

// The same scene as OpenGL would be told to draw it (gl_scene.h): fixed function for the GL preset's
// Gouraud and flat Blinn-Phong, GLSL programs for everything else.
GlScene toGlScene(const PreparedScene& prepared);

// The framebuffer's colour as an image (same linear values).
LinearImage toImage(const Framebuffer& framebuffer);

}  // namespace facet
