// The renderer (render/renderer.h) without Mesa: a prepared scene's frame plan (planFrame) holds every
// object's draws, opaque ones first with depth writes, then the transparent triangles back to front in
// runs without depth writes and with their object's blend; renderFrame draws that plan (a bundled scene
// covers pixels), watched or not; a texture's top row is the top of the textured surface. The
// conformance tests compare these frames with OpenGL's, but only where OSMesa is installed: these tests
// keep the plumbing honest everywhere.
#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "support/bundled_models.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

using testing_support::TempFolder;

using testing_support::kModels;

// Pixels whose colour is not the clear colour (the framebuffer is cleared to exactly it).
std::size_t coveredPixels(const LinearImage& image, const vec4& clearColor) {
    std::size_t covered = 0;
    for (const vec4& pixel : image.pixels)
        covered += pixel != clearColor;
    return covered;
}

// ---- renderFrame draws the plan --------------------------------------------------------------------

// The bundled intersecting quads (an opaque floor and wall, three transparent panes) at 160×120:
// the floor and the wall fill most of the frame. Breaks if planFrame returns no draws, or renderFrame
// draws none of the plan.
TEST(Renderer, BundledSceneCoversMostOfTheFrame) {
    Scene scene = loadScene(kModels / "intersecting-quads.json");
    scene.width = 160;
    scene.height = 120;
    const PreparedScene prepared = prepareScene(scene);
    Framebuffer framebuffer(scene.width, scene.height);
    DrawContext context(1);
    FrameMemory memory;
    const FrameStats stats = renderFrame(prepared, framebuffer, context, memory);
    const LinearImage image = toImage(framebuffer);
    EXPECT_GT(coveredPixels(image, prepared.clearColor), image.pixels.size() / 2);
    EXPECT_GT(stats.draw.fragmentsShaded, image.pixels.size() / 2);
    EXPECT_GT(stats.transparentRuns, 0u);  // the panes are drawn too
}

// A frame leaves no cell of its clear pending (Framebuffer::clear): the cells its draws never reached
// are written by the frame, over the pool, not by whoever reads the image first. The cube at 640×480
// leaves most cells to the end. Breaks if renderFrame forgets finishClear.
TEST(Renderer, AFrameLeavesNoCellOfItsClearPending) {
    Scene scene = sceneForModel(kModels / "cube/cube.obj");
    scene.width = 640;
    scene.height = 480;
    const PreparedScene prepared = prepareScene(scene);
    Framebuffer framebuffer(scene.width, scene.height);
    DrawContext context(2);
    FrameMemory memory;
    renderFrame(prepared, framebuffer, context, memory);
    EXPECT_EQ(framebuffer.pendingCells(), 0u);
    const LinearImage image = toImage(framebuffer);
    EXPECT_EQ(image.pixels.front(), prepared.clearColor) << "a corner cell no draw reached";
}

// ---- planFrame -------------------------------------------------------------------------------------

// The intersecting quads (draw 0: the opaque backdrop; 1–3: the red, blue and green panes, d 0.5,
// blended over) and three cubes: 4 opaque but added ("blend": "additive"), 5 half transparent and
// multiplied, 6 opaque. Opaque and transparent draws alternate in file order on purpose.
PreparedScene mixedScene() {
    Scene scene = loadScene(kModels / "intersecting-quads.json");
    scene.width = 80;
    scene.height = 60;
    ObjectSpec cube;
    cube.model = kModels / "cube/cube.obj";
    cube.worldFromObject = glm::translate(mat4(1.0f), vec3(-0.6f, 0.5f, 0.8f));
    ObjectSpec added = cube;
    added.blend = BlendMode::Additive;
    ObjectSpec multiplied = cube;
    multiplied.worldFromObject = glm::translate(mat4(1.0f), vec3(0.6f, 0.5f, 0.6f));
    multiplied.material.opacity = 0.5f;
    multiplied.blend = BlendMode::Multiply;
    ObjectSpec opaque = cube;
    opaque.worldFromObject = glm::translate(mat4(1.0f), vec3(0.0f, 0.5f, -0.5f));
    scene.objects.push_back(added);
    scene.objects.push_back(multiplied);
    scene.objects.push_back(opaque);
    return prepareScene(scene);
}

