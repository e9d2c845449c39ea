#include "oracle/gl_scene.h"

#include <algorithm>
#include <stdexcept>

namespace facet {

GlScene toGlScene(const PreparedScene& prepared) {
    GlScene gl;
    gl.width = prepared.scene.width;
    gl.height = prepared.scene.height;
    gl.clearColor = prepared.clearColor;
    gl.clipFromView = prepared.camera.clipFromView;
    gl.cullBackFaces = prepared.state.raster.cull == CullMode::Back;
    gl.depthFormat = prepared.state.depth.format;
    gl.colorFormat = prepared.state.colorBuffer;
    gl.textureFilter = prepared.scene.textures.filter;
    if (prepared.state.raster.cull == CullMode::Front)
        throw std::invalid_argument("OpenGL comparison: front-face culling is not mirrored");
    if (prepared.scene.lighting.preset == LightingPreset::Lecture)
        throw std::invalid_argument("OpenGL comparison: the lecture preset's formulas are not mirrored");
    if (prepared.environment.map)
        throw std::invalid_argument("OpenGL comparison: environment maps are not mirrored");
    if (prepared.scene.fog.mode == FogMode::Height)
        throw std::invalid_argument("OpenGL comparison: height fog is not mirrored");
    const bool glPreset = prepared.scene.lighting.preset == LightingPreset::GL;
    if (!prepared.draws.empty()) {
        const SurfaceUniforms& u = prepared.draws.front().uniforms;
        gl.globalAmbient = u.globalAmbient;
        gl.lights.assign(u.lights.begin(), u.lights.begin() + u.lightCount);
        gl.brdf = u.brdf;
        gl.twoSidedFlip = u.twoSidedFlip;
        gl.fog = u.fog;
    }
    for (const LightParams& l : gl.lights) {
        if (isAreaLight(l.kind))
            throw std::invalid_argument("OpenGL comparison: area lights (rect, disk) are not mirrored");
        if (l.range > 0.0f)
            throw std::invalid_argument(
                "OpenGL comparison: a light's range (windowed falloff) is not mirrored");
    }
    const bool smoothSpot = std::any_of(gl.lights.begin(), gl.lights.end(), [](const LightParams& l) {
        return l.kind == LightKind::Spot && l.spotProfile == SpotProfile::Smooth;
    });
    // The draws in the order a frame draws them (the transparent ones sorted from scratch). OpenGL has no
    // fragment lists: exact transparency is compared with the sorted order.
    FrameMemory memory;
    FrameStats stats;
    const TransparencyMode mode = prepared.scene.transparency.mode == TransparencyMode::Exact
                                      ? TransparencyMode::Sorted
                                      : prepared.scene.transparency.mode;
    for (const PlannedDraw& call : planFrame(prepared, mode, memory, stats)) {
        const PreparedDraw& d = prepared.draws[call.draw];
        GlDraw out;
        out.vertices.assign(call.vertices.begin(), call.vertices.end());  // a run's: only what it uses
        out.indices.assign(call.indices.begin(), call.indices.end());
        out.viewFromObject = d.uniforms.viewFromObject;
        out.normalFromObject = d.uniforms.normalFromObject;
        out.reflection = d.uniforms.reflection;
        if (out.reflection == ReflectionModel::CookTorrance)
            for (const LightParams& l : gl.lights)
                if (l.attenuationGiven)
                    throw std::invalid_argument(
                        "OpenGL comparison: Cook-Torrance with a light's \"attenuation\" is not mirrored");
        out.frequency = d.frequency;
        out.material = d.uniforms.material;
        // OpenGL raises N·H to the shininess as given: give it the exponent Facet uses (e′ when matched).
        if (d.uniforms.reflection == ReflectionModel::BlinnPhong)
            out.material.shininess = SpecularFormula(SpecularModel::BlinnPhong, d.uniforms.brdf.blinnExponent)
                                         .exponent(out.material.shininess);
        out.pbr = d.uniforms.pbr;
        out.diffuseMap = d.uniforms.diffuseMap;
        out.emissionMap = d.uniforms.emissionMap;
        out.clampColor = d.uniforms.clampColor;
        out.opacity = d.uniforms.opacity;
        out.blend = call.state.blend;
        out.depthWrite = call.state.depth.writeEnabled;
        // OpenGL 1.x itself where it can say the same: the GL preset's per-vertex Blinn-Phong, opaque or
        // blended with straight alpha, without an emission map.
        const bool fixedFunction = glPreset && d.frequency != ShadingFrequency::Phong && !out.emissionMap &&
                                   d.uniforms.reflection == ReflectionModel::BlinnPhong && !smoothSpot &&
                                   out.material.shininess <= 128.0f &&
                                   (out.blend == BlendMode::Replace || out.blend == BlendMode::Over ||
                                    out.blend == BlendMode::OverGL);
        out.program = fixedFunction                            ? GlProgram::FixedFunction
                      : d.frequency == ShadingFrequency::Phong ? GlProgram::PerPixel
                                                               : GlProgram::PerVertex;
        gl.draws.push_back(std::move(out));
    }
    return gl;
}

}  // namespace facet
