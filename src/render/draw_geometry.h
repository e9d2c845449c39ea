// Where a frame's draws put their triangles, for what traces them (the reference renderer, ray-cast
// shadows, facet compare --reference): the built-in shaders' positions placed in eye space, a shader of
// one's own's where its vertex part puts them.
#pragma once

#include <cstdint>
#include <vector>

#include "render/renderer.h"

namespace facet {

// Where the draw's vertex `vertex` lies in eye space, in double, as drawn: viewFromObjectExact of its
// position for the built-in shaders; for a shader of one's own, its vertex part's clip position mapped
// back to eye space through the inverse of the projection it draws with (drawnClipFromView), so that a
// shader that moves vertices (a displacement) is traced, shadowed and compared where it draws them.
// Non-finite for a clip position with w = 0.
glm::dvec3 eyePosition(const PreparedScene& prepared, const PreparedDraw& draw, std::uint32_t vertex);
// Every vertex of the draw (eyePosition), in order.
std::vector<glm::dvec3> eyePositions(const PreparedScene& prepared, const PreparedDraw& draw);
// A user shader's call for `draw` as the frame draws it (whole, the prepared state) with `uniforms` as
// the scene's uniforms (the draw's own unless given).
ShaderCall userShaderCall(const PreparedScene& prepared, const PreparedDraw& draw,
                          const SurfaceUniforms* uniforms = nullptr);
// A clip position of the draws mapped back to eye space (the inverse of drawnClipFromView, in double).
glm::dvec3 eyeFromClip(const PreparedScene& prepared, const vec4& clip);

}  // namespace facet
