// Image comparison (oracle/image_compare.h), on made-up images: compareImages() tells a like-for-like
// pair of renderings from a different silhouette, a flipped image or different shading; comparePixels()
// counts 8-bit code differences and tells silhouette pixels from interior ones.
#include "oracle/image_compare.h"

#include <stdexcept>

#include <gtest/gtest.h>

namespace facet {
namespace {

const vec4 kBackground(0.1f, 0.1f, 0.1f, 1.0f);

// A disc of radius r centred at (cx, cy), shaded from left to right, on the background.
LinearImage disc(int width, int height, float cx, float cy, float r) {
    LinearImage image;
    image.width = width;
    image.height = height;
    image.pixels.assign(static_cast<std::size_t>(width) * height, kBackground);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float dx = x + 0.5f - cx, dy = y + 0.5f - cy;
            if (dx * dx + dy * dy <= r * r) image.at(x, y) = vec4(0.3f + 0.5f * x / width, 0.4f, 0.5f, 1.0f);
        }
    return image;
}

TEST(CompareImages, IdenticalImagesAgree) {
    const LinearImage a = disc(64, 48, 30.0f, 20.0f, 15.0f);
    const ImageAgreement agreement = compareImages(a, a, kBackground);
    EXPECT_TRUE(agreement.agrees());
    EXPECT_EQ(agreement.coverageAgreement, 1.0);
    EXPECT_EQ(agreement.colorWithinTolerance, 1.0);
    EXPECT_EQ(agreement.meanColorDifference, 0.0);
    EXPECT_EQ(agreement.foregroundA, agreement.foregroundB);
    EXPECT_GT(agreement.foregroundA, 600u);
}

TEST(CompareImages, EdgePixelsAloneDoNotMatter) {
    // Radius 15 vs 15.2: only a ring of edge pixels differs.
    const ImageAgreement agreement =
        compareImages(disc(64, 48, 30.0f, 20.0f, 15.0f), disc(64, 48, 30.0f, 20.0f, 15.2f), kBackground);
    EXPECT_TRUE(agreement.agrees());
    EXPECT_LT(agreement.coverageAgreement, 1.0);
}

TEST(CompareImages, AnotherSilhouetteDisagrees) {
    const ImageAgreement agreement =
        compareImages(disc(64, 48, 30.0f, 20.0f, 15.0f), disc(64, 48, 36.0f, 20.0f, 15.0f), kBackground);
    EXPECT_FALSE(agreement.agrees());
    EXPECT_LT(agreement.coverageAgreement, 0.98);
}

TEST(CompareImages, AnUpsideDownImageDisagrees) {
    // GL's row 0 is the bottom, Facet's the top: forgetting the flip moves an off-centre shape.
    const LinearImage a = disc(64, 48, 30.0f, 14.0f, 10.0f);
    LinearImage flipped = a;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            flipped.at(x, y) = a.at(x, a.height - 1 - y);
    EXPECT_FALSE(compareImages(a, flipped, kBackground).agrees());
}

TEST(CompareImages, OtherShadingDisagrees) {
    const LinearImage a = disc(64, 48, 30.0f, 20.0f, 15.0f);
    LinearImage brighter = a;
    for (vec4& p : brighter.pixels)
        if (p != kBackground) p += vec4(0.1f, 0.0f, 0.0f, 0.0f);
    const ImageAgreement agreement = compareImages(a, brighter, kBackground);
    EXPECT_EQ(agreement.coverageAgreement, 1.0);
    EXPECT_FALSE(agreement.agrees());
}

TEST(CompareImages, EmptyImagesDoNotAgree) {
    // Nothing drawn on either side proves nothing.
    const LinearImage empty = disc(16, 16, 0.0f, 0.0f, 0.0f);
    EXPECT_FALSE(compareImages(empty, empty, kBackground).agrees());
}

TEST(CompareImages, SizesMustMatch) {
    EXPECT_THROW(compareImages(disc(16, 16, 8, 8, 4), disc(16, 15, 8, 8, 4), kBackground),
                 std::invalid_argument);
}

// ---- comparePixels: 8-bit code steps ---------------------------------------------------------------------

TEST(ComparePixels, CountsCodeStepsAndSilhouettePixels) {
    const LinearImage a = disc(64, 48, 30.0f, 20.0f, 15.0f);
    const PixelDifference same = comparePixels(a, a, kSrgbEncoding, kBackground);
    EXPECT_EQ(same.pixels, 64u * 48u);
    EXPECT_EQ(same.differing, 0u);
    EXPECT_EQ(same.maxDifference, 0);
    EXPECT_EQ(same.within1, 1.0);
    std::size_t discPixels = 0;
    for (const vec4& p : a.pixels)
        discPixels += p != kBackground;
    EXPECT_EQ(same.coveredA, discPixels);
    EXPECT_EQ(same.coveredB, discPixels);

    // One interior pixel 2 codes brighter in red (linear encoding: 2/255), one silhouette pixel
    // (background in a, drawn in b) far off.
    LinearImage b = a;
    b.at(30, 20).r = a.at(30, 20).r + 2.0f / 255.0f;
    ASSERT_EQ(a.at(30, 4), kBackground);  // just above the disc (centre 20, radius 15)
    b.at(30, 4) = vec4(0.9f, 0.4f, 0.5f, 1.0f);
    const PixelDifference d = comparePixels(a, b, kLinearEncoding, kBackground);
    EXPECT_EQ(d.differing, 2u);
    EXPECT_EQ(d.differingAtEdges, 1u);
    EXPECT_EQ(d.maxInteriorDifference, 2);
    EXPECT_GT(d.maxDifference, 100);
    EXPECT_DOUBLE_EQ(d.within1, 1.0 - 2.0 / d.pixels);
    EXPECT_DOUBLE_EQ(d.within2, 1.0 - 1.0 / d.pixels);
    EXPECT_EQ(d.coveredA, discPixels);
    EXPECT_EQ(d.coveredB, discPixels + 1);  // the silhouette pixel b drew

    // Without a background colour there is no silhouette.
    const PixelDifference plain = comparePixels(a, b, kLinearEncoding);
    EXPECT_EQ(plain.coveredA + plain.coveredB, 0u);
    EXPECT_EQ(plain.differingAtEdges, 0u);
    EXPECT_EQ(plain.maxInteriorDifference, 0);
    EXPECT_THROW(comparePixels(a, disc(64, 47, 30, 20, 15), kSrgbEncoding), std::invalid_argument);
}

}  // namespace
}  // namespace facet
