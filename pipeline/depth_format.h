// The depth buffer's format and convention in one place: what a pixel stores, what clearing writes,
// which way is nearer, how the viewport maps NDC z to window depth, and how a fragment's window depth
// is stored and compared. The framebuffer, the viewport transform, the back end's depth test and the
// fragment lists' sort order all go through DepthFormat, so a 16- or 24-bit unorm buffer (store()
// rounds z·(2^bits − 1), compares integers) or reversed Z (near at 1, Greater, cleared to 0) is a
// local change here.
#pragma once

#include <algorithm>
#include <cstring>

#include "depth_test.h"
#include "state.h"
#include "wide.h"

namespace facet {

// 32-bit float window depth in [0, 1], smaller is nearer (OpenGL's default convention).
struct DepthFormat {
    using Stored = float;    // one pixel of the depth buffer
    using Stored8 = Float8;  // eight neighbouring pixels of one row, for the eight-lane test

    // Smaller stored values are nearer the eye (the far plane is the largest depth).
    static constexpr bool kLessIsNearer = true;
    // What clearing writes by default: the far plane, which every fragment in range passes under Less.
    static constexpr Stored kClear = 1.0f;
    // r of a depth offset (DepthOffset::units): the smallest depth difference the buffer resolves
    // everywhere in [0, 1], the float spacing just below 1. (OpenGL takes 2^(e − 23) for a float
    // buffer, e the exponent of the triangle's largest depth; one r for all keeps a unit the same
    // distance across an orthographic shadow map, whose depth is linear.)
    static constexpr float kResolution = 0x1p-24f;

    // The viewport's depth mapping (glDepthRange): z_w = n + (z_ndc + 1)/2 · (f − n), with
    // (z_ndc + 1)/2 clamped to [0, 1] first, as OpenGL clamps window depth.
    static float windowDepth(float ndcZ, float minDepth, float maxDepth) {
        const float depth01 = std::clamp((ndcZ + 1.0f) * 0.5f, 0.0f, 1.0f);
        return minDepth + depth01 * (maxDepth - minDepth);
    }

    // A fragment's window depth as the buffer stores it (float: itself).
    static Stored store(float windowDepth) { return windowDepth; }
    static Stored8 store(Float8 windowDepth) { return windowDepth; }

    // The stored depths of eight neighbouring pixels of a row, row[0..7].
    static Stored8 load8(const Stored* row) {
        Stored8 stored;
        std::memcpy(&stored, row, sizeof stored);
        return stored;
    }

    // The depth test on the stored representation (glDepthFunc): a bool for one fragment, a lane mask
    // (all bits set where a lane passes) for eight.
    static bool passes(CompareOp op, float fragmentDepth, Stored stored) {
        return depthTestPasses(op, store(fragmentDepth), stored);
    }
    static Int8 passes(CompareOp op, Float8 fragmentDepth, Stored8 stored) {
        return depthTestPasses(op, store(fragmentDepth), stored);
    }
};

}  // namespace facet
