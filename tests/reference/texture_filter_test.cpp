// Texture filtering against the truth: the reference renderer with 8×8 rays a pixel integrates each
// pixel's footprint of the checkerboard floor (support/checker_scene.h); in the far half of the image,
// where each pixel covers many texels, trilinear filtering comes clearly closer to it than bilinear,
// and bilinear than nearest (whose moiré is the worst).
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "reference/reference.h"
#include "render/renderer.h"
#include "support/checker_scene.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

using testing_support::TempFolderTest;

class TextureFilterTest : public TempFolderTest {};

LinearImage renderWith(Scene scene, TextureFilter filter) {
    scene.textures.filter = filter;
    const PreparedScene prepared = prepareScene(scene);
    Framebuffer framebuffer(scene.width, scene.height);
    DrawContext context(1);
    renderFrame(prepared, framebuffer, context);
    return toImage(framebuffer);
}

// Mean |difference| of the RGB channels (linear) over the image's top half: the floor's far half and
// the background above it (the same in every image).
double farHalfError(const LinearImage& image, const LinearImage& truth) {
    double sum = 0.0;
    int count = 0;
    for (int y = 0; y < image.height / 2; ++y)
        for (int x = 0; x < image.width; ++x) {
            for (int c = 0; c < 3; ++c)
                sum += std::abs(static_cast<double>(image.at(x, y)[c]) - truth.at(x, y)[c]);
            ++count;
        }
    return sum / (3.0 * count);
}

// Measured: nearest 0.0235, bilinear 0.0191, trilinear 0.0036; the margins (0.4 and 0.9) leave room.
// Breaks caught: trilinear sampling level 0 only (its error becomes bilinear's), λ computed from the
// derivatives of the wrong varyings, or the mip chain averaged in the codes (sRGB) instead of linear
// light (the far floor too dark: the mean of black and white codes is 0.21, not ½).
TEST_F(TextureFilterTest, TrilinearIsClosestToTheReferenceOnAGrazingCheckerboard) {
    const Scene scene = loadScene(testing_support::writeCheckerScene(folder_));
    const PreparedScene prepared = prepareScene(scene);
    ThreadPool pool(2);
    const LinearImage truth = renderReference(prepared, {.samples = 8}, pool);
    const double nearest = farHalfError(renderWith(scene, TextureFilter::Nearest), truth);
    const double bilinear = farHalfError(renderWith(scene, TextureFilter::Bilinear), truth);
    const double trilinear = farHalfError(renderWith(scene, TextureFilter::Trilinear), truth);
    std::printf("far-half mean error: nearest %.4f, bilinear %.4f, trilinear %.4f\n", nearest, bilinear,
                trilinear);
    EXPECT_LT(trilinear, 0.4 * bilinear);
    EXPECT_LT(bilinear, 0.9 * nearest);
}

}  // namespace
}  // namespace facet
