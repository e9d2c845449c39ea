// Renders a Scene with the pipeline: makes a frame of it from its loaded assets (prepareFrame, or
// prepareScene to load them too), then draws it (renderFrame) with the built-in surface shaders
// (shaders.h), one draw per object part (material).
#pragma once

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "io/image_io.h"
#include "io/scene_assets.h"
#include "pipeline/draw_run.h"
#include "pipeline/fragment_lists_resolve.h"
#include "pipeline/sample_position.h"
#include "raycast/ray_scene.h"
#include "render/frame_kernels.h"
#include "render/memory_estimate.h"
#include "render/transparency_sort.h"
#include "render/user_shaders.h"
#include "scene/camera.h"
#include "scene/mesh.h"
#include "scene/scene.h"
#include "shaders/shaders.h"

namespace facet {

// One draw's triangles: its own compact vertex array (flat shading, Facet preset: one vertex per corner,
// face normals) and its indices.
struct DrawTriangles {
    std::vector<MeshVertex> vertices;
    std::vector<std::uint32_t> indices;
};

// A transparent triangle, for sorting: which draw, which triangle of it.
struct TransparentTriangle {
    std::uint32_t draw;
    std::uint32_t triangle;
};

// The triangles of a frame's draws (in the frame's draw order) and its transparent triangles listed for
// sorting. Immutable once made and shared by every copy of the frame; a variant with other triangles
// gets its own (setTriangles), which is also what a FrameMemory's runs are cut for.
struct FrameGeometry {
    std::vector<DrawTriangles> draws;
    std::vector<TransparentTriangle> transparentTriangles;  // of every transparent draw, in file order
};

// One draw: the triangles of one material of one object.
struct PreparedDraw {
    // The draw's triangles in the frame's FrameGeometry (which its PreparedScene holds): views, so that
    // copying a draw copies no vertices. setTriangles points them.
    std::span<const MeshVertex> vertices;
    std::span<const std::uint32_t> indices;
    SurfaceUniforms uniforms;  // uniforms.blend: Replace for opaque draws
    ShadingFrequency frequency = ShadingFrequency::Phong;
    mat4 worldFromObject{1.0f};  // the object's placement (the turntable turns it)
    // Eye space from object space as placed now (turntable included), composed in double: the
    // uniforms' matrices are this rounded to float; ray queries and the reference start from it.
    glm::dmat4 viewFromObjectExact{1.0};
    // Drawn in the transparent pass: opacity or texture alpha below 1, or a blend other than over.
    bool transparent = false;
    // A shader of one's own ("shader", --shader), which then draws instead of the built-in surface
    // shader of `frequency`, with the values of its uniforms set by the scene and --uniform.
    UserShader userShader;
    std::vector<UniformSetting> userUniforms;
};

// What the shadows of a frame need, for its objects as placed (and its camera: all in eye space): the
// BVH of the opaque triangles for ray-cast shadows, the shadow maps, and what the draws' uniforms.shadows
// point to. Derived from the frame by prepareShadows and shared by copies that keep the placement; a
// variant that moves objects or changes its shadows builds its own.
struct FrameShadows {
    std::unique_ptr<RayScene> rays;  // null without ray-cast shadows
    std::vector<std::unique_ptr<ShadowMap>> maps;
    SceneShadows forShaders;
};

// A frame to draw: the camera, the pipeline state, the draws and what they draw with. Cheap to copy:
// the assets (meshes and textures, which the draws' uniforms point into), the triangles and the
// shadows are shared, immutable, so a copy is a variant to change (a turntable angle, other uniforms,
// fewer triangles) that leaves the original as it was and needs nothing of it to live on.
struct PreparedScene {
    Scene scene;
    Camera camera;
    DrawState state;
    vec4 clearColor{0.0f};  // linear (Facet preset) or as given (GL preset)
    // The environment map as the draws' uniforms have it, and whether it is the background: then every
    // pass fills the colour buffer with the map along each pixel's view ray before drawing.
    EnvironmentParams environment;
    bool environmentBackground = false;
    ColorEncoding encoding = kSrgbEncoding;  // how 8-bit image files encode the colour buffer
    std::shared_ptr<const SceneAssets> assets;
    std::vector<PreparedDraw> draws;
    std::shared_ptr<const FrameGeometry> geometry;              // the draws' triangles
    std::span<const TransparentTriangle> transparentTriangles;  // geometry's, in file order
    vec3 turntableCentre{0.0f};                                 // world space: the centre of the bounding box
    std::vector<std::string> warnings;  // from the importer and the camera, one line each
    std::size_t triangleCount = 0;
    std::size_t degenerateSkipped = 0;
    // The eye-space distance to the far side of the scene's bounding sphere: the scale of the scene's
    // coordinates, for the shadow rays' offset (shading/shadow.h).
    float sceneExtent = 1.0f;
    // Shadows: per light its method (in the uniforms' light order) and the maps' options; `shadows` is
    // null when no light casts shadows (nothing is built then).
    std::array<ShadowMethod, kMaxLights> shadowMethods{};
    ShadowMapOptions shadowMapOptions;
    std::shared_ptr<const FrameShadows> shadows;
};

// Gives `frame` the triangles `triangles` (one DrawTriangles per draw, in frame.draws' order) as a new
// FrameGeometry: points the draws' views at them, lists the transparent draws' triangles again and sets
// the triangle count. The old geometry stays with the copies that hold it; FrameMemory never reuses runs
// cut for it.
void setTriangles(PreparedScene& frame, std::vector<DrawTriangles> triangles);

// The scene's triangles as they are placed now, in eye space, for ray queries: one RayMesh per draw
// (the draw's index is the mesh's), transparent draws as see-through. The positions are kept in
// `positions` (per draw), which must outlive the meshes.
std::vector<RayMesh> rayMeshes(const PreparedScene& prepared, std::vector<std::vector<vec3>>& positions);

// Builds what the scene's shadows need (the BVH for ray-cast shadows, the shadow maps) for the objects as
// placed now, as a new FrameShadows, and points the draws' uniforms at it; nothing when no light casts
// shadows. prepareFrame and setTurntable call it; so must whoever changes a frame's placement or shadows.
void prepareShadows(PreparedScene& prepared);

// Refuses a scene no frame can be made of (InputError): an image size out of range, no objects, exact
// transparency multisampled.
void checkFrameSettings(const Scene& scene);

// The normal matrix of an object placed at viewFromObject (lecture deck A's vertex shader: n =
// normalize(N·nrm)): N = ((V·M)⁻¹)ᵀ of the upper-left 3×3, then divided by ∛|det| so that its determinant
// is 1 (the shaders renormalise normals; a scaled view would otherwise shrink them). The draws' uniforms
// hold `scaled` rounded to float.
struct NormalMatrix {
    glm::dmat3 inverseTranspose{1.0};  // ((V·M)⁻¹)ᵀ
    double determinant = 1.0;          // det(((V·M)⁻¹)ᵀ)
    glm::dmat3 scaled{1.0};  // inverseTranspose / ∛|determinant| (as it is when that is 0 or not finite)
};
NormalMatrix normalMatrix(const glm::dmat4& viewFromObject);

// Flat shading's face normal of the triangle a, b, c: (b − a) × (c − a), turned to agree with the sum
// of the corners' normals (so a model whose winding disagrees with its normals still lights the side
// its normals show), normalised; that sum normalised when the cross product has no length. A
// FaceNormalRecord, when given, receives the numbers.
struct FaceNormalRecord {
    vec3 cross{0.0f};       // (b − a) × (c − a)
    bool turned = false;    // it pointed against the corners' normals and was negated
    float length = 0.0f;    // |cross|
    bool fallback = false;  // no length: the corners' normals' sum instead
    vec3 normal{0.0f};
};
inline vec3 flatFaceNormal(const MeshVertex& a, const MeshVertex& b, const MeshVertex& c,
                           FaceNormalRecord* record = nullptr) {
    vec3 n = cross(b.position - a.position, c.position - a.position);
    if (record) record->cross = n;
    const bool turned = dot(n, a.normal + b.normal + c.normal) < 0.0f;
    if (turned) n = -n;
    const float length = glm::length(n);
    const bool usable = length > 0.0f && std::isfinite(length);
    n = usable ? n / length : normalize(a.normal + b.normal + c.normal);
    if (record) *record = {record->cross, turned, length, !usable, n};
    return n;
}

// The transparent pass's sort key of a triangle from its corners' eye-space depths z0, z1, z2 (each
// eyeDepthOf its object position): the distance along the view direction, −z, of its centroid,
// −(z0 + z1 + z2)/3, or of its farthest corner, −min(z0, z1, z2). Larger is farther.
inline float eyeDepthOf(const mat4& viewFromObject, const vec3& position) {
    const mat4& m = viewFromObject;
    const vec3 row(m[0][2], m[1][2], m[2][2]);  // z_eye = row · p + m[3][2]
    return dot(row, position) + m[3][2];
}
inline float sortKeyOf(SortKey key, float z0, float z1, float z2) {
    return key == SortKey::FarthestVertex ? -std::min({z0, z1, z2}) : -(z0 + z1 + z2) * (1.0f / 3.0f);
}

// The frame of `scene` drawn from `assets` (loaded for it: assetOptionsFor(scene)): camera, lights,
// materials, draws, shadows.
// Facet preset: every colour a user writes (MTL Ka/Kd/Ks/Ke, scene materials, lights, background,
// ambient) is taken as an sRGB-encoded value, as a colour picker shows it, and decoded to linear light
// here; lighting and blending then happen in linear space. GL preset: colours are used as given and
// written without encoding (docs/lighting.md). Lights end up in eye space. Throws InputError for
// unusable input, and std::invalid_argument for assets loaded for another scene.
PreparedScene prepareFrame(const Scene& scene, std::shared_ptr<const SceneAssets> assets);

// Loads every model and texture the scene names (loadSharedAssets) and makes its frame (prepareFrame).
// Throws InputError for unusable input, textures beyond `limits` included (an unreadable texture is a
// warning instead).
PreparedScene prepareScene(const Scene& scene, const TextureLimits& limits = {});

// The frame of `scene` drawn from `assets` when they were loaded with the options it needs (a variant of
// the scene that changes nothing about loading, as most of the trade's knobs), else from its own, loaded
// now.
PreparedScene prepareScene(const Scene& scene, std::shared_ptr<const SceneAssets> assets,
                           const TextureLimits& limits = {});

// Turns every object by `degrees` about the vertical (world y) axis through turntableCentre, as on a
// turntable: camera and lights stay where they are. 0 is the scene as written. The shadows are built
// again for the turned objects.
void setTurntable(PreparedScene& prepared, float degrees);

// A copy of `prepared` turned by `degrees` (setTurntable); `prepared` stays as it is.
PreparedScene turned(const PreparedScene& prepared, float degrees);

// What a frame keeps for the next one: the back-to-front order of the transparent triangles (so that
// insertion sort starts from an almost sorted order), and scratch buffers.
struct FrameMemory {
    TransparencySorter sorter;
    std::vector<float> keys;                  // per transparent triangle
    std::vector<float> vertexDepths;          // z_eye of one draw's vertices, for the keys
    std::vector<std::uint32_t> runIndices;    // the index lists of the transparent runs
    std::vector<std::uint32_t> runTriangles;  // per triangle of a run: its number in its draw (index / 3)
    // The runs' compact vertex arrays, one after another: each run carries only the vertices it uses,
    // so that a draw cut into thousands of runs is not shaded whole thousands of times.
    std::vector<MeshVertex> runVertices;
    // The runs of the sorted transparent pass, in drawing order: each one's draw, its indices
    // [firstIndex, firstIndex + indexCount) in runIndices (its triangles from firstIndex / 3 in
    // runTriangles) and its vertices in runVertices (vertexCount 0: the run has all of its draw's
    // triangles and uses the draw's own vertex array).
    struct TransparentRun {
        std::uint32_t draw = 0;
        std::size_t firstIndex = 0, indexCount = 0;
        std::size_t firstVertex = 0, vertexCount = 0;
    };
    std::vector<TransparentRun> runs;
    // The triangles the runs were cut for (empty: none), held weakly: a geometry made later, even at the
    // same address, never counts as the same.
    std::weak_ptr<const FrameGeometry> runsGeometry;
    // While a run is compacted: for each vertex of its draw, its index in the run's array, or kNotInRun;
    // and the draw's indices of the vertices copied so far, to put kNotInRun back after the run.
    std::vector<std::uint32_t> runVertexOf;
    std::vector<std::uint32_t> runVertexSources;
    static constexpr std::uint32_t kNotInRun = 0xffffffffu;
    // Supersampling: the sum of the sample passes' linear colours per pixel (empty without it).
    std::vector<vec4> sampleSum;
};

struct FrameStats {
    DrawStats draw;
    SortStats sort;                   // transparent triangles sorted this frame (elements = 0: none)
    double sortMilliseconds = 0;      // keys and sort
    std::size_t transparentRuns = 0;  // draw calls of the transparent pass
    bool runsReused = false;          // the sort moved nothing: the last frame's runs were drawn again
    std::size_t drawRuns = 0;         // runs of consecutive small draw calls drawn together (drawRun)
    FragmentListStats fragmentLists;  // exact transparency: fragments stored, the longest list, bytes held
    double resolveMilliseconds = 0;   // exact transparency: sorting and compositing the lists
    // The copy of the frame's code that drew it (frame_kernels.h): the dispatched renderFrame's choice;
    // baseline for an observed frame, which always runs the baseline code.
    InstructionSet instructionSet = InstructionSet::Baseline;
};

// One draw call of a frame, in order: an opaque part whole, or a run of consecutive transparent
// triangles of one part (back to front across all transparent parts).
struct PlannedDraw {
    std::uint32_t draw;  // index into PreparedScene::draws: its uniforms and shading
    // The draw's own vertices and indices; or, for a run of some of its triangles, a compact copy of
    // just the vertices the run uses and the run's indices into it (both in FrameMemory).
    std::span<const MeshVertex> vertices;
    std::span<const std::uint32_t> indices;
    DrawState state;  // depth writes off and blending for transparent runs
    // Empty: triangle t of this call is triangle t of the draw. A transparent run: triangle t of the run
    // is triangle triangles[t] of the draw (so what a frame observer sees keeps the draw's numbering).
    std::span<const std::uint32_t> triangles;

