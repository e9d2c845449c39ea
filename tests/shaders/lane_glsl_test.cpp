// GLSL's functions over lanes (shaders/lane_glsl.h): each eight-lane function gives, lane by lane, the
// same bits as its one-lane version, over a spread of inputs with negatives, both zeros, tiny and huge
// values, infinities and NaN. Each test names the break it would catch.
#include "float_bits.h"
#include "shaders/user_shader.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

namespace facet {
namespace {

using namespace glsl;  // the one-lane functions

constexpr float kInf = std::numeric_limits<float>::infinity();
const float kNaN = std::numeric_limits<float>::quiet_NaN();

// The inputs, taken eight at a time at every offset so each value meets each lane.
const std::vector<float>& spread() {
    static const std::vector<float> values = {
        -kInf,   -3e38f,   -1e30f, -1000.5f, -7.3f,    -3.75f,      -2.5f, -1.0f, -0.75f, -0.5f, -0.1f,
        -1e-30f, -0.0f,    0.0f,   1e-30f,   1e-7f,    0.1f,        0.25f, 0.5f,  0.75f,  1.0f,  1.5f,
        2.5f,    3.14159f, 7.3f,   42.0f,    1000.25f, 16777217.0f, 1e30f, 3e38f, kInf,   kNaN};
    return values;
}
float at(int i) {
    const auto& v = spread();
    return v[static_cast<std::size_t>(i) % v.size()];
}
Float8 eight(int first, int stride = 1) {
    Float8 r;
    for (int lane = 0; lane < 8; ++lane)
        r[lane] = at(first + lane * stride);
    return r;
}
using testing_shaders::bits;

// f8(x) lane by lane against f1(x[lane]), for every offset of the spread.
template <class F8, class F1>
void expectUnary(const char* name, F8 f8, F1 f1) {
    for (int first = 0; first < static_cast<int>(spread().size()); ++first) {
        const Float8 x = eight(first);
        const Float8 r = f8(x);
        for (int lane = 0; lane < 8; ++lane)
            EXPECT_EQ(bits(r[lane]), bits(f1(x[lane]))) << name << "(" << x[lane] << ") lane " << lane;
    }
}
// The same for two arguments (the second from another stride, so pairs vary).
template <class F8, class F1>
void expectBinary(const char* name, F8 f8, F1 f1) {
    for (int first = 0; first < static_cast<int>(spread().size()); ++first)
        for (int stride : {3, 5, 7}) {
            const Float8 a = eight(first), b = eight(first * 2 + 1, stride);
            const Float8 r = f8(a, b);
            for (int lane = 0; lane < 8; ++lane)
                EXPECT_EQ(bits(r[lane]), bits(f1(a[lane], b[lane])))
                    << name << "(" << a[lane] << ", " << b[lane] << ") lane " << lane;
        }
}

// Rounding per lane: a Float8 floor or ceil that rounded toward zero (truncation, cvttps) or to nearest
// would differ from the one-lane one on the negatives and the halves.
TEST(LaneGlsl, FloorCeilFractMatchOneLane) {
    expectUnary(
        "floor", [](Float8 x) { return floor(x); }, [](float x) { return floor(x); });
    expectUnary(
        "ceil", [](Float8 x) { return ceil(x); }, [](float x) { return ceil(x); });
    expectUnary(
        "fract", [](Float8 x) { return fract(x); }, [](float x) { return fract(x); });
    EXPECT_EQ(fract(-0.25f), 0.75f);  // GLSL's fract, not C's x − trunc(x)
    EXPECT_EQ(floor(-0.5f), -1.0f);
}

// mod is GLSL's x − y·floor(x/y): a C fmod in either version (sign of x, not of y) would break it.
TEST(LaneGlsl, ModMatchesOneLaneAndTakesTheSignOfY) {
    expectBinary(
        "mod", [](Float8 x, Float8 y) { return mod(x, y); }, [](float x, float y) { return mod(x, y); });
    expectUnary(
        "mod(x, 2.5)", [](Float8 x) { return mod(x, 2.5f); }, [](float x) { return mod(x, 2.5f); });
    EXPECT_EQ(mod(-1.0f, 3.0f), 2.0f);
}

// min, max and clamp compare in the same order in one lane and eight: GLM's scalar min keeps its first
// argument on a tie, so min(+0, −0) or a NaN argument would come out differently from the Float8 min.
TEST(LaneGlsl, MinMaxClampAgreeOnZerosAndNaN) {
    expectBinary(
        "min", [](Float8 a, Float8 b) { return min(a, b); }, [](float a, float b) { return min(a, b); });
    expectBinary(
        "max", [](Float8 a, Float8 b) { return max(a, b); }, [](float a, float b) { return max(a, b); });
    expectUnary(
        "clamp", [](Float8 x) { return clamp(x, -0.5f, 2.5f); },
        [](float x) { return clamp(x, -0.5f, 2.5f); });
    expectBinary(
        "clamp(x, lo, lo + 1)", [](Float8 x, Float8 lo) { return clamp(x, lo, lo + 1.0f); },
        [](float x, float lo) { return clamp(x, lo, lo + 1.0f); });
}

// mix is x·(1 − a) + y·a in both (a = 1 gives y exactly): x + (y − x)·a in one of them would not.
TEST(LaneGlsl, MixStepSmoothstepSignMatchOneLane) {
    expectBinary(
        "mix(a, b, 0.3)", [](Float8 a, Float8 b) { return mix(a, b, splat(0.3f)); },
        [](float a, float b) { return mix(a, b, 0.3f); });
    expectBinary(
        "mix(0.2, 0.9, t)", [](Float8, Float8 t) { return mix(0.2f, 0.9f, t); },
        [](float, float t) { return mix(0.2f, 0.9f, t); });
    EXPECT_EQ(mix(3.0f, 7.0f, 1.0f), 7.0f);
    expectBinary(
        "step", [](Float8 e, Float8 x) { return step(e, x); }, [](float e, float x) { return step(e, x); });
    expectUnary(
        "step(0.5, x)", [](Float8 x) { return step(0.5f, x); }, [](float x) { return step(0.5f, x); });
    EXPECT_EQ(step(1.0f, 1.0f), 1.0f);  // x = edge is 1 (GLSL: 0 only where x < edge)
    expectUnary(
        "smoothstep", [](Float8 x) { return smoothstep(-1.0f, 2.5f, x); },
        [](float x) { return smoothstep(-1.0f, 2.5f, x); });
    expectUnary(
        "sign", [](Float8 x) { return sign(x); }, [](float x) { return sign(x); });
    expectUnary(
        "abs", [](Float8 x) { return abs(x); }, [](float x) { return abs(x); });
}

// sin, cos and pow call the C library in each lane: a vector polynomial (or wide.h's fast pow) in the
// eight-lane version would differ in the last bits.
TEST(LaneGlsl, SinCosPowMatchOneLane) {
    expectUnary(
        "sin", [](Float8 x) { return sin(x); }, [](float x) { return sin(x); });
    expectUnary(
        "cos", [](Float8 x) { return cos(x); }, [](float x) { return cos(x); });
    expectBinary(
        "pow", [](Float8 x, Float8 n) { return pow(abs(x), n); },
        [](float x, float n) { return pow(abs(x), n); });
    expectUnary(
        "pow(x, lanes(5))", [](Float8 x) { return pow(x, lanes<Float8>(5.0f)); },
        [](float x) { return pow(x, lanes<float>(5.0f)); });
    expectUnary(
        "sqrt", [](Float8 x) { return sqrt(x); }, [](float x) { return sqrt(x); });
}

// ---- Vectors ------------------------------------------------------------------------------------------

vec3 lane3(const Vec3x8& v, int lane) {
    return laneOf(v, lane);
}
void expectSame(const vec3& got, const vec3& want, const char* name, int lane) {
    for (int k = 0; k < 3; ++k)
        EXPECT_EQ(bits(got[k]), bits(want[k])) << name << " component " << k << " lane " << lane;
}

// The vector functions sum and multiply in GLM's order: a dot summed (x + z) + y, a cross with its
// products swapped, or a normalize by division instead of by the reciprocal would differ by an ulp.
TEST(LaneGlsl, VectorFunctionsMatchGlm) {
    // Moderate values, so that the products are finite and the comparison says something.
    const float moderate[] = {-3.75f, -1.0f, -0.5f, -0.0f, 0.0f,  0.1f,
                              0.25f,  1.0f,  2.5f,  7.3f,  42.0f, -1e-3f};
    auto pick = [&](int i) { return moderate[static_cast<std::size_t>(i) % std::size(moderate)]; };
    for (int first = 0; first < 12; ++first) {
        Vec3x8 a, b;
        for (int lane = 0; lane < 8; ++lane) {
            a.x[lane] = pick(first + lane);
            a.y[lane] = pick(first + 3 * lane + 1);
            a.z[lane] = pick(first + 5 * lane + 2);
            b.x[lane] = pick(first + 7 * lane + 3);
            b.y[lane] = pick(2 * first + lane + 4);
            b.z[lane] = pick(3 * first + 2 * lane + 5);
        }
        const Float8 d = dot(a, b), l = length(a);
        const Vec3x8 c = cross(a, b), n = normalize(a), r = reflect(a, normalize(b));
        const Vec3x8 mn = min(a, b), mx = max(a, b), cl = clamp(a, -1.0f, 1.0f), mi = mix(a, b, 0.25f);
        const Vec3x8 fl = floor(a), fr = fract(a);
        for (int lane = 0; lane < 8; ++lane) {
            const vec3 a1 = lane3(a, lane), b1 = lane3(b, lane);
            EXPECT_EQ(bits(d[lane]), bits(dot(a1, b1))) << "dot lane " << lane;
            EXPECT_EQ(bits(l[lane]), bits(length(a1))) << "length lane " << lane;
            expectSame(lane3(c, lane), cross(a1, b1), "cross", lane);
            expectSame(lane3(n, lane), normalize(a1), "normalize", lane);
            expectSame(lane3(r, lane), reflect(a1, normalize(b1)), "reflect", lane);
            expectSame(lane3(mn, lane), min(a1, b1), "min", lane);
            expectSame(lane3(mx, lane), max(a1, b1), "max", lane);
            expectSame(lane3(cl, lane), clamp(a1, -1.0f, 1.0f), "clamp", lane);
            expectSame(lane3(mi, lane), mix(a1, b1, 0.25f), "mix", lane);
            expectSame(lane3(fl, lane), floor(a1), "floor", lane);
            expectSame(lane3(fr, lane), fract(a1), "fract", lane);
        }
    }
}

// Vec2x8: dot, length and normalize as GLM's vec2 (a dot of a Vec2x8 that summed a third, zero
// component, or a normalize through a division, would show here).
TEST(LaneGlsl, Vec2FunctionsMatchGlm) {
    for (int first = 0; first < 20; ++first) {
        Vec2x8 v{eight(first + 4), eight(first + 9, 3)};
        for (int lane = 0; lane < 8; ++lane) {  // keep it finite and nonzero
            if (!std::isfinite(v.x[lane]) || std::abs(v.x[lane]) > 1e6f) v.x[lane] = 1.5f;
            if (!std::isfinite(v.y[lane]) || std::abs(v.y[lane]) > 1e6f) v.y[lane] = -2.0f;
        }
        const Float8 l = length(v);
        const Vec2x8 n = normalize(v), f = fract(v);
        for (int lane = 0; lane < 8; ++lane) {
            const vec2 v1(v.x[lane], v.y[lane]);
            EXPECT_EQ(bits(l[lane]), bits(length(v1))) << "length lane " << lane;
            EXPECT_EQ(bits(dot(v, v)[lane]), bits(dot(v1, v1))) << "dot lane " << lane;
            const vec2 n1 = normalize(v1), f1 = fract(v1);
            EXPECT_EQ(bits(n.x[lane]), bits(n1.x)) << "normalize lane " << lane;
            EXPECT_EQ(bits(n.y[lane]), bits(n1.y)) << "normalize lane " << lane;
            EXPECT_EQ(bits(f.x[lane]), bits(f1.x)) << "fract lane " << lane;
            EXPECT_EQ(bits(f.y[lane]), bits(f1.y)) << "fract lane " << lane;
        }
    }
}

// lanes<F>(v) puts the vector in every lane (a broadcast that swapped components or left a lane unset
// would show), and select picks per lane.
TEST(LaneGlsl, BroadcastAndSelectPerLane) {
    const Vec3x8 c = lanes<Float8>(vec3(1.0f, 2.0f, 3.0f));
    const Vec4x8 q = lanes<Float8>(vec4(4.0f, 5.0f, 6.0f, 7.0f));
    const Vec2x8 p = lanes<Float8>(vec2(8.0f, 9.0f));
    EXPECT_EQ(lanes<float>(vec3(1.0f, 2.0f, 3.0f)), vec3(1.0f, 2.0f, 3.0f));
    for (int lane = 0; lane < 8; ++lane) {
        EXPECT_EQ(laneOf(c, lane), vec3(1.0f, 2.0f, 3.0f));
        EXPECT_EQ(vec4(q.x[lane], q.y[lane], q.z[lane], q.w[lane]), vec4(4.0f, 5.0f, 6.0f, 7.0f));
        EXPECT_EQ(vec2(p.x[lane], p.y[lane]), vec2(8.0f, 9.0f));
    }
    const Float8 x = {0, 1, 2, 3, 4, 5, 6, 7};
    const auto odd = fract(x * 0.5f) > 0.25f;
    const Vec4x8 s = select(odd, q, lanes<Float8>(vec4(0.0f)));
    const Vec2x8 s2 = select(either(odd, x < 1.0f), p, lanes<Float8>(vec2(0.0f)));
    for (int lane = 0; lane < 8; ++lane) {
        EXPECT_EQ(s.w[lane], lane % 2 ? 7.0f : 0.0f) << lane;
        EXPECT_EQ(s2.x[lane], lane % 2 || lane == 0 ? 8.0f : 0.0f) << lane;
    }
    EXPECT_EQ(select(both(true, negate(false)), vec4(1.0f), vec4(0.0f)), vec4(1.0f));
}

}  // namespace
}  // namespace facet
