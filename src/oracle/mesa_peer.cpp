// The OSMesa peer. Every OSMesa entry point comes from dlsym and every GL function from
// OSMesaGetProcAddress; the GL headers supply only types and constants. Rendering goes to a
// framebuffer object (RGBA32F colour, 32-bit float depth: the formats of Facet's Framebuffer), not to
// OSMesa's own buffer, because glFinish() would copy that buffer out to the caller's memory every
// frame, work that Facet's renderFrame() does not do.
//
// Split by concern: osmesa.h loads the library and its GL functions, mesa_glsl.cpp builds the GLSL
// programs, mesa_fixed_function.cpp sets OpenGL's fixed-function state, and this file uploads a scene
// and draws it.
#include "oracle/mesa_peer.h"

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "oracle/mesa_peer_impl.h"
#include "pipeline/color.h"
#include "pipeline/names.h"

namespace facet {

void MesaPeer::Impl::setBlendState(const Draw& draw) const {
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
        case BlendMode::OverGL:  // c as over, α = α_s·α_s + (1 − α_s)·α_d
            gl.glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_SRC_ALPHA,
                                   GL_ONE_MINUS_SRC_ALPHA);
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

GLuint MesaPeer::Impl::uploadTexture(const Texture& texture, TextureFilter filter) {
    GLuint name = 0;
    gl.glGenTextures(1, &name);
    gl.glBindTexture(GL_TEXTURE_2D, name);
    gl.glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    // Trilinear: Facet's own mip levels (prepareScene built them), so that both filter the same texels.
    const int levels = filter == TextureFilter::Trilinear ? texture.levelCount() : 1;
    std::vector<vec4> rows;
    for (int level = 0; level < levels; ++level) {
        const Texture& t = texture.level(level);
        rows.resize(static_cast<std::size_t>(t.width) * t.height);
        for (int y = 0; y < t.height; ++y)  // OpenGL's rows go bottom up
            for (int x = 0; x < t.width; ++x)
                rows[static_cast<std::size_t>(y) * t.width + x] = t.texel(x, t.height - 1 - y);
        gl.glTexImage2D(GL_TEXTURE_2D, level, GL_RGBA32F, t.width, t.height, 0, GL_RGBA, GL_FLOAT,
                        rows.data());
    }
    const GLint minFilter = filter == TextureFilter::Nearest     ? GL_NEAREST
                            : filter == TextureFilter::Trilinear ? GL_LINEAR_MIPMAP_LINEAR
                                                                 : GL_LINEAR;
    gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, minFilter);
    gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER,
                       filter == TextureFilter::Nearest ? GL_NEAREST : GL_LINEAR);
    gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, levels - 1);
    textures.push_back(name);
    return name;
}

namespace {

GLenum depthRenderbufferFormat(DepthBufferFormat format) {
    switch (format) {
        case DepthBufferFormat::Unorm16:
            return GL_DEPTH_COMPONENT16;
        case DepthBufferFormat::Unorm24:
            return GL_DEPTH_COMPONENT24;
        case DepthBufferFormat::Float:
        case DepthBufferFormat::ReversedFloat:
            break;
    }
    return GL_DEPTH_COMPONENT32F;
}

GLenum colorRenderbufferFormat(ColorBufferFormat format) {
    switch (format) {
        case ColorBufferFormat::Unorm8:
            return GL_RGBA8;
        case ColorBufferFormat::Half:
            return GL_RGBA16F;
        case ColorBufferFormat::Float:
            break;
    }
    return GL_RGBA32F;
}

}  // namespace

void MesaPeer::Impl::createFramebuffer(int w, int h, DepthBufferFormat depth, ColorBufferFormat color) {
    width = w;
    height = h;
    gl.glGenFramebuffers(1, &framebuffer);
    gl.glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    gl.glGenRenderbuffers(1, &colorBuffer);
    gl.glGenRenderbuffers(1, &depthBuffer);
    const bool floatPair = depth == DepthBufferFormat::Float && color == ColorBufferFormat::Float;
    const std::pair<GLenum, GLenum> asked{colorRenderbufferFormat(color), depthRenderbufferFormat(depth)};
    const std::pair<GLenum, GLenum> fallback{GL_RGBA8, GL_DEPTH_COMPONENT24};
    for (const auto& [colorFormat, depthFormat] :
         floatPair ? std::vector{asked, fallback} : std::vector{asked}) {
        gl.glBindRenderbuffer(GL_RENDERBUFFER, colorBuffer);
        gl.glRenderbufferStorage(GL_RENDERBUFFER, colorFormat, w, h);
        gl.glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colorBuffer);
        gl.glBindRenderbuffer(GL_RENDERBUFFER, depthBuffer);
        gl.glRenderbufferStorage(GL_RENDERBUFFER, depthFormat, w, h);
        gl.glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depthBuffer);
        gl.glGetError();  // an unsupported format shows in the status below
        if (gl.glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE) {
            if (floatPair) floatColor = colorFormat == GL_RGBA32F;
            return;
        }
    }
    throw std::runtime_error("the Mesa peer cannot create a " + std::to_string(w) + "x" + std::to_string(h) +
                             " framebuffer of " + std::string(nameOf(color)) + " colour and " +
                             std::string(nameOf(depth)) + " depth");
}

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
    const int threads = options.threads;
    const char* const driver = driverName(options.driver);
    if (threads < 1) throw std::invalid_argument("MesaPeer::open: threads must be at least 1");
    if (options.driver == MesaDriver::Softpipe && threads != 1)
        throw std::invalid_argument("MesaPeer::open: softpipe runs on one thread");

    // Load the library once; Mesa reads GALLIUM_DRIVER (and llvmpipe LP_NUM_THREADS) when it starts.
    OsMesaLibrary& lib = loadOsMesa(options);
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
    const std::string missing = resolveGlFunctions(lib, gl);
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
    impl->clipControl = extensions.find(" GL_ARB_clip_control ") != std::string::npos;

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
    if (scene.depthFormat == DepthBufferFormat::ReversedFloat && !p.clipControl)
        throw std::invalid_argument(
            "GlScene: reversed Z needs glClipControl (GL_ARB_clip_control), which "
            "this Mesa context does not offer");
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
            if (!name) name = p.uploadTexture(*map, scene.textureFilter);
            draw.texture = name;
        }
        if (const Texture* map = source.emissionMap; map && !map->empty()) {
            GLuint& name = textureNames[map];
            if (!name) name = p.uploadTexture(*map, scene.textureFilter);
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

    // Framebuffer and raster state: the whole framebuffer in the scene's formats, counter-clockwise
    // fronts, GL_LESS and depth cleared to 1 (reversed Z: 0..1 clip depth, GL_GREATER, cleared to 0).
    const bool reversedZ = scene.depthFormat == DepthBufferFormat::ReversedFloat;
    p.createFramebuffer(scene.width, scene.height, scene.depthFormat, scene.colorFormat);
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
    if (p.clipControl) gl.glClipControl(GL_LOWER_LEFT, reversedZ ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE);
    gl.glDepthFunc(reversedZ ? GL_GREATER : GL_LESS);
    gl.glDepthMask(GL_TRUE);
    gl.glDisable(GL_BLEND);  // each draw sets its own blending and depth writes
    gl.glBlendEquation(GL_FUNC_ADD);
    gl.glDisable(GL_DITHER);
    gl.glClearColor(scene.clearColor.r, scene.clearColor.g, scene.clearColor.b, scene.clearColor.a);
    gl.glClearDepth(reversedZ ? 0.0 : 1.0);
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