    std::uint32_t triangleOfDraw(std::uint32_t t) const { return triangles.empty() ? t : triangles[t]; }
};

// The frame's draw calls: opaque draws first, then the transparent triangles in the order `mode` gives
// (sorted back to front; file order; file order into the framebuffer's fragment lists, to be resolved
// after the last one). Fills stats.sort and sortMilliseconds. The draws' spans point into `prepared`
// and `memory`: valid until `memory` plans the next frame.
std::vector<PlannedDraw> planFrame(const PreparedScene& prepared, TransparencyMode mode, FrameMemory& memory,
                                   FrameStats& stats);

// Clears `target` to the scene's background and draws every object. `target` must be scene-sized. The
// code that runs is the copy compiled for the widest instruction set the CPU has (or FACET_ISA's:
// render/frame_kernels.h).
// With supersampling (scene.pipeline.antialiasing) the frame is drawn once per sample and `target`
// ends with the average colour and the last pass's depth.
// `terms` (LightingTerm bits) selects the lighting terms drawn: all of them, or one for a component image.
// `memory` carries the transparent triangles' order from frame to frame.
FrameStats renderFrame(const PreparedScene& prepared, Framebuffer& target, DrawContext& context,
                       FrameMemory& memory, std::uint8_t terms = kAllTerms);

// The same without memory between frames (the transparent triangles are sorted from scratch).
DrawStats renderFrame(const PreparedScene& prepared, Framebuffer& target, DrawContext& context,
                      std::uint8_t terms = kAllTerms);

// A frame watched by an observer of the pipeline (pipeline/observer.h: derive from NullObserver and
// override the hooks wanted): every hook of every draw call of the frame, in order, then the resolve
// of exact transparency. Triangle numbers are those of the call's draw (PreparedDraw::indices / 3),
// for transparent runs too. An observer may also have
//   void onPlannedDraw(const PlannedDraw& call, const PreparedDraw& draw);
// called before each draw call. With an enabled observer every draw runs on the calling thread; the
// image is the same bytes as without one. (renderFrame above is this with NullObserver.)
template <PipelineObserver Observer>
FrameStats renderFrame(const PreparedScene& prepared, Framebuffer& target, DrawContext& context,
                       FrameMemory& memory, Observer& observer, std::uint8_t terms = kAllTerms);

// An observer whose hooks are virtual functions that do nothing unless overridden: the pipeline's
// (pipeline/observer.h, as DrawWatcher has them) and onPlannedDraw. The observers of the libraries (the
// step mode's recorders, the reference comparison's) are FrameWatchers watching renderFrameWatched:
// the frame is compiled once for all of them (frame_watched.cpp) instead of once per observer type, and
// a watched frame is not the hot path.
class FrameWatcher : public DrawWatcher {
  public:
    void onDrawBegin(std::uint64_t /*drawId*/, const DrawState& /*state*/) override {}
    void onDrawEnd(std::uint64_t /*drawId*/, const DrawStats& /*stats*/) override {}
    void onVertex(std::uint32_t /*index*/, const vec4& /*clip*/, const float* /*varyings*/, int /*count*/,
                  std::uint8_t /*outcode*/) override {}
    void onAssembled(std::uint32_t /*triangle*/, const ClipPolygon& /*polygon*/) override {}
    void onClipped(std::uint32_t /*triangle*/, const ClipPolygon& /*polygon*/) override {}
    void onSetup(std::uint32_t /*triangle*/, const WindowTriangle& /*window*/, TriangleFate /*fate*/,
                 const TriangleSetup& /*setup*/) override {}
    void onCoverage(const CoverageEvent& /*event*/) override {}
    void onRejected(std::uint32_t /*triangle*/, TriangleFate /*fate*/) override {}
    void onFragment(const FragmentEvent& /*event*/) override {}
    void onResolve(const ResolveEvent& /*event*/) override {}
    // Before each draw call of the frame: the call (a draw, or a run of its transparent triangles).
    virtual void onPlannedDraw(const PlannedDraw& /*call*/, const PreparedDraw& /*draw*/) {}
};

// renderFrame with a FrameWatcher as its observer: every hook, in the order renderFrame gives them.
FrameStats renderFrameWatched(const PreparedScene& prepared, Framebuffer& target, DrawContext& context,
                              FrameMemory& memory, FrameWatcher& watcher, std::uint8_t terms = kAllTerms);

// The framebuffer's colour as an image (same linear values).
LinearImage toImage(const Framebuffer& framebuffer);
// The framebuffer's colour as an image to write, without a copy (valid while the framebuffer is).
inline ImageView viewOf(const Framebuffer& framebuffer) {
    return {framebuffer.width(), framebuffer.height(), framebuffer.colorSpan()};
}

// ---- the frame, watched or not ------------------------------------------------------------------

// The projection that draws the image shifted so that each pixel centre lands on the sample at
// `offset` from it: the scene moves by −offset in the window, which is a translation in normalised
// device coordinates by (−2·dx/width, +2·dy/height) (window y grows downwards, NDC y upwards:
// viewport.cpp's y_w = (1 − y_ndc)/2·height), applied after clipFromView, so in clip space
// x += t_x·w, y += t_y·w.
glm::dmat4 clipFromViewAtSample(const Camera& camera, SampleOffset offset, int width, int height);

// A point on the view ray through window position `window` (pixels, y down) of a projection whose inverse
// is `viewFromClip`: the direction from the eye (eye space) the environment map is read along.
glm::dvec3 environmentViewRay(const glm::dmat4& viewFromClip, glm::dvec2 window, int width, int height);

namespace detail {

// The environment as the background: every pixel (every sample, multisampled) gets the map's colour along
// its view ray through the pixel centre of the pass (`clipFromView`: the sample pass's projection; null:
// the camera's), rounded as the colour buffer stores it. Rows spread over the pool: the same bytes for
// any thread count. Draws then cover it as they cover the clear colour.
void fillEnvironmentBackground(const PreparedScene& prepared, Framebuffer& target,
                               const glm::dmat4* clipFromView, ThreadPool& pool);

// Supersampling: adds the colour of sample pass `pass` of `passes` into `sum` (pass 0 starts it),
// rows spread over the pool; after the last pass writes the average (the box filter's resolve, in
// linear light) to the target. Each pixel sums its passes in pass order: the same bytes for any
// number of threads.
void accumulateSamplePass(Framebuffer& target, std::vector<vec4>& sum, std::size_t pass, std::size_t passes,
                          ColorBufferFormat format, ThreadPool& pool);

// Forwards the pipeline's hooks for one draw call, the call's triangle numbers turned into its draw's.
template <class Observer>
struct DrawTriangleNumbers {
    static constexpr bool enabled = Observer::enabled;
    Observer& inner;
    const PlannedDraw& call;

