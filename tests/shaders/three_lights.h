// The scene uniforms the shader tests light their surfaces with: a directional, an attenuated point
// and a spot light, a material with every term, Cook-Torrance's parameters.
#pragma once

#include <glm/glm.hpp>

#include "shaders/shaders.h"

namespace facet::testing_shaders {

inline SurfaceUniforms threeLights() {
    SurfaceUniforms u;
    u.globalAmbient = vec3(0.1f, 0.12f, 0.08f);
    u.lightCount = 3;
    u.lights[0].kind = LightKind::Directional;
    u.lights[0].direction = normalize(vec3(-0.3f, -1.0f, -0.5f));
    u.lights[0].diffuse = vec3(1.0f, 0.9f, 0.8f);
    u.lights[1].kind = LightKind::Point;
    u.lights[1].position = vec3(2.0f, 1.0f, 1.5f);
    u.lights[1].diffuse = u.lights[1].specular = vec3(0.4f, 0.5f, 1.2f);
    u.lights[1].c1 = 0.3f;
    u.lights[2].kind = LightKind::Spot;
    u.lights[2].position = vec3(-2.0f, -1.0f, 0.5f);
    u.lights[2].spotDirection = normalize(vec3(1.0f, 0.5f, -1.0f));
    u.lights[2].spotCutoffDegrees = 50.0f;
    u.lights[2].spotExponent = 4.0f;
    u.lights[2].ambient = vec3(0.05f);
    u.lights[2].diffuse = vec3(0.7f, 0.2f, 0.1f);
    u.material.ambient = vec3(0.3f);
    u.material.diffuse = vec3(0.6f, 0.4f, 0.2f);
    u.material.specular = vec3(0.5f);
    u.material.emission = vec3(0.01f, 0.02f, 0.0f);
    u.pbr.baseColor = vec3(0.9f, 0.6f, 0.3f);
    u.pbr.roughness = 0.4f;
    u.pbr.metalness = 0.3f;
    return u;
}

}  // namespace facet::testing_shaders
