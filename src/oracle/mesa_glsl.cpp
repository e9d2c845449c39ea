// The Mesa peer's GLSL programs: their sources, built per draw with the draw's choices compiled in, and
// their uniforms.
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "oracle/mesa_peer_impl.h"

namespace facet {

namespace {

// ---- The GLSL programs ---------------------------------------------------------------------------------
//
// lighting.h's formulas line for line, in eye space (the eye at the origin). One program per distinct
// (per pixel or per vertex, flat or smooth, reflection model, BRDF choice, lights, diffuse map, colour
// clamp, two-sided flip, fog mode and distance, what the blend wants written), the choices compiled in
// as #defines, and the light count and each light's kind too, as literal arguments of the calls to
// addLight(): llvmpipe runs a loop with a uniform trip count and uniform-array indexing about twice as
// slowly as the unrolled loop (bunny, 1920×1080, one light: 50 vs 26 ms), while for Facet's compiled
// C++ the runtime loop costs next to nothing. Written without layout
// qualifiers so that it compiles as GLSL 1.30 as well as 3.30; attribute and output locations are bound
// before linking.

// The lighting, in whichever stage evaluates it (the fragment shader per pixel, the vertex shader per
// vertex). Light kinds: 0 directional, 1 point (or a spot without a cone), 2 spot with OpenGL's profile,
// 3 spot with the smooth one.
const char* const kLightingGlsl = R"(
#define PI 3.14159265358979
uniform vec3 globalAmbient;
uniform vec3 lightPosition[MAX_LIGHTS];       // point and spot lights
uniform vec3 lightToward[MAX_LIGHTS];         // directional lights: −normalize(direction)
uniform vec3 lightAttenuation[MAX_LIGHTS];    // c0, c1, c2
uniform vec3 lightSpotDirection[MAX_LIGHTS];  // unit
uniform vec4 lightSpot[MAX_LIGHTS];           // cos cutoff, exponent, cos outer, cos inner
uniform vec3 lightAmbient[MAX_LIGHTS];
uniform vec3 lightDiffuse[MAX_LIGHTS];
uniform vec3 lightSpecular[MAX_LIGHTS];
uniform vec3 materialEmission;
uniform vec3 materialAmbient;
uniform vec3 materialDiffuse;
uniform vec3 materialSpecular;
uniform float materialShininess;
uniform vec3 baseColor;
uniform float metalness;
uniform float alpha;         // alphaFromRoughness(roughness)
uniform vec3 dielectricF0;

struct Terms {
    vec3 emission;
    vec3 ambient;
    vec3 diffuse;
    vec3 specular;
};

// wide.h's safeNormalize: the zero vector stays zero.
vec3 safeNormalize(vec3 v) {
    return v * (1.0 / sqrt(max(dot(v, v), 1e-30)));
}

// x^n for x ≥ 0 as lighting.h's pow: 1 where n = 0, 0 where x = 0 < n (GLSL's pow leaves both undefined).
float powSafe(float x, float n) {
    return n == 0.0 ? 1.0 : (x <= 0.0 ? 0.0 : pow(x, n));
}

// wide.h's smoothstep (GLSL's leaves edge0 ≥ edge1 undefined).
float smoothStep(float edge0, float edge1, float x) {
    float width = edge1 - edge0;
    float t = clamp((x - edge0) * (1.0 / (width != 0.0 ? width : 1e-7)), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

#if REFLECTION == 2
float etaFromF0(float f0) {
    float s = sqrt(clamp(f0, 0.0, 0.9999));
    return (1.0 + s) / (1.0 - s);
}

float fresnelExact(float cosTheta, float eta) {
    float c = clamp(cosTheta, 0.0, 1.0);
    float g2 = eta * eta - 1.0 + c * c;
    float g = sqrt(max(g2, 0.0));
    float a = (g - c) / max(g + c, 1e-7);
    float b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    return g2 < 0.0 ? 1.0 : 0.5 * a * a * (1.0 + b * b);
}

float smithG1GGX(float NdotX, float a2) {
    float c = max(NdotX, 0.0);
    return 2.0 * c / max(c + sqrt(a2 + (1.0 - a2) * c * c), 1e-7);
}

// lighting.h's brdf(), its diffuse and specular lobes apart.
void brdf(vec3 n, vec3 l, vec3 v, vec3 base, out vec3 diffuse, out vec3 specular) {
    vec3 N = safeNormalize(n);
    vec3 L = safeNormalize(l);
    vec3 V = safeNormalize(v);
    vec3 H = safeNormalize(L + V);
    float NdotLRaw = dot(N, L);
    float NdotL = max(NdotLRaw, 1e-4);
    float NdotV = max(dot(N, V), 1e-4);
    float NdotH = dot(N, H);
    float VdotH = clamp(dot(V, H), 0.0, 1.0);
    float a2 = alpha * alpha;
    vec3 f0 = mix(dielectricF0, baseColor, metalness);  // the material's: a diffuse map tints the Lambert lobe only
#if DISTRIBUTION_GGX
    float cH = max(NdotH, 0.0);
    float denominator = cH * cH * (a2 - 1.0) + 1.0;
    float D = NdotH > 0.0 ? a2 / (PI * denominator * denominator) : 0.0;
#else
    float cH = max(NdotH, 1e-4);
    float c2 = cH * cH;
    float D = NdotH > 0.0 ? exp((c2 - 1.0) / (a2 * c2)) / (PI * a2 * c2 * c2) : 0.0;
#endif
#if FRESNEL_EXACT
    vec3 F = vec3(fresnelExact(VdotH, etaFromF0(f0.x)), fresnelExact(VdotH, etaFromF0(f0.y)),
                  fresnelExact(VdotH, etaFromF0(f0.z)));
#else
    float m = 1.0 - clamp(VdotH, 0.0, 1.0);
    float m2 = m * m;
    vec3 F = (vec3(1.0) - f0) * (m2 * m2 * m) + f0;
#endif
#if GEOMETRY_SMITH
    float G = smithG1GGX(NdotV, a2) * smithG1GGX(NdotL, a2);
#else
    float k = 2.0 * max(NdotH, 0.0) / max(VdotH, 1e-4);
    float G = min(min(k * NdotV, k * NdotL), 1.0);
#endif
    bool lit = NdotLRaw > 0.0;
    specular = lit ? F * (D * G / (4.0 * NdotL * NdotV)) : vec3(0.0);
    diffuse = lit ? (vec3(1.0) - F) * (base * ((1.0 - metalness) / PI)) : vec3(0.0);
}
#endif

// One light's share. `kind` is a literal at every call, so each call compiles to straight code.
// surface: m_diffuse (standard equation) or c_base (Cook-Torrance), the texel applied where it applies.
void addLight(int i, int kind, vec3 P, vec3 N, vec3 V, vec3 surface, inout Terms terms) {
    // lightVector(): L towards the light and its distance.
    vec3 L;
    float d = 0.0;
    if (kind == 0) {
        L = lightToward[i];
    } else {
        vec3 toLight = lightPosition[i] - P;
        d = sqrt(dot(toLight, toLight));
        L = toLight * (1.0 / max(d, 1e-20));
    }
    // spotFactorOpenGL() / spotFactorSmooth().
    float spot = 1.0;
    if (kind == 2) {
        float cosAngle = dot(-L, lightSpotDirection[i]);
        spot = cosAngle >= lightSpot[i].x ? powSafe(max(cosAngle, 0.0), lightSpot[i].y) : 0.0;
    } else if (kind == 3) {
        spot = smoothStep(lightSpot[i].z, lightSpot[i].w, dot(-L, lightSpotDirection[i]));
    }
#if REFLECTION == 2
    // physicallyBasedLighting(): π c_light radiance, 1/d² falloff.
    float falloff = kind == 0 ? 1.0 : 1.0 / max(d * d, 1e-8);
    float irradiance = falloff * spot * max(dot(N, L), 0.0);
    vec3 diffuse, specular;
    brdf(N, L, V, surface, diffuse, specular);
    vec3 radiance = lightDiffuse[i] * PI;
    terms.diffuse += diffuse * radiance * irradiance;
    terms.specular += specular * radiance * irradiance;
#else
    // standardLighting(): attenuation and spot, ambient, Lambert diffuse, specular where N·L > 0.
    vec3 c = lightAttenuation[i];
    float attenuation = kind == 0 ? 1.0 : 1.0 / (c.x + d * (c.y + d * c.z));
    float reach = attenuation * spot;
    float NdotL = dot(N, L);
    terms.ambient += (lightAmbient[i] * materialAmbient) * reach;
    terms.diffuse += (lightDiffuse[i] * surface) * (reach * max(NdotL, 0.0));
#if REFLECTION == 0
    vec3 R = N * (2.0 * NdotL) - L;
    float cosine = dot(R, V);
#else
    float cosine = dot(N, safeNormalize(L + V));
#endif
    float spec = NdotL > 0.0 ? powSafe(max(cosine, 0.0), materialShininess) : 0.0;
    terms.specular += (lightSpecular[i] * materialSpecular) * (reach * spec);
#endif
}

void addLights(vec3 P, vec3 N, vec3 V, vec3 surface, inout Terms terms);  // generated per program

// The four terms at eye-space point P with normal n (any length); texel multiplies m_diffuse or c_base.
Terms shade(vec3 P, vec3 n, vec3 texel) {
    vec3 V = safeNormalize(-P);
    vec3 N = safeNormalize(n);
#if TWO_SIDED_FLIP
    if (dot(N, V) < 0.0) N = -N;
#endif
    Terms terms;
    terms.emission = materialEmission;
#if REFLECTION == 2
    vec3 surface = baseColor * texel;
    terms.ambient = globalAmbient * surface;
#else
    vec3 surface = materialDiffuse * texel;
    terms.ambient = globalAmbient * materialAmbient;
#endif
    terms.diffuse = vec3(0.0);
    terms.specular = vec3(0.0);
    addLights(P, N, V, surface, terms);
    return terms;
}

vec3 sum(Terms t) {
    return t.emission + t.ambient + t.diffuse + t.specular;
}
)";

const char* const kVertexGlsl = R"(
in vec3 position;
in vec3 normal;
in vec2 uv;
uniform mat4 clipFromView;
uniform mat4 viewFromObject;
uniform mat3 normalFromObject;
out vec2 texcoord;
#if PER_VERTEX
INTERPOLATION out vec3 shadedColor;  // the colour; with a diffuse map and no clamp, its diffuse term
#if HAS_DIFFUSE_MAP && !CLAMP_COLOR
INTERPOLATION out vec3 shadedRest;   // emission + ambient + specular
#endif
#if FOG_MODE
out vec3 eyePosition;  // smooth even for flat shading: the fog distance is taken per pixel
#endif
#else
out vec3 eyePosition;
out vec3 eyeNormal;  // not normalised
#endif
void main() {
    vec4 eye = viewFromObject * vec4(position, 1.0);
    vec3 n = normalFromObject * normal;
    texcoord = uv;
    gl_Position = clipFromView * eye;
#if PER_VERTEX
    Terms terms = shade(eye.xyz, n, vec3(1.0));
#if HAS_EMISSION_MAP
    terms.emission = vec3(0.0);  // added per fragment, textured
#endif
#if CLAMP_COLOR
    shadedColor = clamp(sum(terms), 0.0, 1.0);
#elif HAS_DIFFUSE_MAP
    shadedColor = terms.diffuse;
    shadedRest = terms.emission + terms.ambient + terms.specular;
#else
    shadedColor = sum(terms);
#endif
#if FOG_MODE
    eyePosition = eye.xyz;
#endif
#else
    eyePosition = eye.xyz;
    eyeNormal = n;
#endif
}
)";

// The fragment's colour c: lit (per pixel, or interpolated and textured), fogged (fog.h's formulas, the
// distance taken per pixel from the interpolated eye-space position), then written as the blend wants
// it (gl_scene.h): BLEND_OUTPUT 0 (Replace, Over) (c, α), 1 (PremultipliedOver, Additive) (α·c, α),
// 2 (Multiply) (mix(1, c, α), α), with α = opacity × the diffuse map's alpha. An emission map
// multiplies m_emission, per pixel (per vertex: the emission is added here, not interpolated).
const char* const kFragmentGlsl = R"(
in vec2 texcoord;
#if PER_VERTEX
INTERPOLATION in vec3 shadedColor;
#if HAS_DIFFUSE_MAP && !CLAMP_COLOR
INTERPOLATION in vec3 shadedRest;
#endif
#if FOG_MODE
in vec3 eyePosition;
#endif
#else
in vec3 eyePosition;
in vec3 eyeNormal;
#endif
uniform sampler2D diffuseMap;
uniform sampler2D emissionMap;
#if PER_VERTEX && HAS_EMISSION_MAP
uniform vec3 materialEmission;
#endif
uniform float opacity;
#if FOG_MODE
uniform vec3 fogColor;
uniform vec3 fogRange;  // linear start and end, exponential density

// fog.h's fogFactor(fogDistance()): FOG_MODE 1 linear, 2 exp, 3 exp².
float fogFactor(vec3 P) {
#if FOG_RADIAL
    float z = sqrt(dot(P, P));
#else
    float z = abs(P.z);
#endif
#if FOG_MODE == 1
    float start = fogRange.x, end = fogRange.y;
    if (end == start) return z < start ? 1.0 : 0.0;  // a wall at start
    return clamp((end - z) * (1.0 / (end - start)), 0.0, 1.0);
#elif FOG_MODE == 2
    return clamp(exp(-fogRange.z * z), 0.0, 1.0);
#else
    float dz = fogRange.z * z;
    return clamp(exp(-(dz * dz)), 0.0, 1.0);
#endif
}
#endif
out vec4 fragColor;
void main() {
    vec3 texel = vec3(1.0);
    float a = opacity;
#if HAS_DIFFUSE_MAP
    vec4 sampled = texture(diffuseMap, texcoord);
    texel = sampled.rgb;
    a *= sampled.a;
#endif
#if PER_VERTEX
#if HAS_DIFFUSE_MAP && !CLAMP_COLOR
    vec3 color = shadedColor * texel + shadedRest;
#else
    vec3 color = shadedColor * texel;
#endif
#if HAS_EMISSION_MAP
    color += materialEmission * texture(emissionMap, texcoord).rgb;
#endif
#else
    Terms terms = shade(eyePosition, eyeNormal, texel);
#if HAS_EMISSION_MAP
    terms.emission *= texture(emissionMap, texcoord).rgb;
#endif
    vec3 color = sum(terms);
#if CLAMP_COLOR
    color = clamp(color, 0.0, 1.0);
#endif
#endif
#if FOG_MODE
    float f = fogFactor(eyePosition);
    color = color * f + fogColor * (1.0 - f);
#endif
#if BLEND_OUTPUT == 1
    fragColor = vec4(color * a, a);
#elif BLEND_OUTPUT == 2
    fragColor = vec4(mix(vec3(1.0), color, a), a);
#else
    fragColor = vec4(color, a);
#endif
}
)";

// How a light enters a GLSL program: 0 directional, 1 point (a spot without a cone is one: its spot
// factor is 1), 2 spot with OpenGL's profile, 3 spot with the smooth one.
int lightKindCode(const LightParams& light) {
    switch (light.kind) {
        case LightKind::Directional:
            return 0;
        case LightKind::Point:
            return 1;
        case LightKind::Spot:
            if (light.spotProfile == SpotProfile::Smooth) return 3;
            return light.spotCutoffDegrees >= 180.0f ? 1 : 2;
        case LightKind::Rect:
        case LightKind::Disk:
            break;  // not mirrored: refused by gl_scene.cpp
    }
    return 1;
}

// How fog enters a GLSL program: FOG_MODE 0 none, 1 linear, 2 exp, 3 exp².
int fogModeCode(FogMode mode) {
    switch (mode) {
        case FogMode::None:
            return 0;
        case FogMode::Linear:
            return 1;
        case FogMode::Exponential:
            return 2;
        case FogMode::ExponentialSquared:
            return 3;
        case FogMode::Height:
            break;  // refused by toGlScene
    }
    return 0;
}

// What a GLSL program writes for a blend: BLEND_OUTPUT 0 (c, α), 1 (α·c, α), 2 (mix(1, c, α), α).
int blendOutputCode(BlendMode blend) {
    switch (blend) {
        case BlendMode::Replace:
        case BlendMode::Over:
        case BlendMode::OverGL:
            return 0;
        case BlendMode::PremultipliedOver:
        case BlendMode::Additive:
            return 1;
        case BlendMode::Multiply:
            return 2;
    }
    return 0;
}

}  // namespace

