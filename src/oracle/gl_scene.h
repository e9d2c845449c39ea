// A scene as OpenGL would be told to draw it: eye-space lights, per-draw matrices and materials, and
// which lighting program each draw uses. Plain data, built from a PreparedScene by toGlScene()
// (renderer.h) and drawn by Mesa in mesa_peer.h, so that Facet's rendering can be compared with
// OpenGL's (the conformance tests, `facet compare`, `facet bench --vs-mesa`).
#pragma once

#include <cstdint>
#include <vector>

#include "pipeline/state.h"
#include "pipeline/texture.h"
#include "render/renderer.h"
#include "scene/mesh.h"
#include "shading/fog.h"
#include "shading/lighting.h"

namespace facet {

// How a draw is lit on the OpenGL side.
enum class GlProgram {
    FixedFunction,  // OpenGL 1.x lighting (glLight, glMaterial, glShadeModel): Gouraud or flat
    PerPixel,       // a GLSL program evaluating the draw's reflection model at every pixel
    PerVertex,      // a GLSL program evaluating it at every vertex (Gouraud) or, flat, once per face
};

// "fixed function", "GLSL per vertex", "GLSL per pixel": for messages and reports.
inline const char* programName(GlProgram program) {
    switch (program) {
        case GlProgram::FixedFunction:
            return "fixed function";
        case GlProgram::PerPixel:
            return "GLSL per pixel";
        case GlProgram::PerVertex:
            return "GLSL per vertex";
    }
    return "?";
}

struct GlDraw {
    std::vector<MeshVertex> vertices;    // object space
    std::vector<std::uint32_t> indices;  // three per triangle
    mat4 viewFromObject{1.0f};           // GL_MODELVIEW
    mat3 normalFromObject{1.0f};         // transpose(inverse(mat3(viewFromObject)))
    GlProgram program = GlProgram::FixedFunction;
    ReflectionModel reflection = ReflectionModel::BlinnPhong;  // FixedFunction: always Blinn-Phong
    ShadingFrequency frequency = ShadingFrequency::Gouraud;    // Flat: the provoking (last) vertex's colour
    PhongMaterial material;                                    // the standard equation's material
    PbrMaterial pbr;                                           // Cook-Torrance's material
    // With a diffuse map, the texel (bilinear, repeat) multiplies: per pixel, m_diffuse (or c_base)
    // before lighting; per vertex and flat, the interpolated diffuse term, the rest added unmultiplied
    // (emission + ambient + specular), except with clampColor, where the whole clamped colour is
    // multiplied, as fixed function's GL_MODULATE does.
    const Texture* diffuseMap = nullptr;
    // With an emission map, m_emission is multiplied by its texel per pixel; per vertex and flat, the
    // emission is left out of the vertex colour and added so per fragment (GLSL programs only).
    const Texture* emissionMap = nullptr;
    bool clampColor = false;  // clamp the lit colour to [0, 1] before interpolation, as fixed function does

    // Transparency. The fragment's alpha is opacity (× the diffuse map's alpha). What the shader writes
    // depends on the blend (as Facet's shaders do): Replace and Over: (c, α); PremultipliedOver and
    // Additive: (α·c, α); Multiply: (mix(1, c, α), α). Fog applies to c before that.
    float opacity = 1.0f;
    BlendMode blend = BlendMode::Replace;  // glBlendFunc: Over (SRC_ALPHA, ONE_MINUS_SRC_ALPHA),
                                           // PremultipliedOver (ONE, ONE_MINUS_SRC_ALPHA), Additive (ONE,
                                           // ONE), Multiply (DST_COLOR, ZERO)
    bool depthWrite = true;                // glDepthMask: off for transparent draws
};

struct GlScene {
    int width = 0, height = 0;
    vec4 clearColor{0.0f};
    mat4 clipFromView{1.0f};          // GL_PROJECTION
    vec3 globalAmbient{0.2f};         // GL_LIGHT_MODEL_AMBIENT
    std::vector<LightParams> lights;  // eye space (as glLightfv sees them under an identity modelview)
    BrdfModel brdf;                   // Cook-Torrance's D, F and G
    bool cullBackFaces = true;        // counter-clockwise front faces
    FogParams fog;                    // glFog; the fog distance of fixed function is |z_eye| or, for
                                      // Radial, GL_EYE_RADIAL_NV (per vertex there, per pixel in GLSL)
    bool twoSidedFlip = false;        // GLSL programs: light the side of N facing the viewer (N·V < 0: −N)
    std::vector<GlDraw> draws;        // in order: opaque draws, then transparent ones back to front
    // The buffers and the texture filter, as Facet's draw state has them: a renderbuffer of the same
    // format (DEPTH_COMPONENT16/24/32F, RGBA8/16F/32F); reversed Z as glClipControl(GL_LOWER_LEFT,
    // GL_ZERO_TO_ONE) with glDepthFunc(GL_GREATER) and depth cleared to 0; trilinear as
    // GL_LINEAR_MIPMAP_LINEAR over Facet's own mip levels, uploaded level by level.
    DepthBufferFormat depthFormat = DepthBufferFormat::Float;
    ColorBufferFormat colorFormat = ColorBufferFormat::Float;
    TextureFilter textureFilter = TextureFilter::Bilinear;
};

// The same scene as OpenGL would be told to draw it (gl_scene.h): fixed function for the GL preset's
// Gouraud and flat Blinn-Phong, GLSL programs for everything else.
GlScene toGlScene(const PreparedScene& prepared);

}  // namespace facet
