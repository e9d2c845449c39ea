// GLSL vocabulary for shaders written in C++: GLM's types and functions under their GLSL names,
// brought into namespace facet only (never `using namespace glm` globally).
#pragma once

#include <glm/glm.hpp>

namespace facet {

using glm::ivec2;
using glm::mat3;
using glm::mat4;
using glm::vec2;
using glm::vec3;
using glm::vec4;

using glm::clamp;
using glm::cross;
using glm::dot;
using glm::inverse;
using glm::length;
using glm::max;
using glm::min;
using glm::mix;
using glm::normalize;
using glm::pow;
using glm::reflect;
using glm::transpose;

}  // namespace facet