// Every draw's state is the scene's state; transparent ones have depth writes off and their own blend.
void expectOpaqueState(const PlannedDraw& call, const PreparedScene& prepared) {
    EXPECT_TRUE(call.state.depth.testEnabled);
    EXPECT_TRUE(call.state.depth.writeEnabled);
    EXPECT_EQ(call.state.blend, BlendMode::Replace);
    EXPECT_EQ(call.state.raster.cull, prepared.state.raster.cull);
}

void expectTransparentState(const PlannedDraw& call, const PreparedScene& prepared) {
    EXPECT_TRUE(call.state.depth.testEnabled);
    EXPECT_FALSE(call.state.depth.writeEnabled);
    EXPECT_EQ(call.state.blend, prepared.draws[call.draw].uniforms.blend);
    EXPECT_EQ(call.state.raster.cull, prepared.state.raster.cull);
}

// The scene's draws are what the objects ask for: the blend of each transparent object.
TEST(Renderer, PreparedDrawsCarryTheirObjectsBlend) {
    const PreparedScene prepared = mixedScene();
    ASSERT_EQ(prepared.draws.size(), 7u);
    const std::vector<bool> transparent = {false, true, true, true, true, true, false};
    const std::vector<BlendMode> blend = {BlendMode::Replace, BlendMode::Over,     BlendMode::Over,
                                          BlendMode::Over,    BlendMode::Additive, BlendMode::Multiply,
                                          BlendMode::Replace};
    for (std::size_t k = 0; k < prepared.draws.size(); ++k) {
        SCOPED_TRACE(k);
        EXPECT_EQ(prepared.draws[k].transparent, transparent[k]);
        EXPECT_EQ(prepared.draws[k].uniforms.blend, blend[k]);
    }
}

// Unsorted: the opaque draws whole in file order, then the transparent ones whole in file order.
TEST(Renderer, UnsortedPlanIsOpaqueDrawsThenTransparentDrawsInFileOrder) {
    const PreparedScene prepared = mixedScene();
    FrameMemory memory;
    FrameStats stats;
    const std::vector<PlannedDraw> plan = planFrame(prepared, TransparencyMode::Unsorted, memory, stats);
    std::vector<std::uint32_t> order;
    for (const PlannedDraw& call : plan)
        order.push_back(call.draw);
    EXPECT_EQ(order, (std::vector<std::uint32_t>{0, 6, 1, 2, 3, 4, 5}));
    EXPECT_EQ(stats.transparentRuns, 5u);
    for (const PlannedDraw& call : plan) {
        SCOPED_TRACE(call.draw);
        const PreparedDraw& draw = prepared.draws[call.draw];
        EXPECT_EQ(call.indices.size(), draw.indices.size());  // whole
        if (draw.transparent)
            expectTransparentState(call, prepared);
        else
            expectOpaqueState(call, prepared);
    }
}