    void onDrawBegin(std::uint64_t id, const DrawState& state) { inner.onDrawBegin(id, state); }
    void onDrawEnd(std::uint64_t id, const DrawStats& stats) { inner.onDrawEnd(id, stats); }
    void onVertex(std::uint32_t index, const vec4& clip, const float* varyings, int count,
                  std::uint8_t outcode) {
        inner.onVertex(index, clip, varyings, count, outcode);
    }
    void onAssembled(std::uint32_t t, const ClipPolygon& polygon) {
        inner.onAssembled(call.triangleOfDraw(t), polygon);
    }
    void onClipped(std::uint32_t t, const ClipPolygon& polygon) {
        inner.onClipped(call.triangleOfDraw(t), polygon);
    }
    void onSetup(std::uint32_t t, const WindowTriangle& window, TriangleFate fate,
                 const TriangleSetup& setup) {
        inner.onSetup(call.triangleOfDraw(t), window, fate, setup);
    }
    void onCoverage(CoverageEvent event) {
        event.triangle = call.triangleOfDraw(event.triangle);
        inner.onCoverage(event);
    }
    void onRejected(std::uint32_t t, TriangleFate fate) { inner.onRejected(call.triangleOfDraw(t), fate); }
    void onFragment(FragmentEvent event) {
        event.triangle = call.triangleOfDraw(event.triangle);
        inner.onFragment(event);
    }
    void onResolve(const ResolveEvent& event) { inner.onResolve(event); }
};

// A DrawWatcher (shaders/shader_module.h) that hands a user shader's draw's hooks to an observer.
template <class Observer>
class WatcherOf final : public DrawWatcher {
  public:
    explicit WatcherOf(Observer observer) : observer_(observer) {}
    void onDrawBegin(std::uint64_t id, const DrawState& state) override { observer_.onDrawBegin(id, state); }
    void onDrawEnd(std::uint64_t id, const DrawStats& stats) override { observer_.onDrawEnd(id, stats); }
    void onVertex(std::uint32_t index, const vec4& clip, const float* varyings, int count,
                  std::uint8_t outcode) override {
        observer_.onVertex(index, clip, varyings, count, outcode);
    }
    void onAssembled(std::uint32_t t, const ClipPolygon& p) override { observer_.onAssembled(t, p); }
    void onClipped(std::uint32_t t, const ClipPolygon& p) override { observer_.onClipped(t, p); }
    void onSetup(std::uint32_t t, const WindowTriangle& w, TriangleFate f, const TriangleSetup& s) override {
        observer_.onSetup(t, w, f, s);
    }
    void onCoverage(const CoverageEvent& e) override { observer_.onCoverage(e); }
    void onRejected(std::uint32_t t, TriangleFate f) override { observer_.onRejected(t, f); }
    void onFragment(const FragmentEvent& e) override { observer_.onFragment(e); }
    void onResolve(const ResolveEvent& e) override { observer_.onResolve(e); }

