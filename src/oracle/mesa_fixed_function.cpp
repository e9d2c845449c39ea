// Mesa's fixed function (Mesa 22.3: ffvertex_prog.c builds a vertex program from the GL state) differs
// from lighting.h only at edges the peer keeps away from: its spot test is cos > cos(cutoff) where
// lighting.h has ≥, and GL accepts cutoffs in [0, 90] or 180 and exponents and shininess in [0, 128]
// only, so load() refuses the rest. Lit vertex colours are clamped to [0, 1] (GL_CLAMP_VERTEX_COLOR)
// before interpolation and texturing, as GlDraw::clampColor describes.
//
// Its fog: the vertex program writes the fog coordinate, |z_eye| (GL_EYE_PLANE_ABSOLUTE_NV, the
// default: abs, not −z) or |P_eye| (GL_EYE_RADIAL_NV), per vertex; the fragment stage computes f from
// the interpolated coordinate, per fragment (so exp and exp² see the interpolated distance, not an
// interpolated factor). That is fog.h's value exactly for |z_eye|, not for |P_eye| inside a triangle
// (setFixedFunctionFog). Linear fog with end = start makes Mesa take f = clamp(z − end, 0, 1), fog near
// and clear far, the opposite of fog.h's wall, so load() refuses it for fixed function.
#include <sstream>
#include <stdexcept>
#include <string>

#include "oracle/mesa_peer_impl.h"

namespace facet {

void checkFixedFunction(const GlScene& scene, std::size_t drawIndex, bool radialFog) {
    const GlDraw& draw = scene.draws[drawIndex];
    const std::string where = "GlScene draw " + std::to_string(drawIndex) + " (fixed function): ";
    if (draw.reflection != ReflectionModel::BlinnPhong)
        throw std::invalid_argument(where + "fixed-function lighting is Blinn-Phong only");
    if (draw.emissionMap && !draw.emissionMap->empty())
        throw std::invalid_argument(where + "an emission map needs a shader (use GlProgram::PerVertex)");
    if (draw.blend != BlendMode::Replace && draw.blend != BlendMode::Over && draw.blend != BlendMode::OverGL)
        throw std::invalid_argument(where + "blend " + (std::ostringstream() << draw.blend).str() +
                                    " needs a shader writing (α·c, α) or (mix(1, c, α), α); fixed function " +
                                    "writes (c, α) only (use GlProgram::PerVertex)");
    const FogParams& fog = scene.fog;
    if (fog.mode == FogMode::Linear && fog.end == fog.start)
        throw std::invalid_argument(where + "linear fog with end = start (" + std::to_string(fog.start) +
                                    ") has no fixed-function equivalent (Mesa fogs the near side)");
    if ((fog.mode == FogMode::Exponential || fog.mode == FogMode::ExponentialSquared) &&
        !(fog.density >= 0.0f))
        throw std::invalid_argument(where + "fog density " + std::to_string(fog.density) +
                                    " is negative (glFog refuses it)");
    if (fog.mode != FogMode::None && fog.distance == FogDistance::Radial && !radialFog)
        throw std::invalid_argument(where + "radial fog needs GL_NV_fog_distance, which this OpenGL lacks");
    const float n = draw.material.shininess;
    if (!(n >= 0.0f && n <= 128.0f))
        throw std::invalid_argument(where + "shininess " + std::to_string(n) +
                                    " is outside OpenGL's [0, 128]");
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const LightParams& light = scene.lights[i];
        const std::string lightWhere = where + "light " + std::to_string(i) + ": ";
        if (light.kind == LightKind::Spot) {
            if (light.spotProfile == SpotProfile::Smooth)
                throw std::invalid_argument(lightWhere +
                                            "a Smooth-profile spot has no fixed-function equivalent");
            const float cutoff = light.spotCutoffDegrees;
            if (!(cutoff >= 0.0f && (cutoff <= 90.0f || cutoff >= 180.0f)))
                throw std::invalid_argument(lightWhere + "spot cutoff " + std::to_string(cutoff) +
                                            " degrees is outside OpenGL's [0, 90] (or 180)");
            if (!(light.spotExponent >= 0.0f && light.spotExponent <= 128.0f))
                throw std::invalid_argument(lightWhere + "spot exponent " +
                                            std::to_string(light.spotExponent) +
                                            " is outside OpenGL's [0, 128]");
        }
        if (light.kind != LightKind::Directional &&
            !(light.c0 >= 0.0f && light.c1 >= 0.0f && light.c2 >= 0.0f))
            throw std::invalid_argument(lightWhere + "attenuation coefficients must not be negative");
    }
}

