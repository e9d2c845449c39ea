// The 8-bit encoding of a linear value (shading/gamma.h): the codes the image writer, `facet compare`
// and the conformance tests all take.
#include "shading/gamma.h"

#include <cmath>

#include <gtest/gtest.h>

namespace facet {
namespace {

TEST(Quantize8, RoundsAsTheImageWriterDoes) {
    EXPECT_EQ(encodeChannel(0.5f, kLinearEncoding), 128);  // 127.5 rounds up
    EXPECT_EQ(encodeChannel(0.5f, kSrgbEncoding), 188);    // 1.055·0.5^(1/2.4) − 0.055 = 0.73536 → 187.5
    EXPECT_EQ(encodeChannel(0.0031308f * 0.5f, kSrgbEncoding), 5);  // the linear toe: 12.92 c · 255 = 5.16
    EXPECT_EQ(encodeChannel(-1.0f, kSrgbEncoding), 0);
    EXPECT_EQ(encodeChannel(std::nanf(""), kLinearEncoding), 0);
    EXPECT_EQ(encodeChannel(7.0f, kSrgbEncoding), 255);
    EXPECT_EQ(encodeChannel(1.0f, kLinearEncoding), 255);
}

}  // namespace
}  // namespace facet