int glslVersion(const std::string& text) {
    int major = 0, minor = 0;
    if (std::sscanf(text.c_str(), "%d.%d", &major, &minor) != 2) return 0;
    return major * 100 + minor;
}

GLuint MesaPeer::Impl::compileShader(GLenum type, const std::string& source) const {
    const GLuint shader = gl.glCreateShader(type);
    const char* text = source.c_str();
    gl.glShaderSource(shader, 1, &text, nullptr);
    gl.glCompileShader(shader);
    GLint ok = GL_FALSE;
    gl.glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        gl.glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        gl.glDeleteShader(shader);
        throw std::runtime_error(std::string("the Mesa peer's ") +
                                 (type == GL_VERTEX_SHADER ? "vertex" : "fragment") +
                                 " shader does not compile: " + firstLine(log));
    }
    return shader;
}

const MesaPeer::Impl::Program& MesaPeer::Impl::program(const GlScene& scene, const GlDraw& draw) {
    const bool perVertex = draw.program == GlProgram::PerVertex;
    const bool hasDiffuseMap = draw.diffuseMap && !draw.diffuseMap->empty();
    const bool hasEmissionMap = draw.emissionMap && !draw.emissionMap->empty();
    const int reflection = draw.reflection == ReflectionModel::Phong        ? 0
                           : draw.reflection == ReflectionModel::BlinnPhong ? 1
                                                                            : 2;
    const bool costTerms = reflection == 2;  // the BRDF's choices matter to Cook-Torrance only
    std::string header =
        versionLine + "\n#define MAX_LIGHTS " + std::to_string(kMaxGlLights) + "\n#define PER_VERTEX " +
        (perVertex ? "1" : "0") + "\n#define INTERPOLATION " +
        (draw.frequency == ShadingFrequency::Flat ? "flat" : "smooth") + "\n#define REFLECTION " +
        std::to_string(reflection) + "\n#define DISTRIBUTION_GGX " +
        (costTerms && scene.brdf.distribution == NormalDistribution::GGX ? "1" : "0") +
        "\n#define FRESNEL_EXACT " + (costTerms && scene.brdf.fresnel == FresnelModel::Exact ? "1" : "0") +
        "\n#define GEOMETRY_SMITH " +
        (costTerms && scene.brdf.geometry == GeometryTerm::SmithGGX ? "1" : "0") +
        "\n#define HAS_DIFFUSE_MAP " + (hasDiffuseMap ? "1" : "0") + "\n#define HAS_EMISSION_MAP " +
        (hasEmissionMap ? "1" : "0") + "\n#define CLAMP_COLOR " + (draw.clampColor ? "1" : "0") +
        "\n#define TWO_SIDED_FLIP " + (scene.twoSidedFlip ? "1" : "0") + "\n";
    header += "#define FOG_MODE " + std::to_string(fogModeCode(scene.fog.mode)) + "\n#define FOG_RADIAL " +
              (scene.fog.distance == FogDistance::Radial ? "1" : "0") + "\n#define BLEND_OUTPUT " +
              std::to_string(blendOutputCode(draw.blend)) + "\n";
    std::string addLights = "void addLights(vec3 P, vec3 N, vec3 V, vec3 surface, inout Terms terms) {\n";
    for (std::size_t i = 0; i < scene.lights.size(); ++i)
        addLights += "    addLight(" + std::to_string(i) + ", " +
                     std::to_string(lightKindCode(scene.lights[i])) + ", P, N, V, surface, terms);\n";
    addLights += "}\n";
    const std::string key = header + addLights;
    Program& p = programs[key];
    if (p.name) return p;

    const std::string lighting = std::string(kLightingGlsl) + addLights;
    const GLuint vertex =
        compileShader(GL_VERTEX_SHADER, header + (perVertex ? lighting : std::string()) + kVertexGlsl);
    GLuint fragment = 0;
    try {
        fragment = compileShader(GL_FRAGMENT_SHADER,
                                 header + (perVertex ? std::string() : lighting) + kFragmentGlsl);
    } catch (...) {
        gl.glDeleteShader(vertex);
        programs.erase(key);
        throw;
    }
    p.name = gl.glCreateProgram();
    gl.glAttachShader(p.name, vertex);
    gl.glAttachShader(p.name, fragment);
    gl.glBindAttribLocation(p.name, 0, "position");
    gl.glBindAttribLocation(p.name, 1, "normal");
    gl.glBindAttribLocation(p.name, 2, "uv");
    gl.glBindFragDataLocation(p.name, 0, "fragColor");
    gl.glLinkProgram(p.name);
    gl.glDeleteShader(vertex);
    gl.glDeleteShader(fragment);
    GLint ok = GL_FALSE;
    gl.glGetProgramiv(p.name, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        gl.glGetProgramInfoLog(p.name, sizeof log, nullptr, log);
        gl.glDeleteProgram(p.name);
        programs.erase(key);
        throw std::runtime_error(std::string("the Mesa peer's shader does not link: ") + firstLine(log));
    }
    auto uniform = [&](const char* name) { return gl.glGetUniformLocation(p.name, name); };
    p.clipFromView = uniform("clipFromView");
    p.globalAmbient = uniform("globalAmbient");
    p.lightPosition = uniform("lightPosition");
    p.lightToward = uniform("lightToward");
    p.lightAttenuation = uniform("lightAttenuation");
    p.lightSpotDirection = uniform("lightSpotDirection");
    p.lightSpot = uniform("lightSpot");
    p.lightAmbient = uniform("lightAmbient");
    p.lightDiffuse = uniform("lightDiffuse");
    p.lightSpecular = uniform("lightSpecular");
    p.viewFromObject = uniform("viewFromObject");
    p.normalFromObject = uniform("normalFromObject");
    p.materialEmission = uniform("materialEmission");
    p.materialAmbient = uniform("materialAmbient");
    p.materialDiffuse = uniform("materialDiffuse");
    p.materialSpecular = uniform("materialSpecular");
    p.materialShininess = uniform("materialShininess");
    p.baseColor = uniform("baseColor");
    p.metalness = uniform("metalness");
    p.alpha = uniform("alpha");
    p.dielectricF0 = uniform("dielectricF0");
    p.opacity = uniform("opacity");
    p.fogColor = uniform("fogColor");  // -1 without fog: glUniform ignores it
    p.fogRange = uniform("fogRange");
    gl.glUseProgram(p.name);
    gl.glUniform1i(uniform("diffuseMap"), 0);   // texture unit 0
    gl.glUniform1i(uniform("emissionMap"), 1);  // texture unit 1
    checkGl("building a shader program");
    return p;
}

