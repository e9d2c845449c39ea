// Anti-aliasing by supersampling and multisampling: the standard sample positions
// (pipeline/sample_position.h), and renderFrame's passes (render/renderer.h): each pass moves the image so
// that the pixel centres land on one sample, and the passes are averaged in linear light.
#include <algorithm>
#include <cstdio>
#include <set>
#include <utility>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "pipeline/sample_position.h"
#include "render/renderer.h"
#include "shaders/shaders.h"
#include "support/temp_folder.h"
#include "support/test_shaders.h"

namespace facet {
namespace {

using testing_support::TempFolderTest;

// ---- The table -------------------------------------------------------------------------------------

constexpr int kCounts[] = {1, 2, 4, 8, 16};

// Every pattern has its count of samples, all inside the pixel's half-open square [−8, 8)/16 (the
// 16-sample pattern touches its left and top edges at −8), no two alike. Breaks if an entry is copied
// twice or mistyped outside the pixel (e.g. the 16-sample pattern's (−7, −8) as (−7, 8)).
TEST(StandardSamplePositions, InsideThePixelAndDistinct) {
    for (const int count : kCounts) {
        SCOPED_TRACE(count);
        const auto samples = standardSamplePositions(count);
        ASSERT_EQ(samples.size(), std::size_t(count));
        std::set<std::pair<int, int>> seen;
        for (const SampleOffset s : samples) {
            EXPECT_GE(s.x, -8);
            EXPECT_LT(s.x, 8);
            EXPECT_GE(s.y, -8);
            EXPECT_LT(s.y, 8);
            seen.insert({s.x, s.y});
        }
        EXPECT_EQ(seen.size(), samples.size());
    }
    EXPECT_TRUE(standardSamplePositions(3).empty());
}

// The samples' mean is the pixel's centre: exactly for 1, 2, 4 and 8 samples; for 16 within the table's
// rounding to 1/16 px, half a unit: the sums are (−8, −8), a mean of (−½, −½)/16. Breaks if an entry
// is mistyped by a unit or more (the 1–8 patterns) or by more than 8 units in sum (16).
TEST(StandardSamplePositions, MeanIsThePixelCentre) {
    for (const int count : kCounts) {
        SCOPED_TRACE(count);
        int sumX = 0, sumY = 0;
        for (const SampleOffset s : standardSamplePositions(count)) {
            sumX += s.x;
            sumY += s.y;
        }
        if (count < 16) {
            EXPECT_EQ(sumX, 0);
            EXPECT_EQ(sumY, 0);
        } else {
            EXPECT_EQ(sumX, -8);
            EXPECT_EQ(sumY, -8);
        }
    }
}

// The 4-sample pattern is the rotated grid: a quarter turn about the centre maps the pattern onto
// itself, and no two samples share a column or a row (so a vertical or horizontal edge sweeping the
// pixel covers 0, 1, 2, 3, 4 samples: five levels). Breaks with the ordered grid (±4, ±4).
TEST(StandardSamplePositions, FourSamplesAreTheRotatedGrid) {
    const auto samples = standardSamplePositions(4);
    std::set<std::pair<int, int>> pattern, turned;
    std::set<int> columns, rows;
    for (const SampleOffset s : samples) {
        pattern.insert({s.x, s.y});
        turned.insert({-s.y, s.x});
        columns.insert(s.x);
        rows.insert(s.y);
    }
    EXPECT_EQ(pattern, turned);
    EXPECT_EQ(columns.size(), 4u);
    EXPECT_EQ(rows.size(), 4u);
    EXPECT_NE(pattern.count({-2, -6}), 0u);  // Vulkan's sample 0 at (0.375, 0.125)
}

// ---- Supersampled frames ---------------------------------------------------------------------------

// A 4×4 frame whose one draw is the rectangle [x0, x1] × [y0, y1] in normalised device coordinates,
// drawn white (emission only) on black: the camera's and the draw's matrices are the identity, so
// window x = (x_ndc + 1)·2 and window y = (1 − y_ndc)·2, and pixel (1, 1) has its centre at (1.5, 1.5).
class SupersampledRectangle : public TempFolderTest {
  protected:
    static constexpr int kSide = 4;

