// The Mesa peer's state (MesaPeer::Impl), shared by its files: osmesa.h loads the library and its GL
// functions, mesa_glsl.cpp builds the GLSL programs, mesa_fixed_function.cpp sets OpenGL's
// fixed-function state, mesa_peer.cpp uploads a scene and draws it. Internal to the oracle.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "oracle/mesa_peer.h"
#include "oracle/osmesa.h"

namespace facet {

constexpr int kMaxGlLights = 8;  // GL_MAX_LIGHTS's guaranteed minimum; the GLSL programs' arrays too

// What OpenGL's fixed function can draw, checked before any state is set: one line for the message.
// radialFog: the context has GL_NV_fog_distance.
void checkFixedFunction(const GlScene& scene, std::size_t drawIndex, bool radialFog);

// "4.50" or "4.50 (compatibility)" → 450.
int glslVersion(const std::string& text);

struct MesaPeer::Impl {
    OSMesaContext context = nullptr;
    float defaultBuffer[4] = {};  // OSMesa's own 1×1 buffer; frames go to `framebuffer`
    GLenum defaultBufferType = GL_FLOAT;
    Gl gl;
    std::string renderer, version, glslVersionText;
    MesaDriver driver = MesaDriver::Llvmpipe;
    int threads = 0;
    bool floatColor = true;
    bool radialFog = false;    // GL_NV_fog_distance: fixed-function fog at the radial distance
    bool clipControl = false;  // GL_ARB_clip_control (or OpenGL 4.5): reversed Z's 0..1 clip depth

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

    GLuint compileShader(GLenum type, const std::string& source) const;

    // The program for one draw of `scene`: its #define header is the cache's key.
    const Program& program(const GlScene& scene, const GlDraw& draw);

    // The scene's uniforms: the projection and the lights, as lighting.h reads LightParams (the
    // directional vector and the spot axis normalised and the cosines taken on the CPU, as there).
    void setSceneUniforms(const Program& p, const GlScene& scene) const;

    // One draw's uniforms (GLM matrices are column-major, as GL expects).
    void setDrawUniforms(const Draw& draw) const;

    // Fixed-function lighting: the light model and the lights, given under an identity modelview so that
    // GL stores them as they are (eye space).
    void setFixedFunctionLights(const GlScene& scene) const;

    // One fixed-function draw's state: modelview, material (front and back), shade model, texturing.
    void setFixedFunctionDraw(const Draw& draw) const;

    // One draw's blending and depth writes. The colour factors are gl_scene.h's; the alpha factors give
    // the alphas of pipeline/state.h's BlendMode, which the colour factors would not for Over
    // (α_s² + (1 − α_s)·α_d) and Multiply (α_s·α_d).
    void setBlendState(const Draw& draw) const;

    // Fixed-function fog (the GLSL programs fog in their fragment shaders). OpenGL's fog coordinate is
    // a vertex output interpolated across the triangle, the factor f computed from it per fragment
    // (GL_FOG_HINT GL_NICEST asks for that). With GL_EYE_PLANE_ABSOLUTE_NV (GL's default) the coordinate
    // is |z_eye|, linear across a triangle (which clipping keeps on one side of the eye), so
    // interpolating it gives fog.h's per-pixel value exactly. GL_EYE_RADIAL_NV's |P_eye| is not linear:
    // its interpolation between the vertices overestimates the distance inside a triangle (|P| is
    // convex), where Facet and the GLSL programs take |P| per pixel; radial fog differs inside large
    // triangles.
    void setFixedFunctionFog(const FogParams& fog) const;

    // A texture as linear float RGBA (8-bit texels decoded as Facet's sampler decodes them), sampled
    // as Facet samples (bilinear, repeat, no mipmaps). Facet's row 0 is the top of the image (v = 1);
    // GL's first row is t = 0, so rows go up in reverse.
    // A texture filtered as `filter` says; trilinear uploads each of Facet's own mip levels.
    GLuint uploadTexture(const Texture& texture, TextureFilter filter);

    // Colour and depth renderbuffers of the scene's size: RGBA32F + DEPTH_COMPONENT32F like Facet's
    // Framebuffer, or RGBA8 + 24-bit depth where float colour is not renderable.
    // A w × h framebuffer of the given formats; the default float pair falls back to RGBA8 and 24-bit
    // depth where float colour is not renderable (floatColor() then says false).
    void createFramebuffer(int w, int h, DepthBufferFormat depth = DepthBufferFormat::Float,
                           ColorBufferFormat color = ColorBufferFormat::Float);
};

}  // namespace facet
