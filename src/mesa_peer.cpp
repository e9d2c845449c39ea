// The OSMesa peer. Every OSMesa entry point comes from dlsym and every GL function from
// OSMesaGetProcAddress; the GL headers supply only types and constants. Rendering goes to a
// framebuffer object (RGBA32F colour, 32-bit float depth: the formats of Facet's Framebuffer), not to
// OSMesa's own buffer, because glFinish() would copy that buffer out to the caller's memory every
// frame, work that Facet's renderFrame() does not do.
#include "mesa_peer.h"

#include <array>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <vector>

#include <dlfcn.h>

#define GL_GLEXT_PROTOTYPES  // declares the prototypes used below with decltype; nothing is linked
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

namespace facet {

namespace {

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
    X(glBufferData)              \
    X(glCheckFramebufferStatus)  \
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
    X(glEnableVertexAttribArray) \
    X(glFinish)                  \
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
    X(glLinkProgram)             \
    X(glPixelStorei)             \
    X(glReadPixels)              \
    X(glRenderbufferStorage)     \
    X(glShaderSource)            \
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
    int threads = 0;  // as asked of the first open()
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

// The built-in shader (shaders.h), line for line in GLSL. Written without layout qualifiers so that
// it compiles as GLSL 1.30 as well as 3.30; attribute and output locations are bound before linking.
// The light count and the presence of a diffuse map are compiled in (LIGHT_COUNT, HAS_DIFFUSE_MAP: one
// program per combination, chosen per draw, as a GL engine would), because llvmpipe runs a loop with a
// uniform trip count and uniform-array indexing about twice as slowly as the unrolled loop (bunny,
// 1920×1080, one light: 50 vs 26 ms), while for Facet's compiled C++ the runtime loop costs next to
// nothing. The arithmetic per pixel is the same either way.
const char* const kVertexShader = R"(
in vec3 position;
in vec3 normal;
in vec2 uv;
uniform mat4 clipFromObject;
uniform mat4 worldFromObject;
uniform mat3 normalFromObject;
out vec3 worldPosition;
out vec3 worldNormal;  // not normalised after interpolation
out vec2 texcoord;
void main() {
    vec4 world = worldFromObject * vec4(position, 1.0);
    worldPosition = world.xyz;
    worldNormal = normalFromObject * normal;
    texcoord = uv;
    gl_Position = clipFromObject * vec4(position, 1.0);
}
)";

// c = k_e + a_global ⊗ k_a + Σ_lights c_light ⊗ (k_d·max(N·L, 0) + k_s·max(N·H, 0)^n), as in shaders.h.
const char* const kFragmentShader = R"(
in vec3 worldPosition;
in vec3 worldNormal;
in vec2 texcoord;
uniform vec3 eyeWorld;
uniform vec3 globalAmbient;
uniform vec4 lightPositionOrDirection[MAX_LIGHTS];  // w = 0: direction the light travels; w = 1: point
uniform vec3 lightColor[MAX_LIGHTS];
uniform vec3 materialAmbient;
uniform vec3 materialDiffuse;
uniform vec3 materialSpecular;
uniform vec3 materialEmission;
uniform float materialShininess;
uniform sampler2D diffuseMap;
out vec4 fragColor;
void main() {
    vec3 N = normalize(worldNormal);
    vec3 V = normalize(eyeWorld - worldPosition);
    if (dot(N, V) < 0.0) N = -N;
    vec3 kd = materialDiffuse;
#if HAS_DIFFUSE_MAP
    kd *= texture(diffuseMap, texcoord).rgb;
#endif

    vec3 color = materialEmission + globalAmbient * materialAmbient;
    for (int i = 0; i < LIGHT_COUNT; ++i) {
        vec4 light = lightPositionOrDirection[i];
        vec3 L = light.w == 0.0 ? -light.xyz : normalize(light.xyz - worldPosition);
        float NdotL = dot(N, L);
        if (NdotL <= 0.0) continue;
        vec3 H = normalize(L + V);
        float specular = materialShininess > 0.0 ? pow(max(dot(N, H), 0.0), materialShininess) : 1.0;
        color += lightColor[i] * (kd * NdotL + materialSpecular * specular);
    }
    fragColor = vec4(color, 1.0);
}
)";

