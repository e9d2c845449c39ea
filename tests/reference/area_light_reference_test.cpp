// The rasterizer's soft shadows of an area light against the exact reference's: with the same sample
// count the two trace the same sample positions, and agree to a few 8-bit codes at nearly every pixel;
// the reference's own count (256) is what the rasterizer's 16 approximate.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "reference/reference.h"
#include "render/renderer.h"
#include "support/analytic_shadow.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

using namespace analytic_shadow;

// The sRGB code of a linear value (IEC 61966-2-1), in double.
int srgbCode(double c) {
    c = std::clamp(c, 0.0, 1.0);
    const double e = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
    return int(std::lround(255.0 * e));
}

struct Agreement {
    double withinThree = 0;  // the share of pixels whose codes differ by at most 3 in every channel
    double meanCodes = 0;    // mean |difference| in codes, over channels and pixels
};
Agreement agreement(const LinearImage& a, const LinearImage& b) {
    std::size_t within = 0;
    double sum = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        int worst = 0;
        for (int c = 0; c < 3; ++c) {
            const int d = std::abs(srgbCode(a.pixels[i][c]) - srgbCode(b.pixels[i][c]));
            worst = std::max(worst, d);
            sum += d / 3.0;
        }
        within += worst <= 3;
    }
    return {double(within) / double(a.pixels.size()), sum / double(a.pixels.size())};
}

class AreaLightReferenceTest : public ShadowTest {
  protected:
    fs::path areaScene() const {
        const fs::path path = writeScene(floatingSquare(), "\"ray\"");
        std::ifstream in(path);
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const std::string from = "{\"type\": \"point\",";
        text.replace(text.find(from), from.size(),
                     "{\"type\": \"rect\", \"width\": 1.2, \"height\": 1.2, \"direction\": [0, -1, 0],");
        return write("area.json", text);
    }
};

// Same sample count: within 3 codes at 99% of pixels (the rest on the square's outline, where the
// pixel centre's ray meets another surface). Breaks if the rasterizer and the reference place their
// samples differently, or one of them leaves out the area light's shadow or emitter cosine.
TEST_F(AreaLightReferenceTest, RasterizerAgreesWithTheReference) {
    const PreparedScene prepared = prepareScene(loadScene(areaScene()));
    const LinearImage raster = render(prepared);
    ThreadPool pool(2);
    const LinearImage same = renderReference(prepared, {.samples = 1, .areaSamples = 16}, pool);
    const Agreement a = agreement(raster, same);
    EXPECT_GT(a.withinThree, 0.99);
    // Against the reference's own 256 samples the 16 samples' penumbra differs more, but little.
    const LinearImage exact = renderReference(prepared, {.samples = 1}, pool);
    const Agreement b = agreement(raster, exact);
    EXPECT_GT(b.withinThree, 0.9);
    EXPECT_GE(b.meanCodes, a.meanCodes);
    std::printf(
        "area light, 160x120: within 3 codes of the reference %.4f (same 16 samples), %.4f "
        "(reference's 256); mean codes %.3f, %.3f\n",
        a.withinThree, b.withinThree, a.meanCodes, b.meanCodes);
    // One sample (the centre) gives a hard shadow: another image.
    const LinearImage one = renderReference(prepared, {.samples = 1, .areaSamples = 1}, pool);
    EXPECT_NE(one.pixels, same.pixels);
}

}  // namespace
}  // namespace facet
