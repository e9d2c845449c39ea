// Variants of a frame made by copying it: they share the assets and the triangles, keep every field they
// do not change, get their own shadows when they move objects, and a FrameMemory never mixes up the
// transparent runs of two frames' triangles.

#include <filesystem>
#include <vector>

#include <gtest/gtest.h>

#include "render/renderer.h"
#include "support/interleaved_quads.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

using testing_support::headOnScene;
using testing_support::interleavedQuadsScene;
using testing_support::TempFolder;
using testing_support::writeInterleavedQuads;

// A small square in front of a wall, lit from the side so that its ray-cast shadow falls on the wall
// beside it, and a textured corner so that the frame draws with the assets' texture.
Scene shadowedScene(TempFolder& dir) {
    LinearImage texture;
    texture.width = texture.height = 2;
    texture.pixels.assign(4, vec4(0.2f, 0.6f, 0.4f, 1.0f));
    writeImage(dir.path() / "wall.png", texture);
    dir.write("scene.mtl", "newmtl wall\nKd 1 1 1\nmap_Kd wall.png\nnewmtl square\nKd 0.8 0.2 0.2\n");
    const std::filesystem::path obj = dir.write(
        "scene.obj",
        "mtllib scene.mtl\nv -3 -3 -2\nv 3 -3 -2\nv 3 3 -2\nv -3 3 -2\nv -0.5 -0.5 0\nv 0.5 -0.5 0\n"
        "v 0.5 0.5 0\nv -0.5 0.5 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
        "usemtl wall\nf 1/1/1 2/2/1 3/3/1 4/4/1\nusemtl square\nf 5//1 6//1 7//1 8//1\n");
    Scene scene = headOnScene(obj);
    scene.lights[0].direction = vec3(0.6f, 0.0f, -1.0f);
    scene.lights[0].shadows = ShadowMethod::Ray;
    return scene;
}

std::vector<vec4> pixels(const PreparedScene& frame) {
    Framebuffer target(frame.scene.width, frame.scene.height);
    DrawContext context(1);
    FrameMemory memory;
    renderFrame(frame, target, context, memory);
    return toImage(target).pixels;
}

// A copy is a whole frame: it draws the same bytes, shadows included, and shares the assets, the
// triangles and the shadows rather than copying them. Turned by 0 degrees (its shadows built again from
// its own fields) it still draws the same bytes. Breaks if `turned` copies fields one by one and
// misses one the shadows need (shadowMethods left at None: the variant has no shadow).
TEST(FrameVariants, ACopyKeepsEveryFieldAndSharesTheAssets) {
    TempFolder dir;
    const PreparedScene frame = prepareScene(shadowedScene(dir));
    ASSERT_NE(frame.shadows, nullptr);
    ASSERT_NE(frame.draws[0].uniforms.diffuseMap, nullptr);
    const std::vector<vec4> image = pixels(frame);

    const PreparedScene copy = frame;
    EXPECT_EQ(copy.assets, frame.assets);
    EXPECT_EQ(copy.geometry, frame.geometry);
    EXPECT_EQ(copy.shadows, frame.shadows);
    EXPECT_EQ(copy.draws[0].vertices.data(), frame.draws[0].vertices.data());
    EXPECT_EQ(copy.draws[0].uniforms.diffuseMap, frame.draws[0].uniforms.diffuseMap);
    EXPECT_EQ(pixels(copy), image);

    const PreparedScene still = turned(frame, 0.0f);
    EXPECT_EQ(still.shadowMethods, frame.shadowMethods);
    EXPECT_EQ(still.sceneExtent, frame.sceneExtent);
    EXPECT_EQ(still.shadowMapOptions.size, frame.shadowMapOptions.size);
    EXPECT_EQ(pixels(still), image);
}