// Interim: the uniforms the GLSL above reads, from the built-in shader's (eye space serves as its
// "world" space, the eye at the origin).
struct LegacyLight {
    vec4 positionOrDirection;
    vec3 color;
};
struct LegacyUniforms {
    mat4 clipFromObject, worldFromObject;
    mat3 normalFromObject;
    vec3 eyeWorld{0.0f}, globalAmbient;
    int lightCount = 0;
    std::array<LegacyLight, kMaxLights> lights{};
    PhongMaterial material;
    const Texture* diffuseMap = nullptr;
};
LegacyUniforms legacyUniforms(const SurfaceUniforms& u) {
    LegacyUniforms out;
    out.clipFromObject = u.clipFromObject;
    out.worldFromObject = u.viewFromObject;
    out.normalFromObject = u.normalFromObject;
    out.globalAmbient = u.globalAmbient;
    out.lightCount = u.lightCount;
    for (int i = 0; i < u.lightCount; ++i) {
        const LightParams& l = u.lights[i];
        out.lights[i] = {l.kind == LightKind::Directional ? vec4(l.direction, 0.0f) : vec4(l.position, 1.0f), l.diffuse};
    }
    out.material = u.material;
    out.diffuseMap = u.diffuseMap;
    return out;
}

GLenum glCompare(CompareOp op) {
    switch (op) {
        case CompareOp::Never:
            return GL_NEVER;
        case CompareOp::Less:
            return GL_LESS;
        case CompareOp::Equal:
            return GL_EQUAL;
        case CompareOp::LessEqual:
            return GL_LEQUAL;
        case CompareOp::Greater:
            return GL_GREATER;
        case CompareOp::NotEqual:
            return GL_NOTEQUAL;
        case CompareOp::GreaterEqual:
            return GL_GEQUAL;
        case CompareOp::Always:
            return GL_ALWAYS;
    }
    return GL_LESS;
}

// "4.50" or "4.50 (compatibility)" → 450.
int glslVersion(const std::string& text) {
    int major = 0, minor = 0;
    if (std::sscanf(text.c_str(), "%d.%d", &major, &minor) != 2) return 0;
    return major * 100 + minor;
}

}  // namespace

struct MesaPeer::Impl {
    OSMesaContext context = nullptr;
    float defaultBuffer[4] = {};  // OSMesa's own 1×1 buffer; frames go to `framebuffer`
    GLenum defaultBufferType = GL_FLOAT;
    Gl gl;
    std::string renderer, version;
    int threads = 0;
    bool floatColor = true;

    // The shader programs, by (light count, has a diffuse map), and their uniform locations.
    struct Program {
        GLuint name = 0;
        GLint clipFromObject, worldFromObject, normalFromObject, eyeWorld, globalAmbient,
            lightPositionOrDirection, lightColor, materialAmbient, materialDiffuse, materialSpecular,
            materialEmission, materialShininess;
    };
    std::string versionLine;  // "#version 330 core" or "#version 130"
    std::map<std::pair<int, bool>, Program> programs;

