// The memory estimates made before the work (render/memory_estimate.h, base/memory_limit.h) against
// what the code then allocates: each estimate and its allocation share one size function, and these
// tests check that the buffers a frame really holds are the bytes estimated, so that neither can drift.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "base/memory_limit.h"
#include "io/image_io.h"
#include "pipeline/fragment_lists.h"
#include "pipeline/framebuffer.h"
#include "pipeline/thread_pool.h"
#include "render/memory_estimate.h"
#include "render/renderer.h"
#include "render/shadow_maps.h"
#include "scene/scene.h"
#include "support/bundled_models.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

using testing_support::kCube;

// Catches: Framebuffer::bytesFor leaving out a plane (the sample planes of --aa msaaN, the cell
// states) or counting one the framebuffer does not allocate.
TEST(MemoryEstimate, FramebufferBytesAreWhatItHolds) {
    for (const auto& [width, height] : {std::pair{1, 1}, {100, 37}, {640, 480}})
        for (const int samples : {1, 2, 4, 16}) {
            Framebuffer framebuffer(width, height);
            framebuffer.useSamples(samples);
            EXPECT_EQ(framebuffer.bytesHeld(), Framebuffer::bytesFor(width, height, samples))
                << width << "x" << height << " at " << samples;
        }
}

// A scene of the cube with `extra` JSON keys, loaded.
Scene cubeScene(const testing_support::TempFolder& dir, const std::string& extra) {
    const auto file = dir.path() / "scene.json";
    std::ofstream(file) << R"({"width": 48, "height": 32, )" << extra << R"("objects": [{"model": ")" << kCube
                        << R"("}]})";
    return loadScene(file);
}

// Catches: frameImageBytes missing supersampling's running sum or the finished image, or counting
// multisampling's planes differently from what the framebuffer allocates.
TEST(MemoryEstimate, FrameImageBytesAreWhatAFrameHolds) {
    const testing_support::TempFolder dir("memory-estimate-frame");
    for (const char* aa : {"none", "ssaa4", "msaa4", "msaa16"}) {
        const Scene scene = cubeScene(dir, std::string(R"("pipeline": {"antialiasing": ")") + aa + R"("}, )");
        const PreparedScene prepared = prepareScene(scene);
        Framebuffer framebuffer(scene.width, scene.height);
        DrawContext context(1);
        FrameMemory memory;
        renderFrame(prepared, framebuffer, context, memory);
        const LinearImage image = toImage(framebuffer);
        const std::uint64_t held = framebuffer.bytesHeld() + memory.sampleSum.size() * sizeof(vec4) +
                                   image.pixels.size() * sizeof(vec4);
        EXPECT_EQ(frameImageBytes(scene), held) << aa;
    }
}

// Catches: the estimate counting one face for a light drawShadowMap gives six (a point light, a wide
// spot) or the other way round, or shadowMapBytes not the depths the faces hold plus one framebuffer.
TEST(MemoryEstimate, ShadowMapBytesAreWhatTheMapsHold) {
    const testing_support::TempFolder dir("memory-estimate-shadows");
    const Scene scene = cubeScene(dir, R"("shadow_map": {"size": 64}, "lights": [
        {"type": "point", "position": [2, 2, 2], "shadows": "map"},
        {"type": "directional", "direction": [0, -1, 0], "shadows": "map"},
        {"type": "spot", "position": [0, 3, 0], "direction": [0, -1, 0], "cutoff": 30, "shadows": "map"},
        {"type": "spot", "position": [0, 3, 1], "direction": [0, -1, 0], "cutoff": 80, "shadows": "map"}], )");
    const PreparedScene prepared = prepareScene(scene);
    ASSERT_TRUE(prepared.shadows);
    ASSERT_EQ(prepared.shadows->maps.size(), 4u);
    const int expectedFaces[] = {6, 1, 1, 6};
    std::uint64_t faces = 0, depthBytes = 0;
    for (std::size_t i = 0; i < 4; ++i) {
        const ShadowMap& map = *prepared.shadows->maps[i];
        EXPECT_EQ(int(map.faces.size()), expectedFaces[i]) << "light " << i;
        EXPECT_EQ(int(map.faces.size()), shadowMapFaces(prepared.draws.front().uniforms.lights[i])) << i;
        faces += map.faces.size();
        for (const ShadowMapFace& face : map.faces)
            depthBytes += face.depth.size() * sizeof(DepthFormat::Stored);
    }
    EXPECT_EQ(shadowMapBytes(faces, 64), depthBytes + Framebuffer(64, 64).bytesHeld());
    std::uint64_t counted = 0;
    int lights = 0;
    EXPECT_EQ(shadowMapsMemory(prepared, counted, lights), frameImageBytes(scene) + shadowMapBytes(14, 64));
    EXPECT_EQ(counted, 14u);
    EXPECT_EQ(lights, 4);
}

