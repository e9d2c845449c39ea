// The shading of one fragment as the lecture writes it: the lighting equation with every number
// substituted, fog, and the form the blend expects. The numbers come from the shaders' own formulas run
// again on the fragment with their record on (shading/record.h), so they are the very values the frame
// computed; traceShading checks that the recomputed output is the pipeline's, bit for bit.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/types.h"
#include "render/renderer.h"
#include "scene/mesh.h"
#include "shaders/shaders.h"
#include "step/screens.h"

namespace facet::step {

// What blocks a light at a point the shadow test found (partly) in shadow: the nearest opaque triangle
// on the shadow ray from P + ε·N towards the light. Under ray-cast shadows that ray is the test's own;
// under a shadow map the map decided, and the step mode casts the ray only to name a blocker.
struct ShadowBlocker {
    bool found = false;
    bool byMap = false;          // the light's shadows come from a shadow map
    std::uint32_t triangle = 0;  // as --triangle counts them
    std::string object;          // the object it belongs to, in words ("object 2, teapot.obj")
    float distance = 0;          // along the ray, from its origin P + ε·N (eye-space units)
};
using ShadowBlockers = std::array<ShadowBlocker, kMaxLights>;  // per light, in the uniforms' order

// Per-vertex shading (Gouraud, flat): the vertex lighting at one corner of the triangle.
struct CornerShading {
    int corner = 0;  // 0, 1 or 2, in the order traceShading was given the corners
    MeshVertex vertex{};
    float invW = 0;  // 1/w_clip of the corner: its weight in perspective-correct interpolation
    VertexLightingRecord lighting;
    ShadowBlockers blockers;  // filled by the caller (walk.h's shadingOf)
};

// Everything the shading screens show about one fragment.
struct ShadingTrace {
    ShadingFrequency frequency = ShadingFrequency::Phong;
    SurfaceUniforms uniforms;  // the draw's, the texture pointers cleared (the records say what they gave)
    int x = 0, y = 0;
    std::uint32_t triangle = 0;
    FragmentFate fate = FragmentFate::Written;
    vec3 barycentrics{0.0f};  // λ0, λ1, λ2 for the corners as given
    float invW = 0;           // 1/w at the pixel
    // Gouraud: the three corners; flat: the provoking corner alone; Phong shading: none.
    std::vector<CornerShading> corners;
    int provokingCorner = 0;
    // The triangle's own vertex number (v0, v1, v2) of each corner: 0, 1, 2, or 0, 2, 1 when setup
    // exchanged v1 and v2. Flat shading: whether the corners carry the face normal (the facet preset)
    // or their own (the gl preset's rule).
    std::array<int, 3> vertexOfCorner{0, 1, 2};
    bool faceNormal = true;
    // Flat shading with the face normal: the triangle's positions v0, v1, v2 (object space, as drawn)
    // and renderer.h's flatFaceNormal of them, the normal every corner carries.
    std::array<vec3, 3> facePositions{};
    FaceNormalRecord faceNormalRecord;
    // Gouraud: the perspective-correct weights μi = λi·(1/wi)/(1/w) of the corners and the corners'
    // colour parts mixed with them. Valid when Σ λi·(1/wi) is the pixel's 1/w, which fails when the
    // corners are not the window triangle's (clipping cut the triangle: the λ are its piece's).
    bool weightsMatchCorners = false;
    vec3 perspectiveWeights{0.0f};
    vec3 mixedModulated{0.0f};
    vec3 mixedAdded{0.0f};
    // Gouraud after clipping: the corners of the fan piece that covers the pixel, p0, p(k+1), p(k+2)
    // of the clipped polygon, with the colours clipping gave them, each new vertex's colours mixed from
    // its edge's ends with t (as the clipper mixes every varying: c = c_in + t·(c_out − c_in)), and the
    // perspective-correct weights μ of the three. Filled by the caller (walk.h's shadingOf).
    struct ClipMix {
        std::string made, plane, from, to;  // "p2", "near", "v1", "v2" (earlier: "p1 after left")
        float t = 0;
        std::array<vec3, 3> modulated{}, added{};  // at `from`, at `to`, and the result
    };
    struct PieceCorners {
        bool present = false;
        int piece = 0;
        std::array<std::string, 3> names;    // "p0", "p2", "p3"
        std::array<std::string, 3> sources;  // where each came from: "v0", "p2 after near", …
        std::array<vec3, 3> modulated{}, added{};
        vec3 weights{0.0f};  // μ, in the order of `names`
        vec3 mixedModulated{0.0f}, mixedAdded{0.0f};
        std::vector<ClipMix> mixes;  // the new vertices behind the three, earliest first
    } piece;
    // How the maps were filtered, and under trilinear the level of detail the fragment's texture
    // coordinate derivatives give (OpenGL 4.6 §8.14.1), for the first map (diffuse, else emission).
    struct TextureFootprint {
        bool mapped = false;
        TextureFilter filter = TextureFilter::Bilinear;
        int width = 0, height = 0, levels = 1;  // the map's level 0 and its mip levels
        vec2 uvDx{0.0f}, uvDy{0.0f};            // ∂(u,v)/∂x and ∂(u,v)/∂y at the pixel
        float rho = 0.0f;                       // the footprint's longer side in level-0 texels
        float lod = 0.0f;                       // λ = log2 ρ
    } texture;
    FragmentRecord fragment;       // the fragment shader's numbers, from the interpolated varyings
    ShadowBlockers blockers;       // Phong shading: at the pixel (filled by walk.h's shadingOf)
    vec4 pipelineOutput{0.0f};     // FragmentEvent::shaded
    bool shaderRan = true;         // the pipeline ran the shader (not when the depth test failed first)
    bool matchesPipeline = false;  // fragment.result == pipelineOutput, bit for bit (when shaderRan)
};

// Recomputes the shading of fragment `f` of a triangle drawn with uniforms `u` at `frequency`, the
// records on: Phong shading: shade<float> on the fragment's interpolated varyings; Gouraud: the vertex
// lighting at the three corners and the fragment part on the interpolated colour; flat: the provoking
// corner's vertex lighting and the fragment part. `corners` are the triangle's vertices in the order of
// the setup that rasterized it, which FragmentEvent::barycentrics refer to: the window triangle's order,
// with v1 and v2 exchanged when its signed area was negative (triangle_setup). `provokingCorner` is the
// index among `corners` of the provoking vertex (RasterState::provokingVertex: by default the last of
// the triangle as submitted).
ShadingTrace traceShading(const SurfaceUniforms& u, ShadingFrequency frequency, const FragmentEvent& f,
                          const std::array<MeshVertex, 3>& corners, int provokingCorner);

// The screens "lighting" (the equation, then each light: symbols, numbers, result per term), "fog" and
// "output" (the form the blend expects and the shader's output).
std::vector<Screen> shadingScreens(const ShadingTrace& trace);

nlohmann::json toJson(const ShadingTrace& trace);

}  // namespace facet::step