    // What load() uploaded.
    struct Draw {
        GLuint vertexArray = 0, vertexBuffer = 0, indexBuffer = 0;
        GLsizei indexCount = 0;
        GLuint texture = 0;  // 0: no diffuse map
        const Program* program = nullptr;
        LegacyUniforms uniforms;
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
            throw std::runtime_error(std::string("the Mesa peer's shader does not compile: ") + log);
        }
        return shader;
    }

    const Program& program(int lightCount, bool hasDiffuseMap) {
        Program& p = programs[{lightCount, hasDiffuseMap}];
        if (p.name) return p;
        const std::string header = versionLine + "\n#define MAX_LIGHTS " + std::to_string(kMaxLights) +
                                   "\n#define LIGHT_COUNT " + std::to_string(lightCount) +
                                   "\n#define HAS_DIFFUSE_MAP " + (hasDiffuseMap ? "1" : "0") + "\n";
        const GLuint vertex = compileShader(GL_VERTEX_SHADER, header + kVertexShader);
        const GLuint fragment = compileShader(GL_FRAGMENT_SHADER, header + kFragmentShader);
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
            throw std::runtime_error(std::string("the Mesa peer's shader does not link: ") + log);
        }
        auto uniform = [&](const char* name) { return gl.glGetUniformLocation(p.name, name); };
        p.clipFromObject = uniform("clipFromObject");
        p.worldFromObject = uniform("worldFromObject");
        p.normalFromObject = uniform("normalFromObject");
        p.eyeWorld = uniform("eyeWorld");
        p.globalAmbient = uniform("globalAmbient");
        p.lightPositionOrDirection = uniform("lightPositionOrDirection");
        p.lightColor = uniform("lightColor");
        p.materialAmbient = uniform("materialAmbient");
        p.materialDiffuse = uniform("materialDiffuse");
        p.materialSpecular = uniform("materialSpecular");
        p.materialEmission = uniform("materialEmission");
        p.materialShininess = uniform("materialShininess");
        gl.glUseProgram(p.name);
        gl.glUniform1i(uniform("diffuseMap"), 0);  // texture unit 0
        checkGl("building a shader program");
        return p;
    }

    // The uniforms of one draw, as BlinnPhongShader::Uniforms holds them (GLM matrices are column-major,
    // as GL expects).
    void setUniforms(const Program& location, const LegacyUniforms& u) const {
        gl.glUniformMatrix4fv(location.clipFromObject, 1, GL_FALSE, &u.clipFromObject[0][0]);
        gl.glUniformMatrix4fv(location.worldFromObject, 1, GL_FALSE, &u.worldFromObject[0][0]);
        gl.glUniformMatrix3fv(location.normalFromObject, 1, GL_FALSE, &u.normalFromObject[0][0]);
        gl.glUniform3fv(location.eyeWorld, 1, &u.eyeWorld[0]);
        gl.glUniform3fv(location.globalAmbient, 1, &u.globalAmbient[0]);
        float positions[kMaxLights * 4], colors[kMaxLights * 3];
        for (int i = 0; i < kMaxLights; ++i) {
            for (int c = 0; c < 4; ++c)
                positions[i * 4 + c] = u.lights[i].positionOrDirection[c];
            for (int c = 0; c < 3; ++c)
                colors[i * 3 + c] = u.lights[i].color[c];
        }
        gl.glUniform4fv(location.lightPositionOrDirection, kMaxLights, positions);
        gl.glUniform3fv(location.lightColor, kMaxLights, colors);
        const PhongMaterial& m = u.material;
        gl.glUniform3fv(location.materialAmbient, 1, &m.ambient[0]);
        gl.glUniform3fv(location.materialDiffuse, 1, &m.diffuse[0]);
        gl.glUniform3fv(location.materialSpecular, 1, &m.specular[0]);
        gl.glUniform3fv(location.materialEmission, 1, &m.emission[0]);
        gl.glUniform1f(location.materialShininess, m.shininess);
    }

    // A linear float RGBA texture sampled as Facet samples (bilinear, repeat, no mipmaps). Facet's
    // row 0 is the top of the image (v = 1); GL's first row is t = 0, so rows go up in reverse.
    GLuint uploadTexture(const Texture& texture) {
        std::vector<vec4> rows(texture.texels.size());
        for (int y = 0; y < texture.height; ++y)
            std::copy_n(&texture.texel(0, texture.height - 1 - y), texture.width,
                        rows.begin() + static_cast<std::ptrdiff_t>(y) * texture.width);
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
    } catch (const std::exception&) {  // the context is destroyed next, with everything in it
    }
}

