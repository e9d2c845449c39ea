// The OSMesa peer. Every OSMesa entry point comes from dlsym and every GL function from
// OSMesaGetProcAddress; the GL headers supply only types and constants. Rendering goes to a
// framebuffer object (RGBA32F colour, 32-bit float depth: the formats of Facet's Framebuffer), not to
// OSMesa's own buffer, because glFinish() would copy that buffer out to the caller's memory every
// frame, work that Facet's renderFrame() does not do.
//
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
#include "oracle/mesa_peer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <dlfcn.h>

#define GL_GLEXT_PROTOTYPES  // declares the prototypes used below with decltype; nothing is linked
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

#include "pipeline/color.h"

// For sanitizer builds, the libraries' own leaks, which LeakSanitizer would report at exit: Mesa and LLVM
// keep process-lifetime allocations (the library is loaded once and never closed), and OpenImageIO
// 2.4's PNG reader loses a copy of its error message when libpng's error handler jumps out of a read
// (a truncated texture). Every program that can load Mesa or read a texture links this file.
extern "C" const char* __lsan_default_suppressions() {
    return "leak:libOSMesa\nleak:libLLVM\nleak:libgallium\nleak:swrast_dri\nleak:ImageInput::geterror\n";
}
// ...without a report of the suppressions used at exit: the command-line tests read standard error.
extern "C" const char* __lsan_default_options() {
    return "print_suppressions=0";
}

namespace facet {

namespace {

constexpr int kMaxGlLights = 8;  // GL_MAX_LIGHTS's guaranteed minimum; the GLSL programs' arrays too

// The GL functions the peer calls, each resolved through OSMesaGetProcAddress.
#define FACET_GL_FUNCTIONS(X)    \
    X(glActiveTexture)           \
    X(glAttachShader)            \
    X(glBindAttribLocation)      \
    X(glBindBuffer)              \
    X(glBindFragDataLocation)    \
    X(glBindFramebuffer)         \
    X(glBindRenderbuffer)        \
    X(glBindTexture)             \
    X(glBindVertexArray)         \
    X(glBlendEquation)           \
    X(glBlendFuncSeparate)       \
    X(glBufferData)              \
    X(glCheckFramebufferStatus)  \
    X(glClampColor)              \
    X(glClear)                   \
    X(glClearColor)              \
    X(glClearDepth)              \
    X(glCompileShader)           \
    X(glCreateProgram)           \
    X(glCreateShader)            \
    X(glCullFace)                \
    X(glDeleteBuffers)           \
    X(glDeleteFramebuffers)      \
    X(glDeleteProgram)           \
    X(glDeleteRenderbuffers)     \
    X(glDeleteShader)            \
    X(glDeleteTextures)          \
    X(glDeleteVertexArrays)      \
    X(glDepthFunc)               \
    X(glDepthMask)               \
    X(glDepthRange)              \
    X(glDisable)                 \
    X(glDrawElements)            \
    X(glEnable)                  \
    X(glEnableClientState)       \
    X(glEnableVertexAttribArray) \
    X(glFinish)                  \
    X(glFogf)                    \
    X(glFogfv)                   \
    X(glFogi)                    \
    X(glFramebufferRenderbuffer) \
    X(glFrontFace)               \
    X(glGenBuffers)              \
    X(glGenFramebuffers)         \
    X(glGenRenderbuffers)        \
    X(glGenTextures)             \
    X(glGenVertexArrays)         \
    X(glGetError)                \
    X(glGetProgramInfoLog)       \
    X(glGetProgramiv)            \
    X(glGetShaderInfoLog)        \
    X(glGetShaderiv)             \
    X(glGetString)               \
    X(glGetUniformLocation)      \
    X(glHint)                    \
    X(glLightModelfv)            \
    X(glLightModeli)             \
    X(glLightf)                  \
    X(glLightfv)                 \
    X(glLinkProgram)             \
    X(glLoadIdentity)            \
    X(glLoadMatrixf)             \
    X(glMaterialf)               \
    X(glMaterialfv)              \
    X(glMatrixMode)              \
    X(glNormalPointer)           \
    X(glPixelStorei)             \
    X(glProvokingVertex)         \
    X(glReadPixels)              \
    X(glRenderbufferStorage)     \
    X(glShadeModel)              \
    X(glShaderSource)            \
    X(glTexCoordPointer)         \
    X(glTexEnvi)                 \
    X(glTexImage2D)              \
    X(glTexParameteri)           \
    X(glUniform1f)               \
    X(glUniform1i)               \
    X(glUniform3fv)              \
    X(glUniform4fv)              \
    X(glUniformMatrix3fv)        \
    X(glUniformMatrix4fv)        \
    X(glUseProgram)              \
    X(glVertexAttribPointer)     \
    X(glVertexPointer)           \
    X(glViewport)

struct Gl {
#define FACET_GL_MEMBER(name) decltype(&::name) name = nullptr;
    FACET_GL_FUNCTIONS(FACET_GL_MEMBER)
#undef FACET_GL_MEMBER
};

// libOSMesa, loaded once per process and never unloaded (Mesa's LLVM keeps global state that
// dlclose would leave dangling).
struct OsMesaLibrary {
    bool tried = false;
    void* handle = nullptr;
    std::string loadError;
    MesaDriver driver = MesaDriver::Llvmpipe;  // as asked of the first open()
    int threads = 0;                           // as asked of the first open()
    decltype(&::OSMesaCreateContextAttribs) createContextAttribs = nullptr;
    decltype(&::OSMesaCreateContextExt) createContextExt = nullptr;
    decltype(&::OSMesaMakeCurrent) makeCurrent = nullptr;
    decltype(&::OSMesaGetCurrentContext) getCurrentContext = nullptr;
    decltype(&::OSMesaDestroyContext) destroyContext = nullptr;
    decltype(&::OSMesaGetProcAddress) getProcAddress = nullptr;
};

OsMesaLibrary& library() {
    static OsMesaLibrary instance;
    return instance;
}

template <class Function>
void resolveSymbol(void* handle, const char* name, Function& function) {
    function = reinterpret_cast<Function>(::dlsym(handle, name));
}

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

// "4.50" or "4.50 (compatibility)" → 450.
int glslVersion(const std::string& text) {
    int major = 0, minor = 0;
    if (std::sscanf(text.c_str(), "%d.%d", &major, &minor) != 2) return 0;
    return major * 100 + minor;
}

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
    }
    return 0;
}