    PreparedScene rectangle(double x0, double x1, double y0, double y1, Antialiasing aa) {
        write("quad.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
        Scene scene;
        scene.source = folder_ / "scene.json";
        scene.width = kSide;
        scene.height = kSide;
        scene.camera.eye = glm::vec3(0.0f, 0.0f, 4.0f);
        scene.camera.target = glm::vec3(0.0f);
        scene.background = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
        scene.gamma.decodeInputs = false;
        scene.pipeline.antialiasing = aa;
        ObjectSpec object;
        object.model = folder_ / "quad.obj";
        scene.objects.push_back(object);
        PreparedScene prepared = prepareScene(scene);
        prepared.camera.clipFromViewExact = glm::dmat4(1.0);
        EXPECT_EQ(prepared.draws.size(), 1u);
        PreparedDraw& d = prepared.draws[0];
        d.viewFromObjectExact = glm::dmat4(1.0);
        d.uniforms.clipFromObject = mat4(1.0f);
        d.uniforms.viewFromObject = mat4(1.0f);
        d.uniforms.material.emission = vec3(1.0f);
        d.uniforms.terms = kEmissionTerm;
        const float a = float(x0), b = float(x1), c = float(y0), e = float(y1);
        setTriangles(prepared, {{{{{a, c, 0.0f}, {0, 0, 1}, {}},
                                  {{b, c, 0.0f}, {0, 0, 1}, {}},
                                  {{b, e, 0.0f}, {0, 0, 1}, {}},
                                  {{a, e, 0.0f}, {0, 0, 1}, {}}},
                                 {0, 1, 2, 0, 2, 3}}});  // counter-clockwise: front faces
        return prepared;
    }

    // Pixel (1, 1)'s resolved red, white being 1.
    static float centrePixel(const PreparedScene& prepared, int threads = 1) {
        Framebuffer target(kSide, kSide);
        DrawContext context(threads);
        FrameMemory memory;
        renderFrame(prepared, target, context, memory);
        return target.color(1, 1).r;
    }

    // NDC of window x (or of window y, flipped) at pixel 1's centre plus `units` sixteenths of a pixel.
    static double ndcX(int units) { return (1.5 + units / 16.0) / 2.0 - 1.0; }
    static double ndcY(int units) { return 1.0 - (1.5 + units / 16.0) / 2.0; }
};

// A vertical edge through the pixel's centre, white on its left: half the samples are left of it, for
// the 4-sample pattern (x = −2, −6 of −2, 6, −6, 2) and for the 16 (x < 0: −1, −3, −5, −2, −4, −6, −8,
// −7; the sample at x = 0 lies on the edge, the rectangle's right edge, which the top-left rule leaves
// out). The resolve is exactly the half mix, 0.5 in linear light. Breaks if the passes are not
// averaged, or the image is not moved per sample (every pass alike: 0 or 1).
TEST_F(SupersampledRectangle, EdgeThroughTheCentreGivesTheHalfMix) {
    EXPECT_EQ(centrePixel(rectangle(-1.0, ndcX(0), -1.0, 1.0, Antialiasing::None)), 0.0f);  // the centre: out
    EXPECT_EQ(centrePixel(rectangle(-1.0, ndcX(0), -1.0, 1.0, Antialiasing::Ssaa4)), 0.5f);
    EXPECT_EQ(centrePixel(rectangle(-1.0, ndcX(0), -1.0, 1.0, Antialiasing::Ssaa16)), 0.5f);
}

// The sign of the shift: pixel centres land on the samples, (x, y) right and down of the centre. An edge
// 3/16 px right of the centre, white on its left, covers the 16-sample pattern's samples with x < 3:
// 1, −1, −3, −5, 2, −2, 0, −4, −6, −8, −7: 11 of 16 (x = 3 lies on the edge, left out). The pattern
// mirrored (the shift's sign wrong) would give 10 (those with x > −3). Likewise an edge 3/16 px below
// the centre, white above it: y < 3 holds for 11 samples, y > −3 for 10. Breaks if either axis of
// clipFromViewAtSample moves the image the wrong way.
TEST_F(SupersampledRectangle, PixelCentresLandOnTheSamples) {
    EXPECT_EQ(centrePixel(rectangle(-1.0, ndcX(3), -1.0, 1.0, Antialiasing::Ssaa16)), 11.0f / 16.0f);
    EXPECT_EQ(centrePixel(rectangle(-1.0, 1.0, ndcY(3), 1.0, Antialiasing::Ssaa16)), 11.0f / 16.0f);
}

// The passes are summed per pixel in sample order: the same bytes for one thread and two. Breaks if the
// accumulation races (rows summed twice or not at all).
TEST_F(SupersampledRectangle, SameBytesForAnyThreadCount) {
    Scene scene;
    write("tri.obj", "v -1 -1 0\nv 1 -0.6 0\nv -0.3 1 0\nf 1 2 3\n");
    scene.source = folder_ / "scene.json";
    scene.width = 61;
    scene.height = 47;
    scene.pipeline.antialiasing = Antialiasing::Ssaa8;
    ObjectSpec object;
    object.model = folder_ / "tri.obj";
    scene.objects.push_back(object);
    const PreparedScene prepared = prepareScene(scene);
    std::vector<vec4> images[2];
    for (int threads : {1, 2}) {
        Framebuffer target(scene.width, scene.height);
        DrawContext context(threads);
        FrameMemory memory;
        renderFrame(prepared, target, context, memory);
        images[threads - 1] = target.colorPixels();
    }
    EXPECT_EQ(images[0], images[1]);
}

// ---- Multisampled frames ---------------------------------------------------------------------------

// Multisampling tests coverage at the same standard samples: an edge through the pixel's centre covers
// half of the 4 and of the 16 samples, and the resolve is the half mix. Breaks if coverage ignores the
// sample offsets (all samples at the centre: 0), or the resolve sums without averaging (2, 8).
TEST_F(SupersampledRectangle, MultisampledEdgeThroughTheCentreGivesTheHalfMix) {
    EXPECT_EQ(centrePixel(rectangle(-1.0, ndcX(0), -1.0, 1.0, Antialiasing::Msaa4)), 0.5f);
    EXPECT_EQ(centrePixel(rectangle(-1.0, ndcX(0), -1.0, 1.0, Antialiasing::Msaa16)), 0.5f);
}

// The samples' offsets have their signs: as for supersampling, an edge 3/16 px right of (or below) the
// centre covers 11 of the 16 samples, 10 when the pattern is mirrored. Breaks if blockCoverage applies
// an offset with the wrong sign or to the wrong axis.
TEST_F(SupersampledRectangle, MultisampledCoverageAtTheStandardPositions) {
    EXPECT_EQ(centrePixel(rectangle(-1.0, ndcX(3), -1.0, 1.0, Antialiasing::Msaa16)), 11.0f / 16.0f);
    EXPECT_EQ(centrePixel(rectangle(-1.0, 1.0, ndcY(3), 1.0, Antialiasing::Msaa16)), 11.0f / 16.0f);
}

// The resolve rounds to the colour buffer's format: 3 of 4 samples white is 0.75, which 8 bits store as
// 191/255. Breaks if the resolve writes the average unrounded.
TEST_F(SupersampledRectangle, MultisampledResolveRoundsToTheColorBuffer) {
    PreparedScene prepared = rectangle(-1.0, ndcX(3), -1.0, 1.0, Antialiasing::Msaa4);
    EXPECT_EQ(centrePixel(prepared), 0.75f);  // x < 3 holds for −2, −6, 2 of −2, 6, −6, 2
    prepared.state.colorBuffer = ColorBufferFormat::Unorm8;
    EXPECT_EQ(centrePixel(prepared), 191.0f / 255.0f);
}

// The depth test runs per sample: a quad tilted in depth whose depth crosses that of a flat quad drawn
// after it exactly at pixel (1, 1)'s centre shows the tilted quad (red) at the pixel's two samples left
// of the centre and the flat one (green) at the two right of it: the resolve is half red, half green.
// Breaks if every sample takes the pixel centre's depth (one colour, or a 1:3 mix) or if a sample's
// depth is not written.
TEST_F(SupersampledRectangle, MultisampledDepthTestPerSample) {
    PreparedScene prepared = rectangle(-1.0, 1.0, -1.0, 1.0, Antialiasing::Msaa4);
    PreparedDraw tilted = prepared.draws[0];
    PreparedDraw& flat = prepared.draws[0];
    flat.uniforms.material.emission = vec3(0.0f, 1.0f, 0.0f);
    tilted.uniforms.material.emission = vec3(1.0f, 0.0f, 0.0f);
    const DrawTriangles flatTriangles{{flat.vertices.begin(), flat.vertices.end()},
                                      {flat.indices.begin(), flat.indices.end()}};
    DrawTriangles tiltedTriangles = flatTriangles;
    const float crossing = float(ndcX(0));
    for (MeshVertex& v : tiltedTriangles.vertices)
        v.position.z = 0.5f * (v.position.x - crossing);  // nearer (z < 0) left of the crossing
    prepared.draws.insert(prepared.draws.begin(), tilted);
    setTriangles(prepared, {tiltedTriangles, flatTriangles});
    Framebuffer target(kSide, kSide);
    DrawContext context(1);
    FrameMemory memory;
    renderFrame(prepared, target, context, memory);
    EXPECT_EQ(target.color(1, 1), vec4(0.5f, 0.5f, 0.0f, 1.0f));
    EXPECT_EQ(target.color(0, 1), vec4(1.0f, 0.0f, 0.0f, 1.0f));  // wholly left of the crossing
    EXPECT_EQ(target.color(3, 1), vec4(0.0f, 1.0f, 0.0f, 1.0f));  // wholly right
}

// A lit triangle on a 61×47 frame, drawn with `aa`; the frame's pixels and its counters.
class MultisampledTriangle : public TempFolderTest {
  protected:
    struct Frame {
        std::vector<vec4> pixels;
        FrameStats stats;
    };