std::unique_ptr<MesaPeer> MesaPeer::open(int threads, std::string& whyNot) {
    OsMesaLibrary& lib = library();
    if (threads < 1) throw std::invalid_argument("MesaPeer::open: threads must be at least 1");

    // Load the library once; llvmpipe reads GALLIUM_DRIVER and LP_NUM_THREADS when it starts.
    if (!lib.tried) {
        lib.tried = true;
        lib.threads = threads;
        ::setenv("GALLIUM_DRIVER", "llvmpipe", 1);
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
    if (threads != lib.threads) {
        whyNot = "llvmpipe already runs on " + std::to_string(lib.threads) +
                 " threads in this process (Mesa reads LP_NUM_THREADS once)";
        return nullptr;
    }

    // A core 3.3 context where OSMesa offers one, else the compatibility profile.
    auto impl = std::make_unique<Impl>();
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
                                  OSMESA_CORE_PROFILE,
                                  OSMESA_CONTEXT_MAJOR_VERSION,
                                  3,
                                  OSMESA_CONTEXT_MINOR_VERSION,
                                  3,
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

    // It must be llvmpipe, and speak GL 3.0 / GLSL 1.30 at least.
    auto text = [&](GLenum name) {
        const GLubyte* value = gl.glGetString(name);
        return value ? std::string(reinterpret_cast<const char*>(value)) : std::string();
    };
    impl->renderer = text(GL_RENDERER);
    impl->version = text(GL_VERSION);
    if (impl->renderer.find("llvmpipe") == std::string::npos) {
        whyNot = "OSMesa renders with \"" + impl->renderer + "\", not llvmpipe";
        return nullptr;
    }
    const int glsl = glslVersion(text(GL_SHADING_LANGUAGE_VERSION));
    if (glsl < 130) {
        whyNot = "OSMesa offers GLSL " + text(GL_SHADING_LANGUAGE_VERSION) + "; the peer needs 1.30";
        return nullptr;
    }
    impl->versionLine = glsl >= 330 ? "#version 330 core" : "#version 130";
    impl->program(1, false);        // a first compile, so that a shader problem shows here
    impl->createFramebuffer(1, 1);  // finds out whether float colour is renderable (floatColor())
    std::unique_ptr<MesaPeer> peer(new MesaPeer(std::move(impl)));
    peer->unload();
    return peer;
}

const std::string& MesaPeer::renderer() const {
    return impl_->renderer;
}
const std::string& MesaPeer::version() const {
    return impl_->version;
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

void MesaPeer::load(const PreparedScene& prepared) {
    unload();
    Impl& p = *impl_;
    const Gl& gl = p.gl;
    const DrawState& state = prepared.state;
    if (state.interpolation != Interpolation::PerspectiveCorrect || state.blend != BlendMode::Replace)
        throw std::invalid_argument("the Mesa peer mirrors perspective-correct, unblended draws only");

    // Meshes: each draw's vertices (position, normal, uv: 32 bytes) and 32-bit indices, as Facet reads them.
    static_assert(sizeof(MeshVertex) == 32 && offsetof(MeshVertex, normal) == 12 &&
                  offsetof(MeshVertex, uv) == 24);
    std::map<const Texture*, GLuint> textureNames;
    for (const PreparedDraw& source : prepared.draws) {
        Impl::Draw draw;
        draw.uniforms = legacyUniforms(source.uniforms);
        draw.indexCount = static_cast<GLsizei>(source.indices.size());
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
        gl.glEnableVertexAttribArray(0);
        gl.glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(0));
        gl.glEnableVertexAttribArray(1);
        gl.glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride,
                                 reinterpret_cast<const void*>(offsetof(MeshVertex, normal)));
        gl.glEnableVertexAttribArray(2);
        gl.glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, stride,
                                 reinterpret_cast<const void*>(offsetof(MeshVertex, uv)));
        if (const Texture* map = source.uniforms.diffuseMap; map && !map->empty()) {
            GLuint& name = textureNames[map];
            if (!name) name = p.uploadTexture(*map);
            draw.texture = name;
        }
        draw.program = &p.program(source.uniforms.lightCount, draw.texture != 0);
        p.draws.push_back(draw);
    }
    gl.glBindVertexArray(0);

    // Framebuffer and fixed-function state, as the scene's DrawState says. The viewport's y is flipped:
    // Facet counts rows from the top, GL from the bottom; the image is the same.
    p.createFramebuffer(prepared.scene.width, prepared.scene.height);
    const Viewport& v = state.viewport;
    gl.glViewport(v.x, p.height - (v.y + v.height), v.width, v.height);
    gl.glDepthRange(v.minDepth, v.maxDepth);
    if (state.raster.cull == CullMode::None) {
        gl.glDisable(GL_CULL_FACE);
    } else {
        gl.glEnable(GL_CULL_FACE);
        gl.glCullFace(state.raster.cull == CullMode::Back ? GL_BACK : GL_FRONT);
    }
    gl.glFrontFace(state.raster.frontFace == FrontFace::CounterClockwise ? GL_CCW : GL_CW);
    if (state.depth.testEnabled) {
        gl.glEnable(GL_DEPTH_TEST);
        gl.glDepthFunc(glCompare(state.depth.compare));
        gl.glDepthMask(state.depth.writeEnabled ? GL_TRUE : GL_FALSE);
    } else {
        gl.glDisable(GL_DEPTH_TEST);
    }
    gl.glDisable(GL_BLEND);
    gl.glDisable(GL_DITHER);
    gl.glClearColor(prepared.clearColor.r, prepared.clearColor.g, prepared.clearColor.b,
                    prepared.clearColor.a);
    gl.glClearDepth(1.0);
    p.checkGl("uploading the scene");
}