// Sorted: the opaque draws whole in file order, then runs of transparent triangles that together hold
// every transparent triangle once, farthest first (the key is the centroid's −z_eye, as sort_key
// "centroid" says: each run's triangles, and the runs one after another, never come nearer and then
// farther again).
TEST(Renderer, SortedPlanIsOpaqueDrawsThenEveryTransparentTriangleBackToFront) {
    const PreparedScene prepared = mixedScene();
    ASSERT_EQ(prepared.scene.transparency.key, SortKey::Centroid);
    FrameMemory memory;
    FrameStats stats;
    const std::vector<PlannedDraw> plan = planFrame(prepared, TransparencyMode::Sorted, memory, stats);
    ASSERT_GE(plan.size(), 2u + 5u);
    EXPECT_EQ(plan[0].draw, 0u);
    EXPECT_EQ(plan[1].draw, 6u);
    for (int i = 0; i < 2; ++i) {
        EXPECT_EQ(plan[i].indices.size(), prepared.draws[plan[i].draw].indices.size());
        expectOpaqueState(plan[i], prepared);
    }
    EXPECT_EQ(stats.transparentRuns, plan.size() - 2);
    EXPECT_EQ(stats.sort.elements, prepared.transparentTriangles.size());

    std::map<std::uint32_t, std::size_t> trianglesOf;  // per transparent draw, over its runs
    float previousDistance = INFINITY;
    for (std::size_t r = 2; r < plan.size(); ++r) {
        const PlannedDraw& run = plan[r];
        SCOPED_TRACE(::testing::Message() << "run " << r << ", draw " << run.draw);
        ASSERT_TRUE(prepared.draws[run.draw].transparent);
        expectTransparentState(run, prepared);
        ASSERT_EQ(run.indices.size() % 3, 0u);
        trianglesOf[run.draw] += run.indices.size() / 3;
        // Each run triangle names its triangle in the draw: the same corners.
        const PreparedDraw& d = prepared.draws[run.draw];
        ASSERT_EQ(run.triangles.size(), run.indices.size() / 3);
        for (std::size_t i = 0; i < run.triangles.size(); ++i)
            for (std::size_t c = 0; c < 3; ++c)
                EXPECT_EQ(run.vertices[run.indices[3 * i + c]].position,
                          d.vertices[d.indices[3 * run.triangles[i] + c]].position)
                    << "triangle " << i << ", corner " << c;
        const mat4& viewFromObject = prepared.draws[run.draw].uniforms.viewFromObject;
        for (std::size_t i = 0; i < run.indices.size(); i += 3) {
            float zSum = 0.0f;
            for (std::size_t c = 0; c < 3; ++c)
                zSum += (viewFromObject * vec4(run.vertices[run.indices[i + c]].position, 1.0f)).z;
            const float distance = -zSum / 3.0f;
            EXPECT_LE(distance, previousDistance + 1e-5f * std::abs(previousDistance))
                << "triangle " << i / 3;
            previousDistance = distance;
        }
    }
    for (std::uint32_t k = 1; k <= 5; ++k)
        EXPECT_EQ(trianglesOf[k], prepared.draws[k].indices.size() / 3) << "draw " << k;
    EXPECT_EQ(trianglesOf.size(), 5u);
}

// A still frame draws the last frame's runs again: the sort moved nothing, so the runs are reused, and
// the bytes are those of a frame planned from scratch. A turned frame changes the order: its runs are
// cut anew, again to a fresh memory's bytes. Breaks caught: reuse without the "no moves" condition (the
// turned frame draws the still frame's order), no reuse at all (runsReused stays false).
TEST(Renderer, AStillFrameReusesTheLastFramesRunsWithTheSameBytes) {
    PreparedScene prepared = mixedScene();
    DrawContext context(2);
    Framebuffer kept(prepared.scene.width, prepared.scene.height);
    Framebuffer fresh(prepared.scene.width, prepared.scene.height);
    FrameMemory memory;
    const auto expectFreshBytes = [&](const char* frame) {
        SCOPED_TRACE(frame);
        FrameMemory scratch;
        renderFrame(prepared, fresh, context, scratch);
        const LinearImage a = toImage(kept), b = toImage(fresh);
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(vec4)), 0);
    };
    EXPECT_FALSE(renderFrame(prepared, kept, context, memory).runsReused);  // the first frame
    expectFreshBytes("first");
    const FrameStats still = renderFrame(prepared, kept, context, memory);
    EXPECT_TRUE(still.runsReused);
    EXPECT_EQ(still.sort.moves, 0u);
    expectFreshBytes("still");
    setTurntable(prepared, 180.0f);  // the panes' order reverses
    const FrameStats turned = renderFrame(prepared, kept, context, memory);
    EXPECT_GT(turned.sort.moves, 0u);
    EXPECT_FALSE(turned.runsReused);
    expectFreshBytes("turned");
}