// What a GLSL program writes for a blend: BLEND_OUTPUT 0 (c, α), 1 (α·c, α), 2 (mix(1, c, α), α).
int blendOutputCode(BlendMode blend) {
    switch (blend) {
        case BlendMode::Replace:
        case BlendMode::Over:
            return 0;
        case BlendMode::PremultipliedOver:
        case BlendMode::Additive:
            return 1;
        case BlendMode::Multiply:
            return 2;
    }
    return 0;
}

// What OpenGL's fixed function can draw, checked before any state is set: one line for the message.
// radialFog: the context has GL_NV_fog_distance.
void checkFixedFunction(const GlScene& scene, std::size_t drawIndex, bool radialFog) {
    const GlDraw& draw = scene.draws[drawIndex];
    const std::string where = "GlScene draw " + std::to_string(drawIndex) + " (fixed function): ";
    if (draw.reflection != ReflectionModel::BlinnPhong)
        throw std::invalid_argument(where + "fixed-function lighting is Blinn-Phong only");
    if (draw.emissionMap && !draw.emissionMap->empty())
        throw std::invalid_argument(where + "an emission map needs a shader (use GlProgram::PerVertex)");
    if (draw.blend != BlendMode::Replace && draw.blend != BlendMode::Over)
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

}  // namespace

const char* driverName(MesaDriver driver) {
    return driver == MesaDriver::Softpipe ? "softpipe" : "llvmpipe";
}

struct MesaPeer::Impl {
    OSMesaContext context = nullptr;
    float defaultBuffer[4] = {};  // OSMesa's own 1×1 buffer; frames go to `framebuffer`
    GLenum defaultBufferType = GL_FLOAT;
    Gl gl;
    std::string renderer, version, glslVersionText;
    MesaDriver driver = MesaDriver::Llvmpipe;
    int threads = 0;
    bool floatColor = true;
    bool radialFog = false;  // GL_NV_fog_distance: fixed-function fog at the radial distance

    // The GLSL programs, by their #define header, and their uniform locations.
    struct Program {
        GLuint name = 0;
        // Set once per load(): the scene's.
        GLint clipFromView, globalAmbient, lightPosition, lightToward, lightAttenuation, lightSpotDirection,
            lightSpot, lightAmbient, lightDiffuse, lightSpecular, fogColor, fogRange;
        // Set per draw.
        GLint viewFromObject, normalFromObject, materialEmission, materialAmbient, materialDiffuse,
            materialSpecular, materialShininess, baseColor, metalness, alpha, dielectricF0, opacity;
    };
    std::string versionLine;  // "#version 330" or "#version 130"
    std::map<std::string, Program> programs;