void MesaPeer::Impl::setSceneUniforms(const Program& p, const GlScene& scene) const {
    std::array<float, kMaxGlLights * 3> position{}, toward{}, attenuation{}, spotDirection{}, ambient{},
        diffuse{}, specular{};
    std::array<float, kMaxGlLights * 4> spot{};
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const LightParams& light = scene.lights[i];
        const vec3 towardLight =
            light.kind == LightKind::Directional ? -normalize(light.direction) : vec3(0.0f);
        const vec3 axis =
            light.kind == LightKind::Spot ? normalize(light.spotDirection) : vec3(0.0f, 0.0f, -1.0f);
        const vec3 c(light.c0, light.c1, light.c2);
        for (int k = 0; k < 3; ++k) {
            position[i * 3 + k] = light.position[k];
            toward[i * 3 + k] = towardLight[k];
            attenuation[i * 3 + k] = c[k];
            spotDirection[i * 3 + k] = axis[k];
            ambient[i * 3 + k] = light.ambient[k];
            diffuse[i * 3 + k] = light.diffuse[k];
            specular[i * 3 + k] = light.specular[k];
        }
        spot[i * 4 + 0] = std::cos(glm::radians(light.spotCutoffDegrees));
        spot[i * 4 + 1] = light.spotExponent;
        spot[i * 4 + 2] = std::cos(glm::radians(light.spotOuterDegrees));
        spot[i * 4 + 3] = std::cos(glm::radians(light.spotInnerDegrees));
    }
    gl.glUseProgram(p.name);
    gl.glUniformMatrix4fv(p.clipFromView, 1, GL_FALSE, &scene.clipFromView[0][0]);
    gl.glUniform3fv(p.globalAmbient, 1, &scene.globalAmbient[0]);
    gl.glUniform3fv(p.lightPosition, kMaxGlLights, position.data());
    gl.glUniform3fv(p.lightToward, kMaxGlLights, toward.data());
    gl.glUniform3fv(p.lightAttenuation, kMaxGlLights, attenuation.data());
    gl.glUniform3fv(p.lightSpotDirection, kMaxGlLights, spotDirection.data());
    gl.glUniform4fv(p.lightSpot, kMaxGlLights, spot.data());
    gl.glUniform3fv(p.lightAmbient, kMaxGlLights, ambient.data());
    gl.glUniform3fv(p.lightDiffuse, kMaxGlLights, diffuse.data());
    gl.glUniform3fv(p.lightSpecular, kMaxGlLights, specular.data());
    const vec3 fogRange(scene.fog.start, scene.fog.end, scene.fog.density);
    gl.glUniform3fv(p.fogColor, 1, &scene.fog.color[0]);
    gl.glUniform3fv(p.fogRange, 1, &fogRange[0]);
}