// Reused runs are drawn with the states the scene has now (a blend changed between frames reaches the
// calls), and a memory moved to another scene with as many transparent triangles cuts its runs anew.
// Breaks caught: keeping the last frame's calls whole (their old blend), dropping the scene check.
TEST(Renderer, ReusedRunsTakeTheScenesStatesAndBelongToOneScene) {
    PreparedScene prepared = mixedScene();
    FrameMemory memory;
    FrameStats first, second;
    planFrame(prepared, TransparencyMode::Sorted, memory, first);
    prepared.draws[1].uniforms.blend = BlendMode::Additive;
    const std::vector<PlannedDraw> plan = planFrame(prepared, TransparencyMode::Sorted, memory, second);
    ASSERT_TRUE(second.runsReused);
    std::size_t runsOfDraw1 = 0;
    for (const PlannedDraw& call : plan)
        if (call.draw == 1) {
            ++runsOfDraw1;
            EXPECT_EQ(call.state.blend, BlendMode::Additive);
        }
    EXPECT_GT(runsOfDraw1, 0u);

    const PreparedScene twin = mixedScene();  // the same triangles, another scene
    ASSERT_NE(twin.geometry, prepared.geometry);
    FrameStats third;
    planFrame(twin, TransparencyMode::Sorted, memory, third);
    EXPECT_FALSE(third.sort.fromScratch);
    EXPECT_FALSE(third.runsReused);
}

// ---- Watching a frame ------------------------------------------------------------------------------

// Records what a frame observer sees: the draw calls, and per call the triangles that reached primitive
// assembly or were rejected before it, by the numbers the hooks give; and every hook in order. A
// FrameWatcher, so that it watches renderFrame as a template observer (its hooks called directly) and
// renderFrameWatched through the virtual functions alike.
struct FrameRecorder final : FrameWatcher {
    std::vector<std::uint32_t> callDraws;               // PlannedDraw::draw of each call, in order
    std::vector<std::vector<std::uint32_t>> triangles;  // per call
    std::size_t fragments = 0, resolvedPixels = 0;
    // Every hook: which one (its place in pipeline/observer.h, the planned draw last), and the triangle,
    // vertex or draw and the pixel it names (0 where it names none).
    std::vector<std::array<std::uint32_t, 4>> hooks;

    // The call's triangle list; a triangle before any onPlannedDraw (a frame that did not call it) gets
    // a list of its own, so that the hooks' comparison, not a crash, reports it.
    std::vector<std::uint32_t>& callTriangles() {
        if (triangles.empty()) triangles.emplace_back();
        return triangles.back();
    }

    void onPlannedDraw(const PlannedDraw& call, const PreparedDraw&) override {
        callDraws.push_back(call.draw);
        triangles.emplace_back();
        hooks.push_back({10, call.draw, 0, 0});
    }
    void onDrawBegin(std::uint64_t id, const DrawState&) override {
        hooks.push_back({0, static_cast<std::uint32_t>(id), 0, 0});
    }
    void onDrawEnd(std::uint64_t id, const DrawStats&) override {
        hooks.push_back({1, static_cast<std::uint32_t>(id), 0, 0});
    }
    void onVertex(std::uint32_t index, const vec4&, const float*, int, std::uint8_t) override {
        hooks.push_back({2, index, 0, 0});
    }
    void onAssembled(std::uint32_t triangle, const ClipPolygon&) override {
        callTriangles().push_back(triangle);
        hooks.push_back({3, triangle, 0, 0});
    }
    void onClipped(std::uint32_t triangle, const ClipPolygon&) override {
        hooks.push_back({4, triangle, 0, 0});
    }
    void onSetup(std::uint32_t triangle, const WindowTriangle&, TriangleFate, const TriangleSetup&) override {
        hooks.push_back({5, triangle, 0, 0});
    }
    void onCoverage(const CoverageEvent& e) override {
        hooks.push_back({6, e.triangle, static_cast<std::uint32_t>(e.x), static_cast<std::uint32_t>(e.y)});
    }
    void onRejected(std::uint32_t triangle, TriangleFate) override {
        callTriangles().push_back(triangle);
        hooks.push_back({7, triangle, 0, 0});
    }
    void onFragment(const FragmentEvent& e) override {
        ++fragments;
        hooks.push_back({8, e.triangle, static_cast<std::uint32_t>(e.x), static_cast<std::uint32_t>(e.y)});
    }
    void onResolve(const ResolveEvent& e) override {
        ++resolvedPixels;
        hooks.push_back({9, 0, static_cast<std::uint32_t>(e.x), static_cast<std::uint32_t>(e.y)});
    }
};