  private:
    Observer observer_;
};

// A draw call of a user shader: the module's own copy of the pipeline's draw for it.
template <class Observer>
DrawStats drawUserShader(const PlannedDraw& call, const PreparedDraw& d, const SurfaceUniforms& uniforms,
                         Framebuffer& target, DrawContext& context, Observer& observer) {
    const ShaderCall shaderCall{&call.state, &uniforms, d.userUniforms, call.vertices, call.indices};
    // The module compiled for the scene holds this draw's walk; a watched draw, or one of settings the
    // scene did not have, may find it compiled again (once) with its walk added.
    const ShaderModule& module =
        userShaderFor(d.userShader, backEndWalkOf(planDraw(call.state), Observer::enabled));
    if constexpr (Observer::enabled) {
        WatcherOf<DrawTriangleNumbers<Observer>> watcher(DrawTriangleNumbers<Observer>{observer, call});
        return module.drawWatched(shaderCall, target, context, watcher);
    } else {
        return module.draw(shaderCall, target, context);
    }
}

template <ShadingFrequency kFrequency, class Observer>
DrawStats drawSurface(const PlannedDraw& call, const SurfaceUniforms& uniforms, Framebuffer& target,
                      DrawContext& context, Observer& observer) {
    if constexpr (Observer::enabled)
        return draw<SurfaceShader<kFrequency>>(call.state, uniforms, call.vertices, call.indices, target,
                                               context, DrawTriangleNumbers<Observer>{observer, call});
    else
        return draw<SurfaceShader<kFrequency>>(call.state, uniforms, call.vertices, call.indices, target,
                                               context);
}

}  // namespace detail

namespace detail {

// A call's uniforms: its draw's, or a copy in `scratch` with the selected lighting terms and a
// supersampling pass's projection.
inline const SurfaceUniforms& callUniforms(const PreparedDraw& d, std::uint8_t terms,
                                           const glm::dmat4* clipFromView, SurfaceUniforms& scratch) {
    if (terms == kAllTerms && !clipFromView) return d.uniforms;
    scratch = d.uniforms;
    if (terms != kAllTerms) scratch.terms = terms;
    if (clipFromView) scratch.clipFromObject = mat4(*clipFromView * d.viewFromObjectExact);
    return scratch;
}

// Consecutive small draw calls of one shading frequency are drawn together (pipeline.h's drawRun, which
// draws them in runs of 64 calls per two threads: one job of the pool per run instead of two or three per
// call). One past the last call of the sequence that starts at plan[first] (first + 1: a call drawn alone).
inline std::size_t smallCallsEnd(const PreparedScene& prepared, std::span<const PlannedDraw> plan,
                                 std::size_t first) {
    const auto fits = [&](const PlannedDraw& call) {
        return fitsInRun(call.vertices.size(), call.indices.size()) &&
               !prepared.draws[call.draw].userShader.module;
    };
    if (!fits(plan[first])) return first + 1;
    const ShadingFrequency frequency = prepared.draws[plan[first].draw].frequency;
    const Viewport& viewport = plan[first].state.viewport;
    std::size_t end = first + 1;
    while (end < plan.size()) {
        const PlannedDraw& call = plan[end];
        if (!fits(call) || prepared.draws[call.draw].frequency != frequency ||
            !samePixels(call.state.viewport, viewport))
            break;
        ++end;
    }
    return end;
}

// Consecutive small calls, drawn with drawRun; `runs` gets the number of runs.
template <ShadingFrequency kFrequency>
DrawStats drawSurfaceRun(const PreparedScene& prepared, std::span<const PlannedDraw> calls,
                         std::uint8_t terms, const glm::dmat4* clipFromView, Framebuffer& target,
                         DrawContext& context, std::size_t& runs) {
    using S = SurfaceShader<kFrequency>;
    const bool adjusted = terms != kAllTerms || clipFromView;
    std::vector<SurfaceUniforms> adjustedUniforms(adjusted ? calls.size() : 0);
    std::vector<RunDraw<S>> draws(calls.size());
    for (std::size_t i = 0; i < calls.size(); ++i) {
        const PreparedDraw& d = prepared.draws[calls[i].draw];
        const SurfaceUniforms& uniforms =
            adjusted ? callUniforms(d, terms, clipFromView, adjustedUniforms[i]) : d.uniforms;
        draws[i] = {&calls[i].state, &uniforms, calls[i].vertices, calls[i].indices};
    }
    return drawRun<S>(std::span<const RunDraw<S>>(draws), target, context, &runs);
}

// body.template operator()<kFrequency>() for the frequency given at run time.
template <class Body>
decltype(auto) withShadingFrequency(ShadingFrequency frequency, Body&& body) {
    switch (frequency) {
        case ShadingFrequency::Flat:
        case ShadingFrequency::Constant:  // the flat shader with SurfaceUniforms::unlit
            return body.template operator()<ShadingFrequency::Flat>();
        case ShadingFrequency::Gouraud:
            return body.template operator()<ShadingFrequency::Gouraud>();
        case ShadingFrequency::Phong:
            break;
    }
    return body.template operator()<ShadingFrequency::Phong>();
}

// One pass of the frame: clears `target` and draws the plan; `clipFromView` (null: the camera's own)
// is the projection of a supersampling pass.
template <class Observer>
void drawFramePass(const PreparedScene& prepared, std::span<const PlannedDraw> plan, Framebuffer& target,
                   DrawContext& context, Observer& observer, std::uint8_t terms,
                   const glm::dmat4* clipFromView, FrameStats& stats) {
    // Exact transparency's lists may hold what the memory limit leaves beside the image (memory_estimate.h).
    const bool exact =
        prepared.scene.transparency.mode == TransparencyMode::Exact && !prepared.transparentTriangles.empty();
    if (exact) target.fragmentLists().setByteBudget(fragmentListBudget(prepared.scene));
    // The background and the far plane, as the buffers' formats store them.
    target.clear(roundToColorBuffer(prepared.state.colorBuffer, prepared.clearColor),
                 depthClearValue(prepared.state.depth.format), context.pool);
    if (prepared.environmentBackground)
        fillEnvironmentBackground(prepared, target, clipFromView, context.pool);
    for (std::size_t k = 0; k < plan.size();) {
        const PlannedDraw& call = plan[k];
        const PreparedDraw& d = prepared.draws[call.draw];
        // An observer watches draw by draw.
        if constexpr (!Observer::enabled && !requires { observer.onPlannedDraw(call, d); }) {
            const std::size_t end = smallCallsEnd(prepared, plan, k);
            if (end - k > 1) {
                const std::span<const PlannedDraw> calls = plan.subspan(k, end - k);
                std::size_t runs = 0;
                stats.draw += withShadingFrequency(d.frequency, [&]<ShadingFrequency kFrequency>() {
                    return drawSurfaceRun<kFrequency>(prepared, calls, terms, clipFromView, target, context,
                                                      runs);
                });
                stats.drawRuns += runs;
                k = end;
                continue;
            }
        }
        ++k;
        if constexpr (requires { observer.onPlannedDraw(call, d); }) observer.onPlannedDraw(call, d);
        SurfaceUniforms selected;
        const SurfaceUniforms& uniforms = callUniforms(d, terms, clipFromView, selected);
        if (d.userShader.module) {
            stats.draw += drawUserShader(call, d, uniforms, target, context, observer);
            continue;
        }
        stats.draw += withShadingFrequency(d.frequency, [&]<ShadingFrequency kFrequency>() {
            return drawSurface<kFrequency>(call, uniforms, target, context, observer);
        });
    }
    // Exact transparency: every pixel's fragments sorted by depth and composited, farthest first.
    if (exact) {
        checkFragmentListMemory(prepared.scene, target.fragmentLists().bytesRefused());
        const auto start = std::chrono::steady_clock::now();
        if constexpr (Observer::enabled)
            stats.fragmentLists = resolveFragmentLists(target, context.pool, observer);
        else
            stats.fragmentLists = resolveFragmentLists(target, context.pool);
        stats.resolveMilliseconds +=
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    // The cells no draw reached still wait for the clear's values (Framebuffer::clear).
    target.finishClear(context.pool);
}

}  // namespace detail

template <PipelineObserver Observer>
FrameStats renderFrame(const PreparedScene& prepared, Framebuffer& target, DrawContext& context,
                       FrameMemory& memory, Observer& observer, std::uint8_t terms) {
    FrameStats stats;
    // The plan (the transparent triangles' order included) is the same for every sample pass: it
    // depends on eye-space depths, not on where the pixels sample.
    const std::vector<PlannedDraw> plan =
        planFrame(prepared, prepared.scene.transparency.mode, memory, stats);
    // Multisampling: one pass into the framebuffer's sample planes (drawFramePass clears them), then
    // each pixel's samples averaged. Without it the planes are released and nothing more is cleared.
    const int multisamples = prepared.state.samples;
    if (target.samples() != multisamples) target.useSamples(multisamples);
    if (multisamples > 1) {
        detail::drawFramePass(prepared, plan, target, context, observer, terms, nullptr, stats);
        target.resolveSamples(prepared.state.colorBuffer, context.pool);
        return stats;
    }
    const std::span<const SampleOffset> samples =
        standardSamplePositions(samplesPerPixel(prepared.scene.pipeline.antialiasing));
    if (samples.size() <= 1) {
        detail::drawFramePass(prepared, plan, target, context, observer, terms, nullptr, stats);
        return stats;
    }
    for (std::size_t pass = 0; pass < samples.size(); ++pass) {
        const glm::dmat4 clipFromView =
            clipFromViewAtSample(prepared.camera, samples[pass], target.width(), target.height());
        detail::drawFramePass(prepared, plan, target, context, observer, terms, &clipFromView, stats);
        detail::accumulateSamplePass(target, memory.sampleSum, pass, samples.size(),
                                     prepared.state.colorBuffer, context.pool);
    }
    return stats;
}

}  // namespace facet