void MesaPeer::Impl::setDrawUniforms(const Draw& draw) const {
    const Program& p = *draw.program;
    gl.glUniformMatrix4fv(p.viewFromObject, 1, GL_FALSE, &draw.viewFromObject[0][0]);
    gl.glUniformMatrix3fv(p.normalFromObject, 1, GL_FALSE, &draw.normalFromObject[0][0]);
    const PhongMaterial& m = draw.material;
    gl.glUniform3fv(p.materialEmission, 1, &m.emission[0]);
    gl.glUniform3fv(p.materialAmbient, 1, &m.ambient[0]);
    gl.glUniform3fv(p.materialDiffuse, 1, &m.diffuse[0]);
    gl.glUniform3fv(p.materialSpecular, 1, &m.specular[0]);
    gl.glUniform1f(p.materialShininess, m.shininess);
    gl.glUniform3fv(p.baseColor, 1, &draw.pbr.baseColor[0]);
    gl.glUniform1f(p.metalness, draw.pbr.metalness);
    gl.glUniform1f(p.alpha, alphaFromRoughness(draw.pbr.roughness));
    gl.glUniform3fv(p.dielectricF0, 1, &draw.pbr.f0[0]);
    gl.glUniform1f(p.opacity, draw.opacity);
}

}  // namespace facet