    // What load() uploaded.
    struct Draw {
        GLuint vertexArray = 0, vertexBuffer = 0, indexBuffer = 0;
        GLsizei indexCount = 0;
        GLuint texture = 0;                // 0: no diffuse map
        GLuint emissionTexture = 0;        // 0: no emission map (GLSL programs only)
        const Program* program = nullptr;  // nullptr: fixed function
        bool flat = false;
        mat4 viewFromObject{1.0f};
        mat3 normalFromObject{1.0f};
        PhongMaterial material;
        PbrMaterial pbr;
        float opacity = 1.0f;
        BlendMode blend = BlendMode::Replace;
        bool depthWrite = true;
    };
    std::vector<Draw> draws;
    std::vector<GLuint> textures;
    GLuint framebuffer = 0, colorBuffer = 0, depthBuffer = 0;
    int width = 0, height = 0;

    ~Impl() {
        if (context) library().destroyContext(context);
    }

    // Every call works on this peer's context, whichever peer was used last on this thread.
    void makeCurrent() {
        if (library().getCurrentContext() != context &&
            !library().makeCurrent(context, defaultBuffer, defaultBufferType, 1, 1))
            throw std::runtime_error("OSMesa cannot make the Mesa peer's context current");
    }

    void checkGl(const char* during) const {
        const GLenum error = gl.glGetError();
        if (error == GL_NO_ERROR) return;
        char code[16];
        std::snprintf(code, sizeof code, "0x%04x", error);
        throw std::runtime_error(std::string("OpenGL error ") + code + " while " + during);
    }

    // The first line of a compiler or linker log, for a one-line message.
    static std::string firstLine(const char* log) {
        std::string line(log);
        line = line.substr(0, line.find('\n'));
        return line.empty() ? "no log" : line;
    }

