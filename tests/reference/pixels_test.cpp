// The reference renderer's chosen pixels (renderReferencePixels): each the very colour the whole image
// gives it, and the rays' disagreement (ReferenceOptions::raySpread) where a pixel is not one colour.
#include <algorithm>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "reference/reference.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace facet {
namespace {

Scene spotScene() {
    Scene scene = loadSceneOrModel(FACET_SOURCE_DIR "/models/spot/spot_triangulated.obj");
    scene.width = 40;
    scene.height = 30;
    return scene;
}

// Pixels in no order: row ends, runs of neighbours, lone pixels, one asked twice; N = 3 (9 rays a pixel,
// so that the packets of eight straddle pixels) and N = 4. Catches a pixel traced with other jitter or
// other packets than the whole image's (the subset's rays not the row's k-th), a run's pixels written
// to the wrong places, or the spread of one pixel given to another.
TEST(ReferencePixels, EachPixelIsTheWholeImagesPixelBitForBit) {
    const PreparedScene prepared = prepareScene(spotScene());
    ThreadPool pool(2);
    const std::vector<glm::ivec2> pixels = {{39, 29}, {0, 0},   {20, 15}, {21, 15}, {22, 15}, {5, 29},
                                            {39, 0},  {19, 15}, {13, 7},  {20, 15}, {0, 14},  {39, 14}};
    for (const int n : {3, 4}) {
        SCOPED_TRACE(n);
        ReferenceOptions options;
        options.samples = n;
        std::vector<float> wholeSpread, pixelSpread;
        options.raySpread = &wholeSpread;
        const LinearImage whole = renderReference(prepared, options, pool);
        options.raySpread = &pixelSpread;
        const std::vector<vec4> colors = renderReferencePixels(prepared, options, pixels, pool);
        ASSERT_EQ(colors.size(), pixels.size());
        ASSERT_EQ(pixelSpread.size(), pixels.size());
        for (std::size_t k = 0; k < pixels.size(); ++k) {
            SCOPED_TRACE(::testing::Message() << pixels[k].x << "," << pixels[k].y);
            const vec4 expected = whole.at(pixels[k].x, pixels[k].y);
            for (int c = 0; c < 4; ++c)
                EXPECT_EQ(colors[k][c], expected[c]);  // bit for bit
            EXPECT_EQ(pixelSpread[k], wholeSpread[static_cast<std::size_t>(pixels[k].y) * 40 + pixels[k].x]);
        }
    }
}

// The spread is the disagreement of a pixel's own rays: none in the background's corner, some along
// the model's outline (a pixel there sees the cow and the background). Catches a spread that is not
// filled, or filled from the mean rather than from the rays.
TEST(ReferencePixels, RaysDisagreeOnlyWhereThePixelIsNotOneColour) {
    const PreparedScene prepared = prepareScene(spotScene());
    ThreadPool pool(1);
    ReferenceOptions options;
    options.samples = 4;
    std::vector<float> spread;
    options.raySpread = &spread;
    const LinearImage image = renderReference(prepared, options, pool);
    ASSERT_EQ(spread.size(), image.pixels.size());
    EXPECT_EQ(spread[0], 0.0f);  // the top-left corner: background only
    // Along a row through the middle, the first pixel that is not the background's colour is partly so.
    const int y = 15;
    const vec4 background = image.at(0, y);
    int x = 0;
    while (x < 40 && image.at(x, y) == background)
        ++x;
    ASSERT_LT(x, 40);
    EXPECT_GT(spread[static_cast<std::size_t>(y) * 40 + x], 0.0f);
}

// Catches a pixel outside the image read or written out of bounds instead of refused.
TEST(ReferencePixels, APixelOutsideTheImageIsRefused) {
    const PreparedScene prepared = prepareScene(spotScene());
    ThreadPool pool(1);
    const std::vector<glm::ivec2> outside = {{40, 0}};
    EXPECT_THROW(renderReferencePixels(prepared, ReferenceOptions{}, outside, pool), std::invalid_argument);
}

}  // namespace
}  // namespace facet