void MesaPeer::renderFrame() {
    Impl& p = *impl_;
    p.makeCurrent();
    const Gl& gl = p.gl;
    gl.glBindFramebuffer(GL_FRAMEBUFFER, p.framebuffer);
    gl.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl.glActiveTexture(GL_TEXTURE0);
    for (const Impl::Draw& draw : p.draws) {
        gl.glUseProgram(draw.program->name);
        p.setUniforms(*draw.program, draw.uniforms);
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

ImageAgreement compareImages(const LinearImage& a, const LinearImage& b, vec4 background,
                             float backgroundTolerance) {
    if (a.width != b.width || a.height != b.height || a.pixels.size() != b.pixels.size())
        throw std::invalid_argument("compareImages: the images differ in size");
    auto isForeground = [&](const vec4& c) {
        for (int channel = 0; channel < 3; ++channel)
            if (std::abs(c[channel] - background[channel]) > backgroundTolerance) return true;
        return false;
    };
    ImageAgreement result;
    std::size_t coverageSame = 0, bothCovered = 0, colorWithin = 0;
    double differenceSum = 0.0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        const bool inA = isForeground(a.pixels[i]);
        const bool inB = isForeground(b.pixels[i]);
        result.foregroundA += inA;
        result.foregroundB += inB;
        coverageSame += inA == inB;
        if (!(inA && inB)) continue;
        ++bothCovered;
        float difference = 0.0f;
        for (int channel = 0; channel < 3; ++channel) {
            const float d = std::abs(a.pixels[i][channel] - b.pixels[i][channel]);
            difference = std::max(difference, std::isnan(d) ? 1.0f : d);  // NaN counts as fully wrong
        }
        differenceSum += difference;
        colorWithin += difference <= ImageAgreement::kColorTolerance;
    }
    if (!a.pixels.empty()) result.coverageAgreement = static_cast<double>(coverageSame) / a.pixels.size();
    if (bothCovered) {
        result.colorWithinTolerance = static_cast<double>(colorWithin) / bothCovered;
        result.meanColorDifference = differenceSum / bothCovered;
    }
    return result;
}

}  // namespace facet