// Watching a frame changes no byte of colour or depth, sorted or exact (breaks caught: an observed
// frame drawing its calls in another order, or skipping the resolve). The unwatched frame draws the
// sorted transparent calls in runs (drawRun), the watched one call by call: also caught, a run that
// draws its calls out of order or with another call's state or uniforms. renderFrameWatched, the frame
// compiled once for every FrameWatcher (the step mode's recorders, the reference comparison's), hands
// its watcher every hook the template observer gets, in the same order, and draws the same bytes
// (caught: a hook not forwarded, onPlannedDraw among them, or the watched frame drawn with other terms).
TEST(Renderer, WatchingAFrameChangesNoByte) {
    const auto terms = static_cast<std::uint8_t>(kAllTerms & ~kSpecularTerm);
    for (const TransparencyMode mode : {TransparencyMode::Sorted, TransparencyMode::Exact}) {
        PreparedScene prepared = mixedScene();
        prepared.scene.transparency.mode = mode;
        Framebuffer plain(prepared.scene.width, prepared.scene.height);
        Framebuffer watched(prepared.scene.width, prepared.scene.height);
        Framebuffer watcherWatched(prepared.scene.width, prepared.scene.height);
        DrawContext threads(3), calling(1), watcherCalling(1);
        FrameMemory plainMemory, watchedMemory, watcherMemory;
        const FrameStats plainStats = renderFrame(prepared, plain, threads, plainMemory, terms);
        EXPECT_GT(plainStats.drawRuns, 0u);
        FrameRecorder recorder, watcher;
        renderFrame(prepared, watched, calling, watchedMemory, recorder, terms);
        renderFrameWatched(prepared, watcherWatched, watcherCalling, watcherMemory, watcher, terms);
        EXPECT_GT(recorder.fragments, 0u);
        EXPECT_EQ(recorder.resolvedPixels > 0, mode == TransparencyMode::Exact);
        for (std::uint32_t kind = 0; kind <= 10; ++kind) {
            // The scene has no triangle clipped or rejected, and only exact transparency resolves lists.
            if (kind == 4 || kind == 7 || (kind == 9 && mode != TransparencyMode::Exact)) continue;
            EXPECT_TRUE(std::any_of(recorder.hooks.begin(), recorder.hooks.end(),
                                    [&](const auto& hook) { return hook[0] == kind; }))
                << "hook " << kind;
        }
        EXPECT_EQ(watcher.hooks, recorder.hooks);
        for (const Framebuffer* other : {&watched, &watcherWatched}) {
            EXPECT_EQ(std::memcmp(plain.colorPixels().data(), other->colorPixels().data(),
                                  plain.colorPixels().size() * sizeof(vec4)),
                      0);
            for (int y = 0; y < plain.height(); ++y)
                for (int x = 0; x < plain.width(); ++x)
                    ASSERT_EQ(plain.depth(x, y), other->depth(x, y)) << x << "," << y;
        }
    }
}

