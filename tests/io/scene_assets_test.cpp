// The scene's assets loaded alone, without a renderer: each file read once, only what the scene uses,
// and assets shared by a variant of the scene that changes nothing about loading.

#include "io/scene_assets.h"

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "io/image_io.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

using testing_support::TempFolder;

// A square of two materials, both mapped with the same texture and one also with an unreadable one, plus a
// degenerate triangle (a repeated corner), drawn by two objects.
struct TwoObjects {
    TempFolder dir;
    Scene scene;

    TwoObjects() {
        LinearImage texture;
        texture.width = texture.height = 4;
        texture.pixels.assign(16, vec4(0.5f, 0.25f, 0.75f, 1.0f));
        writeImage(dir.path() / "shared.png", texture);
        dir.write("broken.png", "not an image");
        dir.write("square.mtl",
                  "newmtl a\nmap_Kd shared.png\nnewmtl b\nmap_Kd shared.png\nmap_Ke broken.png\n");
        const std::filesystem::path obj =
            dir.write("square.obj",
                      "mtllib square.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\n"
                      "usemtl a\nf 1/1 2/1 3/1\nf 1/1 1/1 2/1\nusemtl b\nf 1/1 3/1 4/1\n");
        scene = sceneForModel(obj);
        scene.objects.push_back(scene.objects.front());
    }
};

// Two objects of one model and two materials of one texture: one mesh, one texture, the unreadable
// texture warned about once, the degenerate triangle counted once. Breaks if loadModels loses its "already
// loaded" check (the second object's model read again: its warnings and its degenerate triangle
// counted twice).
TEST(SceneAssets, EachFileIsReadOnce) {
    TwoObjects two;
    const SceneAssets assets = loadSceneAssets(assetOptionsFor(two.scene));
    EXPECT_EQ(assets.models.size(), 1u);
    EXPECT_EQ(assets.degenerateSkipped, 1u);
    ASSERT_EQ(assets.textures.size(), 2u);
    const LoadedTexture* shared = assets.texture(two.dir.path() / "shared.png");
    ASSERT_NE(shared, nullptr);
    EXPECT_FALSE(shared->translucent);
    EXPECT_EQ(shared->texture->mipLevels.size(), 0u);  // the scene filters bilinearly: no mip chain
    EXPECT_EQ(assets.texture(two.dir.path() / "broken.png"), nullptr);
    ASSERT_EQ(assets.textureWarnings.size(), 1u);
    EXPECT_NE(assets.textureWarnings[0].find("broken.png"), std::string::npos);
    EXPECT_EQ(assets.textureBytes, shared->texture->bytes());
}

// What the scene's settings decide: without texture maps no texture is read at all; trilinear filtering
// builds the mip chains. Breaks if loadSceneAssets reads the textures whatever options.textured says.
TEST(SceneAssets, TheScenesSettingsDecideWhatIsRead) {
    TwoObjects two;
    Scene untextured = two.scene;
    untextured.textures.maps = TextureMaps::Off;
    const SceneAssets plain = loadSceneAssets(assetOptionsFor(untextured));
    EXPECT_TRUE(plain.textures.empty());
    EXPECT_TRUE(plain.textureWarnings.empty());

    Scene trilinear = two.scene;
    trilinear.textures.filter = TextureFilter::Trilinear;
    const SceneAssets mipmapped = loadSceneAssets(assetOptionsFor(trilinear));
    const LoadedTexture* shared = mipmapped.texture(two.dir.path() / "shared.png");
    ASSERT_NE(shared, nullptr);
    EXPECT_FALSE(shared->texture->mipLevels.empty());
}

// A variant of the scene that changes nothing about loading (the camera, the image size) shares the
// assets; one that does (the crease angle changes the computed normals) gets its own. Breaks if
// assetsFor always loads again (the variant's assets are another copy) or never does (the crease
// angle's variant drawn with the first one's normals).
TEST(SceneAssets, AVariantSharesTheAssetsUnlessItLoadsDifferently) {
    TwoObjects two;
    const std::shared_ptr<const SceneAssets> assets = loadSharedAssets(two.scene);
    Scene moved = two.scene;
    moved.camera.eye = vec3(1, 2, 3);
    moved.width = 17;
    EXPECT_EQ(assetsFor(moved, assets), assets);
    Scene creased = two.scene;
    creased.lighting.creaseAngleDegrees = 10.0f;
    const std::shared_ptr<const SceneAssets> own = assetsFor(creased, assets);
    EXPECT_NE(own, assets);
    EXPECT_EQ(own->options.obj.creaseAngleDegrees, 10.0f);
}

}  // namespace
}  // namespace facet