// Catches: a fragment list growing past its budget (1,000 layers at 640x480 took 5.4 GB) or a refusal
// that is not reported (overBudget) or not forgotten by the next clear.
TEST(MemoryEstimate, FragmentListsStopAtTheirBudget) {
    FragmentLists lists;
    lists.prepare(8, 8, 8);
    const std::size_t first = FragmentLists::nextCapacity(0);
    lists.setByteBudget(FragmentLists::nodeBytes(first));
    FragmentLists::TileWriter writer = lists.writer(0, 0);
    for (std::size_t k = 0; k < first; ++k)
        ASSERT_TRUE(writer.append(int(k % 8), 0, vec4(1.0f), 0.5f, BlendMode::Over)) << k;
    EXPECT_FALSE(lists.overBudget());
    EXPECT_FALSE(writer.append(0, 0, vec4(1.0f), 0.5f, BlendMode::Over));
    EXPECT_TRUE(lists.overBudget());
    EXPECT_EQ(lists.bytesRefused(), FragmentLists::nodeBytes(FragmentLists::nextCapacity(first)));
    EXPECT_EQ(lists.size(), first);
    EXPECT_EQ(lists.dropped(), 1u);
    ThreadPool pool(1);
    lists.clear(pool);
    EXPECT_FALSE(lists.overBudget());
    EXPECT_TRUE(lists.writer(0, 0).append(0, 0, vec4(1.0f), 0.5f, BlendMode::Over));  // capacity kept
}

// Catches: sizes misread (a unit taken as decimal, 1.5G truncated to 1G, "0" or junk accepted) or a
// message that does not name the limit and where it came from.
TEST(MemoryEstimate, SizesAndTheRefusalMessage) {
    EXPECT_EQ(parseMemorySize("123", "--x"), 123u);
    EXPECT_EQ(parseMemorySize("2k", "--x"), 2048u);
    EXPECT_EQ(parseMemorySize("512M", "--x"), 512u << 20);
    EXPECT_EQ(parseMemorySize("1.5G", "--x"), 3u << 29);
    EXPECT_EQ(parseMemorySize("4GiB", "--x"), std::uint64_t{4} << 30);
    EXPECT_EQ(parseMemorySize("1tb", "--x"), std::uint64_t{1} << 40);
    for (const char* bad : {"", "G", "0", "0.1", "-1G", "1.2.3", "12X", "1GG", "1 G"})
        EXPECT_THROW(parseMemorySize(bad, "--x"), InputError) << bad;
    EXPECT_EQ(describeBytes(1000), "1000 bytes");
    EXPECT_EQ(describeBytes(1536), "1.5 KiB");
    EXPECT_EQ(describeBytes(std::uint64_t{12} << 30), "12.0 GiB");
    setMemoryLimit("1K", "--memory-limit");
    EXPECT_NO_THROW(requireMemory("the thing", 1024));
    try {
        requireMemory("the thing", 2048);
        ADD_FAILURE() << "2 KiB passed a 1 KiB limit";
    } catch (const ResourceError& e) {
        EXPECT_STREQ(e.what(),
                     "the thing needs 2.0 KiB, more than the memory limit of 1.0 KiB (--memory-limit)");
    }
    resetMemoryLimit();
    EXPECT_GT(memoryLimit().bytes, std::uint64_t{1} << 20);  // the machine's: more than a megabyte
}

// Catches: the header's estimate of a texture differing from the texels readTexture then holds (8-bit
// as 4 bytes a texel, others 16), which would let textures past the total be decoded.
TEST(MemoryEstimate, TextureBytesFromTheHeaderAreWhatTheTextureHolds) {
    const testing_support::TempFolder dir("memory-estimate-texture");
    LinearImage image;
    image.width = 37;
    image.height = 23;
    image.pixels.assign(37 * 23, glm::vec4(0.25f, 0.5f, 0.75f, 1.0f));
    writeImage(dir.path() / "t.png", image);
    const std::uint64_t estimate = textureBytesFromHeader(dir.path() / "t.png");
    const TextureRead read =
        readTexture(dir.path() / "t.png", true, TextureLimits{}, TextureLimits{}.maxTotalBytes);
    ASSERT_FALSE(read.texture.empty()) << read.problem;
    EXPECT_EQ(estimate, read.texture.bytes());
    EXPECT_EQ(estimate, 37u * 23u * 4u);
    EXPECT_EQ(textureBytesFromHeader(dir.path() / "missing.png"), 0u);
    // Two of them beyond a total of one and a half: refused from the headers.
    writeImage(dir.path() / "u.png", image);
    TextureLimits limits;
    limits.maxTotalBytes = estimate * 3 / 2;
    EXPECT_THROW(checkTextureTotal({dir.path() / "t.png", dir.path() / "u.png"}, limits), InputError);
    EXPECT_NO_THROW(checkTextureTotal({dir.path() / "t.png"}, limits));
}

}  // namespace
}  // namespace facet