// The observer sees every draw call of the plan, and a transparent draw cut into runs keeps its own
// triangle numbers: over its runs, each of its triangles once (break caught: the run's numbers, which
// start at 0 in every run, passed on unchanged).
TEST(Renderer, FrameObserverSeesTheDrawsOwnTriangleNumbers) {
    const PreparedScene prepared = mixedScene();
    FrameMemory planMemory;
    FrameStats stats;
    const std::size_t calls = planFrame(prepared, TransparencyMode::Sorted, planMemory, stats).size();

    Framebuffer framebuffer(prepared.scene.width, prepared.scene.height);
    DrawContext context(1);
    FrameMemory memory;
    FrameRecorder recorder;
    renderFrame(prepared, framebuffer, context, memory, recorder);
    ASSERT_EQ(recorder.callDraws.size(), calls);

    std::map<std::uint32_t, std::vector<int>> seen;  // per draw: how many runs showed each triangle
    std::map<std::uint32_t, int> runs;
    for (std::size_t c = 0; c < calls; ++c) {
        const std::uint32_t k = recorder.callDraws[c];
        ++runs[k];
        std::vector<int>& count = seen[k];
        count.resize(prepared.draws[k].indices.size() / 3);
        std::vector<std::uint32_t> numbers = recorder.triangles[c];
        std::sort(numbers.begin(), numbers.end());
        numbers.erase(std::unique(numbers.begin(), numbers.end()), numbers.end());
        for (const std::uint32_t t : numbers) {
            ASSERT_LT(t, count.size()) << "draw " << k;
            ++count[t];
        }
    }
    bool someDrawInSeveralRuns = false;
    for (const auto& [k, count] : seen) {
        someDrawInSeveralRuns |= runs[k] > 1;
        for (std::size_t t = 0; t < count.size(); ++t)
            EXPECT_EQ(count[t], 1) << "draw " << k << ", triangle " << t;
    }
    EXPECT_TRUE(someDrawInSeveralRuns);  // else the test shows nothing
}

// ---- Textures ------------------------------------------------------------------------------------

// A square facing the camera, textured with an image whose top half is red and bottom half blue
// (OBJ texture coordinates: v = 1 is the top row of the image file). Lit head on with Kd 1 and no
// specular, the top of the square is red and its bottom blue; a texture read upside down swaps them.
TEST(Renderer, TextureTopRowIsDrawnAtTheTop) {
    TempFolder dir;
    LinearImage texture;
    texture.width = 2;
    texture.height = 4;
    for (int y = 0; y < texture.height; ++y)
        for (int x = 0; x < texture.width; ++x)
            texture.pixels.push_back(y < 2 ? vec4(1.0f, 0.0f, 0.0f, 1.0f) : vec4(0.0f, 0.0f, 1.0f, 1.0f));
    writeImage(dir.path() / "red-over-blue.png", texture);
    dir.write("square.mtl", "newmtl t\nKa 0 0 0\nKd 1 1 1\nKs 0 0 0\nmap_Kd red-over-blue.png\n");
    const auto obj = dir.write("square.obj",
                               "mtllib square.mtl\nusemtl t\n"
                               "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                               "vn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/4/1\n");
    Scene scene = sceneForModel(obj);
    scene.width = 64;
    scene.height = 48;
    scene.camera.eye = vec3(0.0f, 0.0f, 5.0f);
    scene.camera.target = vec3(0.0f);
    scene.ambientLight = vec3(0.0f);
    LightSpec light;
    light.direction = vec3(0.0f, 0.0f, -1.0f);  // straight onto the square
    scene.lights = {light};
    const PreparedScene prepared = prepareScene(scene);
    ASSERT_EQ(prepared.draws.size(), 1u);
    ASSERT_NE(prepared.draws.front().uniforms.diffuseMap, nullptr);
    Framebuffer framebuffer(scene.width, scene.height);
    DrawContext context(1);
    renderFrame(prepared, framebuffer, context);
    const LinearImage image = toImage(framebuffer);

    // Down the middle column: red rows, then blue rows, nothing red below blue.
    int lastRed = -1, firstBlue = scene.height, reds = 0, blues = 0;
    for (int y = 0; y < scene.height; ++y) {
        const vec4 p = image.at(scene.width / 2, y);
        if (p.r > 0.5f && p.b < 0.05f) {
            lastRed = y;
            ++reds;
        } else if (p.b > 0.5f && p.r < 0.05f) {
            firstBlue = std::min(firstBlue, y);
            ++blues;
        }
    }
    EXPECT_GT(reds, 5);
    EXPECT_GT(blues, 5);
    EXPECT_LT(lastRed, firstBlue) << "red must be above blue";
}

}  // namespace
}  // namespace facet