    Frame frame(Antialiasing aa, int threads = 1, int tileSize = kDefaultTileSize) {
        Scene scene;
        write("tri.obj", "v -1 -1 0\nv 1 -0.6 0\nv -0.3 1 0\nf 1 2 3\n");
        scene.source = folder_ / "scene.json";
        scene.width = kWidth;
        scene.height = kHeight;
        scene.background = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
        scene.pipeline.antialiasing = aa;
        ObjectSpec object;
        object.model = folder_ / "tri.obj";
        scene.objects.push_back(object);
        const PreparedScene prepared = prepareScene(scene);
        Framebuffer target(scene.width, scene.height);
        DrawContext context(threads, tileSize);
        FrameMemory memory;
        Frame result;
        result.stats = renderFrame(prepared, target, context, memory);
        result.pixels = target.colorPixels();
        return result;
    }

    static constexpr int kWidth = 61, kHeight = 47;
};

// The samples are resolved row by row and tiles write disjoint pixels: the same bytes for one thread and
// two, and for 8- and 64-pixel tiles. Breaks if the resolve or the tile loop races, or a tile's sample
// planes are indexed by the tile's own coordinates.
TEST_F(MultisampledTriangle, SameBytesForAnyThreadCountAndTileSize) {
    const std::vector<vec4> one = frame(Antialiasing::Msaa8, 1).pixels;
    EXPECT_EQ(one, frame(Antialiasing::Msaa8, 2).pixels);
    EXPECT_EQ(one, frame(Antialiasing::Msaa8, 2, 8).pixels);
}

// Inside the triangle, where a pixel's every sample is covered, the pixel is shaded once at its centre
// and all its samples hold that colour: the same bytes as without anti-aliasing. Interior pixels are
// those whose eight neighbours' centres are covered too (the pixel's square then lies in the triangle).
// Breaks if the shading point is not the pixel centre (e.g. the block's barycentrics a pixel off), or
// if the resolve's sum of equal samples rounds (a sequential sum of 8: 3x, 5x, 7x are inexact).
TEST_F(MultisampledTriangle, InteriorPixelsAreTheSameBytesAsWithoutAntialiasing) {
    const std::vector<vec4> none = frame(Antialiasing::None).pixels;
    const std::vector<vec4> msaa = frame(Antialiasing::Msaa8).pixels;
    const vec4 background(0.0f, 0.0f, 0.0f, 1.0f);
    int interior = 0, same = 0;
    for (int y = 1; y + 1 < kHeight; ++y)
        for (int x = 1; x + 1 < kWidth; ++x) {
            bool covered = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    covered &= none[std::size_t((y + dy) * kWidth + x + dx)] != background;
            if (!covered) continue;
            ++interior;
            same += msaa[std::size_t(y * kWidth + x)] == none[std::size_t(y * kWidth + x)];
        }
    EXPECT_GT(interior, 300);
    EXPECT_EQ(same, interior);
}

// Multisampling shades once per pixel and triangle: the fragment shader runs about as often as without
// anti-aliasing (more by at most the silhouette's pixels, whose centre may miss while a sample is
// covered), far less than supersampling's once per sample. Breaks if each covered sample is shaded (or
// queued) on its own.
TEST_F(MultisampledTriangle, ShadesOncePerPixel) {
    const Frame none = frame(Antialiasing::None), msaa = frame(Antialiasing::Msaa4),
                ssaa = frame(Antialiasing::Ssaa4);
    std::uint64_t silhouette = 0;
    for (std::size_t k = 0; k < none.pixels.size(); ++k)
        silhouette += msaa.pixels[k] != none.pixels[k];
    const std::uint64_t shadedNone = none.stats.draw.fragmentsShaded,
                        shaded = msaa.stats.draw.fragmentsShaded;
    std::printf("fragments shaded: none %llu, msaa4 %llu, ssaa4 %llu; silhouette pixels %llu\n",
                (unsigned long long)shadedNone, (unsigned long long)shaded,
                (unsigned long long)ssaa.stats.draw.fragmentsShaded, (unsigned long long)silhouette);
    EXPECT_GT(silhouette, 20u);
    EXPECT_GE(shaded + silhouette, shadedNone);
    EXPECT_LE(shaded, shadedNone + silhouette);
    EXPECT_GT(ssaa.stats.draw.fragmentsShaded, 3 * shaded);
}

// Under ssaaN each pass samples 1/N of the pixel, so trilinear filtering takes the mip level for the
// samples' spacing: the uv derivatives times the footprint 1/√N (λ lowered by ½·log2 N), as a frame
// drawn √N times larger would. prepareScene sets the footprint from the scene's anti-aliasing: 1/√N
// for ssaaN, 1 for none and for msaaN (which shades once per pixel). A 64×64 texture whose level l ≥ 1
// holds l, seen at four texels per pixel (λ = 2): footprint 1 reads level 2, ssaa4's ½ level 1 and
// ssaa16's ¼ level 0. Breaks if the shaders' texture lookup ignores the footprint (every pass would
// take the whole pixel's level and the average of the passes filter the texture twice: a blur), or if
// prepareScene leaves it at 1 under supersampling or sets it under multisampling.
TEST_F(SupersampledRectangle, TrilinearTakesTheMipLevelOfTheSampleSpacing) {
    const Texture levels = testing::levelNumberTexture();
    const TexCoordDerivativesT<float> fourTexelsPerPixel{vec2(4.0f / 64.0f, 0.0f), vec2(0.0f, 4.0f / 64.0f)};
    const auto levelRead = [&](float footprint) {
        return detail::texels<float>(levels, vec2(0.5f), 1u, TextureFilter::Trilinear, footprint,
                                     fourTexelsPerPixel)
            .x;
    };
    EXPECT_FLOAT_EQ(levelRead(1.0f), 2.0f);
    EXPECT_FLOAT_EQ(levelRead(0.5f), 1.0f);
    EXPECT_FLOAT_EQ(levelRead(0.25f), 0.0f);
    const std::pair<Antialiasing, float> footprints[] = {{Antialiasing::None, 1.0f},
                                                         {Antialiasing::Ssaa4, 0.5f},
                                                         {Antialiasing::Ssaa16, 0.25f},
                                                         {Antialiasing::Msaa4, 1.0f}};
    for (const auto& [aa, footprint] : footprints) {
        SCOPED_TRACE(nameOf(aa));
        EXPECT_FLOAT_EQ(rectangle(-1, 1, -1, 1, aa).draws[0].uniforms.textureFootprint, footprint);
    }
}

// Exact transparency keeps its fragment lists per pixel: with multisampling the scene is refused with
// a message naming both options and what to use instead. Breaks if the check is dropped (the draw
// would then throw an internal error or draw the lists unsampled).
TEST_F(SupersampledRectangle, ExactTransparencyIsRefusedWithMultisampling) {
    write("quad.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
    Scene scene;
    scene.source = folder_ / "scene.json";
    scene.transparency.mode = TransparencyMode::Exact;
    scene.pipeline.antialiasing = Antialiasing::Msaa4;
    ObjectSpec object;
    object.model = folder_ / "quad.obj";
    scene.objects.push_back(object);
    try {
        prepareScene(scene);
        FAIL() << "exact transparency with msaa4 was accepted";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("--transparency exact"), std::string::npos) << message;
        EXPECT_NE(message.find("--aa msaa4"), std::string::npos) << message;
        EXPECT_NE(message.find("ssaa4"), std::string::npos) << message;
    }
}

// The scene file's "pipeline": {"antialiasing": ...} reaches the image: the bundled intersecting quads
// (opaque and transparent, sorted and exact; multisampled, sorted) read with "ssaa4" or "msaa4" differ from
// the same file with "none" at their edges, and only there (the passes are averaged, not summed; inside a
// surface each sample is shaded a fraction of a pixel away, which changes the colour far less). Breaks if the
// key is read but not kept in the scene, or renderFrame ignores it.
TEST_F(SupersampledRectangle, SceneFileKeyReachesTheImage) {
    const std::filesystem::path models =
        std::filesystem::path(FACET_SOURCE_DIR) / "models" / "intersecting-quads";
    const auto image = [&](const std::string& aa, const std::string& transparency) {
        std::string json = "{\"width\": 64, \"height\": 48, \"camera\": {\"eye\": [0.4, 1.7, 3.6], ";
        json += "\"target\": [0.0, 0.75, 0.0]}, \"objects\": [{\"model\": \"";
        json += (models / "backdrop.obj").string();
        json += "\"}, {\"model\": \"";
        json += (models / "quads.obj").string();
        json += "\", \"blend\": \"over\"}], \"transparency\": {\"mode\": \"" + transparency;
        json += "\"}, \"pipeline\": {\"antialiasing\": \"" + aa + "\"}}";
        const Scene scene = loadScene(write("scene.json", json));
        const PreparedScene prepared = prepareScene(scene);
        Framebuffer target(scene.width, scene.height);
        DrawContext context(2);
        FrameMemory memory;
        renderFrame(prepared, target, context, memory);
        return target.colorPixels();
    };
    for (const auto& [aa, transparency] :
         {std::pair<std::string, std::string>{"ssaa4", "sorted"}, {"ssaa4", "exact"}, {"msaa4", "sorted"}}) {
        SCOPED_TRACE(aa + " " + transparency);
        const std::vector<vec4> one = image("none", transparency), four = image(aa, transparency);
        // Differing by more than the shading's change between nearby points: edge pixels.
        std::size_t differing = 0;
        for (std::size_t k = 0; k < one.size(); ++k) {
            const vec3 d = glm::abs(vec3(four[k]) - vec3(one[k]));
            differing += std::max({d.r, d.g, d.b}) > 0.02f;
        }
        EXPECT_GT(differing, 20u);
        EXPECT_LT(differing, one.size() / 4);
    }
}

}  // namespace
}  // namespace facet