// Turning a copy moves its objects and their shadows and leaves the original as it was: the copy builds
// its own shadows, which its draws point to, and the original still draws its first image. Breaks if
// setTurntable does not build the shadows again (the turned copy would share, and draw, the original's).
TEST(FrameVariants, ATurnedVariantGetsItsOwnShadows) {
    TempFolder dir;
    const PreparedScene frame = prepareScene(shadowedScene(dir));
    const std::vector<vec4> image = pixels(frame);
    const PreparedScene variant = turned(frame, 30.0f);
    ASSERT_NE(variant.shadows, nullptr);
    EXPECT_NE(variant.shadows, frame.shadows);
    for (const PreparedDraw& d : variant.draws)
        EXPECT_EQ(d.uniforms.shadows, &variant.shadows->forShaders);
    for (const PreparedDraw& d : frame.draws)
        EXPECT_EQ(d.uniforms.shadows, &frame.shadows->forShaders);
    EXPECT_NE(pixels(variant), image);
    EXPECT_EQ(pixels(frame), image);
    EXPECT_EQ(variant.assets, frame.assets);
    EXPECT_EQ(variant.geometry, frame.geometry);
}

// Variants of the scene's settings made from loaded assets read no file again: with the model and the
// texture deleted, a variant with another camera and image size is still made, from the same assets.
// Breaks if prepareScene(scene, assets) loads the files again although the assets serve the scene.
TEST(FrameVariants, AssetsAreLoadedOnceForEveryVariant) {
    TempFolder dir;
    const Scene scene = shadowedScene(dir);
    const PreparedScene frame = prepareScene(scene);
    std::filesystem::remove(dir.path() / "scene.obj");
    std::filesystem::remove(dir.path() / "wall.png");
    Scene other = scene;
    other.camera.eye = vec3(1.0f, 1.0f, 6.0f);
    other.width = 40;
    const PreparedScene variant = prepareScene(other, frame.assets);
    EXPECT_EQ(variant.assets, frame.assets);
    EXPECT_EQ(variant.draws[0].uniforms.diffuseMap, frame.draws[0].uniforms.diffuseMap);
    EXPECT_EQ(variant.state.viewport.width, 40);
}

// Assets loaded for another scene are refused rather than drawn with the wrong normals or textures.
// Breaks if prepareFrame does not compare the assets' options with the scene's.
TEST(FrameVariants, AssetsOfAnotherSceneAreRefused) {
    TempFolder dir;
    const Scene scene = shadowedScene(dir);
    const std::shared_ptr<const SceneAssets> assets = loadSharedAssets(scene);
    Scene untextured = scene;
    untextured.textures.maps = TextureMaps::Off;
    EXPECT_THROW(prepareFrame(untextured, assets), std::invalid_argument);
}

// A FrameMemory's runs are cut for one frame's triangles. A variant given other triangles
// (setTriangles) with the same order as before (only the normals changed) is planned with its own
// vertices, not the runs' compact copies of the first frame's. Breaks if planFrame reuses the runs
// whenever the sort moved nothing, whatever triangles they were cut for.
TEST(FrameVariants, RunsAreNotReusedForOtherTriangles) {
    TempFolder dir;
    const PreparedScene frame = prepareScene(interleavedQuadsScene(writeInterleavedQuads(dir, 12)));
    FrameMemory memory;
    FrameStats first, again;
    planFrame(frame, TransparencyMode::Sorted, memory, first);
    planFrame(frame, TransparencyMode::Sorted, memory, again);
    ASSERT_TRUE(again.runsReused);  // the same triangles, a still camera

    PreparedScene variant = frame;
    std::vector<DrawTriangles> triangles;
    for (const PreparedDraw& d : variant.draws) {
        DrawTriangles& t = triangles.emplace_back();
        t.vertices.assign(d.vertices.begin(), d.vertices.end());
        t.indices.assign(d.indices.begin(), d.indices.end());
        for (MeshVertex& v : t.vertices)
            v.normal = -v.normal;
    }
    setTriangles(variant, std::move(triangles));
    FrameStats third;
    const std::vector<PlannedDraw> plan = planFrame(variant, TransparencyMode::Sorted, memory, third);
    EXPECT_FALSE(third.runsReused);
    for (const PlannedDraw& call : plan)
        for (const MeshVertex& v : call.vertices)
            EXPECT_LT(v.normal.z, 0.0f);  // the quads face the camera (+z): flipped, away from it
}

}  // namespace
}  // namespace facet