void MesaPeer::Impl::setFixedFunctionLights(const GlScene& scene) const {
    gl.glMatrixMode(GL_MODELVIEW);
    gl.glLoadIdentity();
    const vec4 ambient(scene.globalAmbient, 1.0f);
    gl.glLightModelfv(GL_LIGHT_MODEL_AMBIENT, &ambient[0]);
    gl.glLightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, GL_TRUE);
    gl.glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_FALSE);
    gl.glLightModeli(GL_LIGHT_MODEL_COLOR_CONTROL, GL_SINGLE_COLOR);
    for (int i = 0; i < kMaxGlLights; ++i) {
        const GLenum name = GL_LIGHT0 + static_cast<GLenum>(i);
        if (static_cast<std::size_t>(i) >= scene.lights.size()) {
            gl.glDisable(name);
            continue;
        }
        const LightParams& light = scene.lights[i];
        gl.glEnable(name);
        const vec4 position =
            light.kind == LightKind::Directional ? vec4(-light.direction, 0.0f) : vec4(light.position, 1.0f);
        gl.glLightfv(name, GL_POSITION, &position[0]);
        const bool cone = light.kind == LightKind::Spot && light.spotCutoffDegrees < 180.0f;
        const vec3 axis = light.kind == LightKind::Spot ? light.spotDirection : vec3(0.0f, 0.0f, -1.0f);
        gl.glLightfv(name, GL_SPOT_DIRECTION, &axis[0]);
        gl.glLightf(name, GL_SPOT_CUTOFF, cone ? light.spotCutoffDegrees : 180.0f);
        gl.glLightf(name, GL_SPOT_EXPONENT, cone ? light.spotExponent : 0.0f);
        const bool local = light.kind != LightKind::Directional;
        gl.glLightf(name, GL_CONSTANT_ATTENUATION, local ? light.c0 : 1.0f);
        gl.glLightf(name, GL_LINEAR_ATTENUATION, local ? light.c1 : 0.0f);
        gl.glLightf(name, GL_QUADRATIC_ATTENUATION, local ? light.c2 : 0.0f);
        const vec4 la(light.ambient, 1.0f), ld(light.diffuse, 1.0f), ls(light.specular, 1.0f);
        gl.glLightfv(name, GL_AMBIENT, &la[0]);
        gl.glLightfv(name, GL_DIFFUSE, &ld[0]);
        gl.glLightfv(name, GL_SPECULAR, &ls[0]);
    }
}

void MesaPeer::Impl::setFixedFunctionDraw(const Draw& draw) const {
    gl.glUseProgram(0);
    gl.glMatrixMode(GL_MODELVIEW);
    gl.glLoadMatrixf(&draw.viewFromObject[0][0]);
    const PhongMaterial& m = draw.material;
    const vec4 emission(m.emission, 1.0f), ambient(m.ambient, 1.0f), diffuse(m.diffuse, draw.opacity),
        specular(m.specular, 1.0f);
    gl.glMaterialfv(GL_FRONT_AND_BACK, GL_EMISSION, &emission[0]);
    gl.glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT, &ambient[0]);
    // Its alpha is the lit colour's (clamped to [0, 1] with the colour), the fragment's alpha once
    // GL_MODULATE has multiplied the texel's in.
    gl.glMaterialfv(GL_FRONT_AND_BACK, GL_DIFFUSE, &diffuse[0]);
    gl.glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, &specular[0]);
    gl.glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, m.shininess);
    gl.glShadeModel(draw.flat ? GL_FLAT : GL_SMOOTH);
    if (draw.texture)
        gl.glEnable(GL_TEXTURE_2D);
    else
        gl.glDisable(GL_TEXTURE_2D);
}

void MesaPeer::Impl::setFixedFunctionFog(const FogParams& fog) const {
    if (fog.mode == FogMode::None) {
        gl.glDisable(GL_FOG);
        return;
    }
    gl.glEnable(GL_FOG);
    gl.glFogi(GL_FOG_MODE, fog.mode == FogMode::Linear        ? GL_LINEAR
                           : fog.mode == FogMode::Exponential ? GL_EXP
                                                              : GL_EXP2);
    gl.glFogf(GL_FOG_START, fog.start);
    gl.glFogf(GL_FOG_END, fog.end);
    gl.glFogf(GL_FOG_DENSITY, fog.density);
    const vec4 color(fog.color, 1.0f);  // fog leaves alpha alone
    gl.glFogfv(GL_FOG_COLOR, &color[0]);
    gl.glFogi(GL_FOG_COORD_SRC, GL_FRAGMENT_DEPTH);
    gl.glHint(GL_FOG_HINT, GL_NICEST);
    if (radialFog)
        gl.glFogi(GL_FOG_DISTANCE_MODE_NV,
                  fog.distance == FogDistance::Radial ? GL_EYE_RADIAL_NV : GL_EYE_PLANE_ABSOLUTE_NV);
}

}  // namespace facet