    GLuint compileShader(GLenum type, const std::string& source) const {
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

    // The program for one draw of `scene`: its #define header is the cache's key.
    const Program& program(const GlScene& scene, const GlDraw& draw) {
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
            "\n#define FRESNEL_EXACT " +
            (costTerms && scene.brdf.fresnel == FresnelModel::Exact ? "1" : "0") +
            "\n#define GEOMETRY_SMITH " +
            (costTerms && scene.brdf.geometry == GeometryTerm::SmithGGX ? "1" : "0") +
            "\n#define HAS_DIFFUSE_MAP " + (hasDiffuseMap ? "1" : "0") + "\n#define HAS_EMISSION_MAP " +
            (hasEmissionMap ? "1" : "0") + "\n#define CLAMP_COLOR " + (draw.clampColor ? "1" : "0") +
            "\n#define TWO_SIDED_FLIP " + (scene.twoSidedFlip ? "1" : "0") + "\n";
        header += "#define FOG_MODE " + std::to_string(fogModeCode(scene.fog.mode)) +
                  "\n#define FOG_RADIAL " + (scene.fog.distance == FogDistance::Radial ? "1" : "0") +
                  "\n#define BLEND_OUTPUT " + std::to_string(blendOutputCode(draw.blend)) + "\n";
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

    // The scene's uniforms: the projection and the lights, as lighting.h reads LightParams (the
    // directional vector and the spot axis normalised and the cosines taken on the CPU, as there).
    void setSceneUniforms(const Program& p, const GlScene& scene) const {
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

    // One draw's uniforms (GLM matrices are column-major, as GL expects).
    void setDrawUniforms(const Draw& draw) const {
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

    // Fixed-function lighting: the light model and the lights, given under an identity modelview so that
    // GL stores them as they are (eye space).
    void setFixedFunctionLights(const GlScene& scene) const {
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
            const vec4 position = light.kind == LightKind::Directional ? vec4(-light.direction, 0.0f)
                                                                       : vec4(light.position, 1.0f);
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

    // One fixed-function draw's state: modelview, material (front and back), shade model, texturing.
    void setFixedFunctionDraw(const Draw& draw) const {
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

    // One draw's blending and depth writes. The colour factors are gl_scene.h's; the alpha factors give
    // the alphas of pipeline/state.h's BlendMode, which the colour factors would not for Over
    // (α_s² + (1 − α_s)·α_d) and Multiply (α_s·α_d).
    void setBlendState(const Draw& draw) const {
        gl.glDepthMask(draw.depthWrite ? GL_TRUE : GL_FALSE);
        if (draw.blend == BlendMode::Replace) {
            gl.glDisable(GL_BLEND);
            return;
        }
        gl.glEnable(GL_BLEND);
        switch (draw.blend) {
            case BlendMode::Replace:
                break;
            case BlendMode::Over:  // c = α_s·c_s + (1 − α_s)·c_d, α = α_s + (1 − α_s)·α_d
                gl.glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
                break;
            case BlendMode::PremultipliedOver:  // c = c_s + (1 − α_s)·c_d, α likewise
                gl.glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
                break;
            case BlendMode::Additive:  // c = c_s + c_d, α = α_s + α_d
                gl.glBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
                break;
            case BlendMode::Multiply:  // c = c_s·c_d, α = α_d
                gl.glBlendFuncSeparate(GL_DST_COLOR, GL_ZERO, GL_ZERO, GL_ONE);
                break;
        }
    }

    // Fixed-function fog (the GLSL programs fog in their fragment shaders). OpenGL's fog coordinate is
    // a vertex output interpolated across the triangle, the factor f computed from it per fragment
    // (GL_FOG_HINT GL_NICEST asks for that). With GL_EYE_PLANE_ABSOLUTE_NV (GL's default) the coordinate
    // is |z_eye|, linear across a triangle (which clipping keeps on one side of the eye), so
    // interpolating it gives fog.h's per-pixel value exactly. GL_EYE_RADIAL_NV's |P_eye| is not linear:
    // its interpolation between the vertices overestimates the distance inside a triangle (|P| is
    // convex), where Facet and the GLSL programs take |P| per pixel; radial fog differs inside large
    // triangles.
    void setFixedFunctionFog(const FogParams& fog) const {
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

    // A texture as linear float RGBA (8-bit texels decoded as Facet's sampler decodes them), sampled
    // as Facet samples (bilinear, repeat, no mipmaps). Facet's row 0 is the top of the image (v = 1);
    // GL's first row is t = 0, so rows go up in reverse.
    GLuint uploadTexture(const Texture& texture) {
        std::vector<vec4> rows(static_cast<std::size_t>(texture.width) * texture.height);
        for (int y = 0; y < texture.height; ++y)
            for (int x = 0; x < texture.width; ++x)
                rows[static_cast<std::size_t>(y) * texture.width + x] =
                    texture.texel(x, texture.height - 1 - y);
        GLuint name = 0;
        gl.glGenTextures(1, &name);
        gl.glBindTexture(GL_TEXTURE_2D, name);
        gl.glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        gl.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, texture.width, texture.height, 0, GL_RGBA, GL_FLOAT,
                        rows.data());
        gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
        gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
        gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
        textures.push_back(name);
        return name;
    }
    // Colour and depth renderbuffers of the scene's size: RGBA32F + DEPTH_COMPONENT32F like Facet's
    // Framebuffer, or RGBA8 + 24-bit depth where float colour is not renderable.
    void createFramebuffer(int w, int h) {
        width = w;
        height = h;
        gl.glGenFramebuffers(1, &framebuffer);
        gl.glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        gl.glGenRenderbuffers(1, &colorBuffer);
        gl.glGenRenderbuffers(1, &depthBuffer);
        for (const bool useFloat : {true, false}) {
            gl.glBindRenderbuffer(GL_RENDERBUFFER, colorBuffer);
            gl.glRenderbufferStorage(GL_RENDERBUFFER, useFloat ? GL_RGBA32F : GL_RGBA8, w, h);
            gl.glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colorBuffer);
            gl.glBindRenderbuffer(GL_RENDERBUFFER, depthBuffer);
            gl.glRenderbufferStorage(GL_RENDERBUFFER, useFloat ? GL_DEPTH_COMPONENT32F : GL_DEPTH_COMPONENT24,
                                     w, h);
            gl.glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depthBuffer);
            gl.glGetError();  // an unsupported format shows in the status below
            if (gl.glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE) {
                floatColor = useFloat;
                return;
            }
        }
        throw std::runtime_error("the Mesa peer cannot create a " + std::to_string(w) + "x" +
                                 std::to_string(h) + " framebuffer");
    }
};

MesaPeer::MesaPeer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

MesaPeer::~MesaPeer() {
    if (!impl_) return;
    try {
        unload();
        impl_->makeCurrent();
        for (const auto& [key, program] : impl_->programs)
            impl_->gl.glDeleteProgram(program.name);
    } catch (const std::exception&) {  // the context is destroyed next, with everything in it
    }
}

std::unique_ptr<MesaPeer> MesaPeer::open(const MesaOptions& options, std::string& whyNot) {
    OsMesaLibrary& lib = library();
    const int threads = options.threads;
    const char* const driver = driverName(options.driver);
    if (threads < 1) throw std::invalid_argument("MesaPeer::open: threads must be at least 1");
    if (options.driver == MesaDriver::Softpipe && threads != 1)
        throw std::invalid_argument("MesaPeer::open: softpipe runs on one thread");

    // Load the library once; Mesa reads GALLIUM_DRIVER (and llvmpipe LP_NUM_THREADS) when it starts.
    if (!lib.tried) {
        lib.tried = true;
        lib.driver = options.driver;
        lib.threads = threads;
        ::setenv("GALLIUM_DRIVER", driver, 1);
        if (options.driver == MesaDriver::Llvmpipe)
            ::setenv("LP_NUM_THREADS", std::to_string(lpNumThreads(threads)).c_str(), 1);
        lib.handle = ::dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
        if (!lib.handle) {
            const char* error = ::dlerror();
            lib.loadError = error ? error : "libOSMesa.so.8 cannot be loaded";
        } else {
            resolveSymbol(lib.handle, "OSMesaCreateContextAttribs", lib.createContextAttribs);
            resolveSymbol(lib.handle, "OSMesaCreateContextExt", lib.createContextExt);
            resolveSymbol(lib.handle, "OSMesaMakeCurrent", lib.makeCurrent);
            resolveSymbol(lib.handle, "OSMesaGetCurrentContext", lib.getCurrentContext);
            resolveSymbol(lib.handle, "OSMesaDestroyContext", lib.destroyContext);
            resolveSymbol(lib.handle, "OSMesaGetProcAddress", lib.getProcAddress);
            if (!lib.createContextExt || !lib.makeCurrent || !lib.getCurrentContext || !lib.destroyContext ||
                !lib.getProcAddress)
                lib.loadError = "libOSMesa.so.8 lacks the OSMesa entry points";
        }
    }
    if (!lib.loadError.empty()) {
        whyNot = lib.loadError;
        return nullptr;
    }
    if (options.driver != lib.driver) {
        whyNot = std::string("Mesa already runs ") + driverName(lib.driver) + " in this process (it reads " +
                 "GALLIUM_DRIVER once); " + driver + " needs a process of its own";
        return nullptr;
    }
    if (threads != lib.threads) {
        whyNot = "llvmpipe already runs on " + std::to_string(lib.threads) +
                 " threads in this process (Mesa reads LP_NUM_THREADS once)";
        return nullptr;
    }

    // A compatibility-profile context: fixed-function lighting needs one.
    auto impl = std::make_unique<Impl>();
    impl->driver = options.driver;
    impl->threads = threads;
    if (lib.createContextAttribs) {
        const int attributes[] = {OSMESA_FORMAT,
                                  OSMESA_RGBA,
                                  OSMESA_DEPTH_BITS,
                                  0,
                                  OSMESA_STENCIL_BITS,
                                  0,
                                  OSMESA_ACCUM_BITS,
                                  0,
                                  OSMESA_PROFILE,
                                  OSMESA_COMPAT_PROFILE,
                                  0};
        impl->context = lib.createContextAttribs(attributes, nullptr);
    }
    if (!impl->context) impl->context = lib.createContextExt(OSMESA_RGBA, 0, 0, 0, nullptr);
    if (!impl->context) {
        whyNot = "OSMesa cannot create a GL context";
        return nullptr;
    }
    if (!lib.makeCurrent(impl->context, impl->defaultBuffer, GL_FLOAT, 1, 1)) {
        impl->defaultBufferType = GL_UNSIGNED_BYTE;
        if (!lib.makeCurrent(impl->context, impl->defaultBuffer, GL_UNSIGNED_BYTE, 1, 1)) {
            whyNot = "OSMesa cannot make its context current";
            return nullptr;
        }
    }

    // The GL functions.
    Gl& gl = impl->gl;
    std::string missing;
#define FACET_GL_RESOLVE(name)                                                \
    gl.name = reinterpret_cast<decltype(gl.name)>(lib.getProcAddress(#name)); \
    if (!gl.name) missing += std::string(missing.empty() ? "" : ", ") + #name;
    FACET_GL_FUNCTIONS(FACET_GL_RESOLVE)
#undef FACET_GL_RESOLVE
    if (!missing.empty()) {
        whyNot = "OSMesa lacks " + missing;
        return nullptr;
    }

    // It must be the driver asked for, and speak GLSL 1.30 at least (flat varyings).
    auto text = [&](GLenum name) {
        const GLubyte* value = gl.glGetString(name);
        return value ? std::string(reinterpret_cast<const char*>(value)) : std::string();
    };
    impl->renderer = text(GL_RENDERER);
    impl->version = text(GL_VERSION);
    impl->glslVersionText = text(GL_SHADING_LANGUAGE_VERSION);
    if (impl->renderer.find(driver) == std::string::npos) {
        whyNot = "OSMesa renders with \"" + impl->renderer + "\", not " + driver;
        return nullptr;
    }
    const int glsl = glslVersion(impl->glslVersionText);
    if (glsl < 130) {
        whyNot = "OSMesa offers GLSL " + impl->glslVersionText + "; the Mesa peer needs 1.30";
        return nullptr;
    }
    impl->versionLine = glsl >= 330 ? "#version 330" : "#version 130";
    const std::string extensions = " " + text(GL_EXTENSIONS) + " ";  // a compatibility context has it
    impl->radialFog = extensions.find(" GL_NV_fog_distance ") != std::string::npos;

    // A first program, so that a shader problem shows here, and a first framebuffer, which finds out
    // whether float colour is renderable (floatColor()).
    GlScene probe;
    probe.lights.resize(1);
    probe.draws.resize(1);
    probe.draws[0].program = GlProgram::PerPixel;
    probe.draws[0].frequency = ShadingFrequency::Phong;
    try {
        impl->program(probe, probe.draws[0]);
        impl->createFramebuffer(1, 1);
    } catch (const std::exception& error) {
        whyNot = error.what();
        return nullptr;
    }
    std::unique_ptr<MesaPeer> peer(new MesaPeer(std::move(impl)));
    peer->unload();
    return peer;
}

MesaDriver MesaPeer::driver() const {
    return impl_->driver;
}
const std::string& MesaPeer::renderer() const {
    return impl_->renderer;
}
const std::string& MesaPeer::version() const {
    return impl_->version;
}
const std::string& MesaPeer::shadingLanguageVersion() const {
    return impl_->glslVersionText;
}
int MesaPeer::threads() const {
    return impl_->threads;
}
// llvmpipe bins triangles on the application's thread and rasterizes them on LP_NUM_THREADS threads of
// its own, binning on while they work once a frame's bins fill up (a million triangles kept 1.3 cores
// busy with LP_NUM_THREADS=1). LP_NUM_THREADS=0 rasterizes on the application's thread: one in all.
int MesaPeer::lpNumThreads(int threads) {
    return threads == 1 ? 0 : threads;
}
bool MesaPeer::floatColor() const {
    return impl_->floatColor;
}

void MesaPeer::load(const GlScene& scene) {
    unload();
    Impl& p = *impl_;
    const Gl& gl = p.gl;

    // What GL cannot draw as asked, before anything is uploaded.
    if (scene.width < 1 || scene.height < 1)
        throw std::invalid_argument("GlScene: width and height must be at least 1");
    if (scene.lights.size() > static_cast<std::size_t>(kMaxGlLights))
        throw std::invalid_argument("GlScene: " + std::to_string(scene.lights.size()) +
                                    " lights, the Mesa peer draws at most " + std::to_string(kMaxGlLights));
    bool fixedFunction = false;
    for (std::size_t i = 0; i < scene.draws.size(); ++i) {
        const GlDraw& draw = scene.draws[i];
        const std::string where =
            "GlScene draw " + std::to_string(i) + " (" + programName(draw.program) + "): ";
        const bool perPixel = draw.program == GlProgram::PerPixel;
        if (perPixel != (draw.frequency == ShadingFrequency::Phong))
            throw std::invalid_argument(where + (perPixel ? "needs ShadingFrequency::Phong"
                                                          : "needs ShadingFrequency::Flat or Gouraud"));
        if (draw.indices.size() % 3 != 0)
            throw std::invalid_argument(where + "the index count is not a multiple of 3");
        for (const std::uint32_t index : draw.indices)
            if (index >= draw.vertices.size())
                throw std::invalid_argument(where + "index " + std::to_string(index) + " is past the " +
                                            std::to_string(draw.vertices.size()) + " vertices");
        if (draw.program == GlProgram::FixedFunction) {
            checkFixedFunction(scene, i, p.radialFog);
            fixedFunction = true;
        }
    }

    // Meshes: each draw's vertices (position, normal, uv: 32 bytes) and 32-bit indices, as Facet reads
    // them: fixed function through the conventional arrays, GLSL through generic attributes 0, 1, 2.
    static_assert(sizeof(MeshVertex) == 32 && offsetof(MeshVertex, normal) == 12 &&
                  offsetof(MeshVertex, uv) == 24);
    std::map<const Texture*, GLuint> textureNames;
    std::vector<const Impl::Program*> used;
    for (const GlDraw& source : scene.draws) {
        Impl::Draw draw;
        draw.indexCount = static_cast<GLsizei>(source.indices.size());
        draw.flat = source.frequency == ShadingFrequency::Flat;
        draw.viewFromObject = source.viewFromObject;
        draw.normalFromObject = source.normalFromObject;
        draw.material = source.material;
        draw.pbr = source.pbr;
        draw.opacity = source.opacity;
        draw.blend = source.blend;
        draw.depthWrite = source.depthWrite;
        gl.glGenVertexArrays(1, &draw.vertexArray);
        gl.glBindVertexArray(draw.vertexArray);
        gl.glGenBuffers(1, &draw.vertexBuffer);
        gl.glBindBuffer(GL_ARRAY_BUFFER, draw.vertexBuffer);
        gl.glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(source.vertices.size() * sizeof(MeshVertex)),
                        source.vertices.data(), GL_STATIC_DRAW);
        gl.glGenBuffers(1, &draw.indexBuffer);
        gl.glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, draw.indexBuffer);
        gl.glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                        static_cast<GLsizeiptr>(source.indices.size() * sizeof(std::uint32_t)),
                        source.indices.data(), GL_STATIC_DRAW);
        const GLsizei stride = sizeof(MeshVertex);
        const auto* normalOffset = reinterpret_cast<const void*>(offsetof(MeshVertex, normal));
        const auto* uvOffset = reinterpret_cast<const void*>(offsetof(MeshVertex, uv));
        if (source.program == GlProgram::FixedFunction) {
            gl.glEnableClientState(GL_VERTEX_ARRAY);
            gl.glVertexPointer(3, GL_FLOAT, stride, nullptr);
            gl.glEnableClientState(GL_NORMAL_ARRAY);
            gl.glNormalPointer(GL_FLOAT, stride, normalOffset);
            gl.glEnableClientState(GL_TEXTURE_COORD_ARRAY);
            gl.glTexCoordPointer(2, GL_FLOAT, stride, uvOffset);
        } else {
            gl.glEnableVertexAttribArray(0);
            gl.glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
            gl.glEnableVertexAttribArray(1);
            gl.glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, normalOffset);
            gl.glEnableVertexAttribArray(2);
            gl.glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, stride, uvOffset);
        }
        if (const Texture* map = source.diffuseMap; map && !map->empty()) {
            GLuint& name = textureNames[map];
            if (!name) name = p.uploadTexture(*map);
            draw.texture = name;
        }
        if (const Texture* map = source.emissionMap; map && !map->empty()) {
            GLuint& name = textureNames[map];
            if (!name) name = p.uploadTexture(*map);
            draw.emissionTexture = name;
        }
        if (source.program != GlProgram::FixedFunction) {
            draw.program = &p.program(scene, source);
            if (std::find(used.begin(), used.end(), draw.program) == used.end()) used.push_back(draw.program);
        }
        p.draws.push_back(draw);
    }
    gl.glBindVertexArray(0);
    for (const Impl::Program* program : used)
        p.setSceneUniforms(*program, scene);
    gl.glUseProgram(0);

    // Fixed-function state: the lights and light model, the projection, per-vertex normalisation of the
    // modelview's normals, texels modulating the lit colour; vertex colours clamped to [0, 1] (GL's
    // default, said here), fragment and read colours not (the framebuffer is float).
    if (fixedFunction) p.setFixedFunctionLights(scene);
    gl.glEnable(GL_LIGHTING);
    gl.glEnable(GL_NORMALIZE);
    gl.glMatrixMode(GL_PROJECTION);
    gl.glLoadMatrixf(&scene.clipFromView[0][0]);
    gl.glMatrixMode(GL_MODELVIEW);
    gl.glActiveTexture(GL_TEXTURE0);
    gl.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
    gl.glClampColor(GL_CLAMP_VERTEX_COLOR, GL_TRUE);
    gl.glClampColor(GL_CLAMP_FRAGMENT_COLOR, GL_FALSE);
    gl.glClampColor(GL_CLAMP_READ_COLOR, GL_FALSE);
    gl.glProvokingVertex(GL_LAST_VERTEX_CONVENTION);  // flat shading takes a triangle's last vertex
    p.setFixedFunctionFog(scene.fog);

    // Framebuffer and raster state: the whole framebuffer, counter-clockwise fronts, GL_LESS, depth 1.
    p.createFramebuffer(scene.width, scene.height);
    gl.glViewport(0, 0, scene.width, scene.height);
    gl.glDepthRange(0.0, 1.0);
    if (scene.cullBackFaces) {
        gl.glEnable(GL_CULL_FACE);
        gl.glCullFace(GL_BACK);
    } else {
        gl.glDisable(GL_CULL_FACE);
    }
    gl.glFrontFace(GL_CCW);
    gl.glEnable(GL_DEPTH_TEST);
    gl.glDepthFunc(GL_LESS);
    gl.glDepthMask(GL_TRUE);
    gl.glDisable(GL_BLEND);  // each draw sets its own blending and depth writes
    gl.glBlendEquation(GL_FUNC_ADD);
    gl.glDisable(GL_DITHER);
    gl.glClearColor(scene.clearColor.r, scene.clearColor.g, scene.clearColor.b, scene.clearColor.a);
    gl.glClearDepth(1.0);
    p.checkGl("uploading the scene");
}

void MesaPeer::renderFrame() {
    Impl& p = *impl_;
    p.makeCurrent();
    const Gl& gl = p.gl;
    gl.glBindFramebuffer(GL_FRAMEBUFFER, p.framebuffer);
    gl.glDepthMask(GL_TRUE);  // glClear writes depth only where the mask lets it: the last draw may have
                              // turned depth writes off
    gl.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl.glActiveTexture(GL_TEXTURE0);
    for (const Impl::Draw& draw : p.draws) {
        p.setBlendState(draw);
        if (draw.program) {
            gl.glUseProgram(draw.program->name);
            p.setDrawUniforms(draw);
        } else {
            p.setFixedFunctionDraw(draw);
        }
        if (draw.emissionTexture) {
            gl.glActiveTexture(GL_TEXTURE1);
            gl.glBindTexture(GL_TEXTURE_2D, draw.emissionTexture);
            gl.glActiveTexture(GL_TEXTURE0);
        }
        gl.glBindTexture(GL_TEXTURE_2D, draw.texture);
        gl.glBindVertexArray(draw.vertexArray);
        gl.glDrawElements(GL_TRIANGLES, draw.indexCount, GL_UNSIGNED_INT, nullptr);
    }
    gl.glFinish();
}

LinearImage MesaPeer::readImage() const {
    Impl& p = *impl_;
    p.makeCurrent();
    LinearImage image;
    image.width = p.width;
    image.height = p.height;
    std::vector<vec4> bottomUp(static_cast<std::size_t>(p.width) * p.height);
    p.gl.glBindFramebuffer(GL_FRAMEBUFFER, p.framebuffer);
    p.gl.glPixelStorei(GL_PACK_ALIGNMENT, 4);
    p.gl.glReadPixels(0, 0, p.width, p.height, GL_RGBA, GL_FLOAT, bottomUp.data());
    p.checkGl("reading the image back");
    image.pixels.resize(bottomUp.size());
    for (int y = 0; y < p.height; ++y)
        std::copy_n(bottomUp.begin() + static_cast<std::ptrdiff_t>(p.height - 1 - y) * p.width, p.width,
                    image.pixels.begin() + static_cast<std::ptrdiff_t>(y) * p.width);
    return image;
}

void MesaPeer::unload() {
    Impl& p = *impl_;
    p.makeCurrent();
    const Gl& gl = p.gl;
    for (const Impl::Draw& draw : p.draws) {
        gl.glDeleteVertexArrays(1, &draw.vertexArray);
        gl.glDeleteBuffers(1, &draw.vertexBuffer);
        gl.glDeleteBuffers(1, &draw.indexBuffer);
    }
    p.draws.clear();
    if (!p.textures.empty()) gl.glDeleteTextures(static_cast<GLsizei>(p.textures.size()), p.textures.data());
    p.textures.clear();
    if (p.framebuffer) {
        gl.glBindFramebuffer(GL_FRAMEBUFFER, 0);
        gl.glDeleteFramebuffers(1, &p.framebuffer);
        gl.glDeleteRenderbuffers(1, &p.colorBuffer);
        gl.glDeleteRenderbuffers(1, &p.depthBuffer);
        p.framebuffer = p.colorBuffer = p.depthBuffer = 0;
    }
    p.width = p.height = 0;
}

}  // namespace facet
