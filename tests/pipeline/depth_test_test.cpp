#include "depth_test.h"

#include <gtest/gtest.h>

#include "../support/test_shaders.h"

namespace facet {
namespace {

TEST(DepthTest, CompareFunctionsOnHandValues) {
    struct Case {
        CompareOp op;
        bool less, equal, greater;  // verdict for fragment 0.3, 0.5, 0.7 against stored 0.5
    };
    for (const Case& c :
         {Case{CompareOp::Never, false, false, false}, Case{CompareOp::Less, true, false, false},
          Case{CompareOp::Equal, false, true, false}, Case{CompareOp::LessEqual, true, true, false},
          Case{CompareOp::Greater, false, false, true}, Case{CompareOp::NotEqual, true, false, true},
          Case{CompareOp::GreaterEqual, false, true, true}, Case{CompareOp::Always, true, true, true}}) {
        EXPECT_EQ(depthTestPasses(c.op, 0.3f, 0.5f), c.less) << c.op;
        EXPECT_EQ(depthTestPasses(c.op, 0.5f, 0.5f), c.equal) << c.op;
        EXPECT_EQ(depthTestPasses(c.op, 0.7f, 0.5f), c.greater) << c.op;
    }
}

// The eight-lane test agrees with the one-lane test for every compare function.
TEST(DepthTest, EightLanesAgreeWithOne) {
    const Float8 fragment = {0.1f, 0.5f, 0.9f, 0.5f, 0.0f, 1.0f, 0.25f, 0.75f};
    const Float8 stored = {0.5f, 0.5f, 0.5f, 0.4f, 0.0f, 0.99f, 0.3f, 0.7f};
    for (CompareOp op :
         {CompareOp::Never, CompareOp::Less, CompareOp::Equal, CompareOp::LessEqual, CompareOp::Greater,
          CompareOp::NotEqual, CompareOp::GreaterEqual, CompareOp::Always}) {
        const unsigned lanes = signMask(depthTestPasses(op, fragment, stored));
        for (int i = 0; i < 8; ++i)
            EXPECT_EQ(((lanes >> i) & 1u) != 0, depthTestPasses(op, fragment[i], stored[i]))
                << op << " lane " << i;
    }
}

using testing::ClipSpaceColorShader;

// Two full-screen quads, red at NDC z = −0.5 (nearer) and green at z = 0.5, drawn in both orders: for each
// compare function the surviving colour is the one the function selects, whatever the order.
TEST(DepthTest, KeepsTheFragmentTheCompareFunctionSelects) {
    auto quad = [](float z, vec4 color) {
        std::vector<ClipSpaceColorShader::Attributes> v;
        for (vec2 p : {vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1)})
            v.push_back({vec4(p, z, 1.0f), color});
        return v;
    };
    const vec4 red(1, 0, 0, 1), green(0, 1, 0, 1), clear(0, 0, 1, 1);
    struct Case {
        CompareOp op;
        float clearDepth;
        vec4 nearFirst, farFirst;  // expected colour when the near quad is drawn first / the far one
    };
    for (const Case& c :
         {Case{CompareOp::Less, 1.0f, red, red}, Case{CompareOp::LessEqual, 1.0f, red, red},
          Case{CompareOp::Greater, 0.0f, green, green}, Case{CompareOp::GreaterEqual, 0.0f, green, green},
          Case{CompareOp::Always, 1.0f, green, red}, Case{CompareOp::Never, 1.0f, clear, clear},
          Case{CompareOp::NotEqual, 1.0f, green, red}, Case{CompareOp::Equal, 1.0f, clear, clear}}) {
        for (bool nearFirst : {true, false}) {
            Framebuffer fb(8, 8);
            fb.clearColor(clear);
            fb.clearDepth(c.clearDepth);
            DrawState state = testing::stateFor(fb);
            state.depth.compare = c.op;
            const auto nearQuad = quad(-0.5f, red), farQuad = quad(0.5f, green);
            testing::drawTriangles<ClipSpaceColorShader>(state, nearFirst ? nearQuad : farQuad, fb);
            testing::drawTriangles<ClipSpaceColorShader>(state, nearFirst ? farQuad : nearQuad, fb);
            EXPECT_EQ(fb.color(3, 4), nearFirst ? c.nearFirst : c.farFirst)
                << c.op << (nearFirst ? " near first" : " far first");
        }
    }
}

TEST(DepthTest, WritesCanBeTurnedOff) {
    Framebuffer fb(4, 4);
    fb.clearDepth(1.0f);
    DrawState state = testing::stateFor(fb);
    state.depth.writeEnabled = false;
    std::vector<ClipSpaceColorShader::Attributes> v = {
        {{-1, -1, 0, 1}, vec4(1)}, {{3, -1, 0, 1}, vec4(1)}, {{-1, 3, 0, 1}, vec4(1)}};
    testing::drawTriangles<ClipSpaceColorShader>(state, v, fb);
    EXPECT_EQ(fb.color(1, 1), vec4(1));
    EXPECT_EQ(fb.depth(1, 1), 1.0f);
    state.depth.writeEnabled = true;
    testing::drawTriangles<ClipSpaceColorShader>(state, v, fb);
    EXPECT_FLOAT_EQ(fb.depth(1, 1), 0.5f);  // NDC z = 0 → window depth ½
}

}  // namespace
}  // namespace facet
