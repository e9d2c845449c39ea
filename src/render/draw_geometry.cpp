#include "render/draw_geometry.h"

namespace facet {

ShaderCall userShaderCall(const PreparedScene& prepared, const PreparedDraw& draw,
                          const SurfaceUniforms* uniforms) {
    return {&prepared.state, uniforms ? uniforms : &draw.uniforms, draw.userUniforms, draw.vertices,
            draw.indices};
}

glm::dvec3 eyeFromClip(const PreparedScene& prepared, const vec4& clip) {
    const glm::dvec4 eye = glm::inverse(drawnClipFromView(prepared.camera)) * glm::dvec4(clip);
    return glm::dvec3(eye) / eye.w;
}

namespace {

// The eye-space positions of a user shader's vertices: its vertex part's clip positions mapped back.
template <class Each>
void userShaderEyePositions(const PreparedScene& prepared, const PreparedDraw& d,
                            std::span<const std::uint32_t> vertices, Each each) {
    const glm::dmat4 viewFromClip = glm::inverse(drawnClipFromView(prepared.camera));
    const ShaderCall call = userShaderCall(prepared, d);
    std::vector<float> varyings(d.userShader.module->varyingNames.size() + 1);
    const auto one = [&](std::uint32_t index) {
        const glm::dvec4 eye = viewFromClip * glm::dvec4(d.userShader.module->shadeVertex(
                                                  d.vertices[index], call, varyings.data()));
        each(glm::dvec3(eye) / eye.w);
    };
    if (vertices.empty()) {
        for (std::uint32_t index = 0; index < d.vertices.size(); ++index)
            one(index);
    } else {
        for (const std::uint32_t index : vertices)
            one(index);
    }
}

}  // namespace

glm::dvec3 eyePosition(const PreparedScene& prepared, const PreparedDraw& draw, std::uint32_t vertex) {
    if (!draw.userShader.module)
        return glm::dvec3(draw.viewFromObjectExact *
                          glm::dvec4(glm::dvec3(draw.vertices[vertex].position), 1.0));
    glm::dvec3 out(0.0);
    userShaderEyePositions(prepared, draw, std::span<const std::uint32_t>(&vertex, 1),
                           [&](const glm::dvec3& p) { out = p; });
    return out;
}

std::vector<glm::dvec3> eyePositions(const PreparedScene& prepared, const PreparedDraw& draw) {
    std::vector<glm::dvec3> out;
    out.reserve(draw.vertices.size());
    if (!draw.userShader.module) {
        for (const MeshVertex& v : draw.vertices)
            out.push_back(glm::dvec3(draw.viewFromObjectExact * glm::dvec4(glm::dvec3(v.position), 1.0)));
        return out;
    }
    userShaderEyePositions(prepared, draw, {}, [&](const glm::dvec3& p) { out.push_back(p); });
    return out;
}

}  // namespace facet
