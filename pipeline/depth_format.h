// The depth buffer's formats and conventions in one place: what a pixel stores, what clearing writes,
// which way is nearer, how the viewport maps NDC z to window depth, and how a fragment's window depth
// is stored and compared. The framebuffer, the viewport transform, the back end's depth test and the
// fragment lists' sort order all go through DepthFormatOf<format>, chosen once per draw
// (DrawState::depth.format; the back end's drawTileOfChunks switches on it), so the default Float path is
// the code it was before the other formats existed.
//
// Storage: every format keeps the framebuffer's 32-bit float buffer. The unorm formats store their
// integer codes round(z_w·(2^N − 1)) in it, exact as floats (every integer up to 2^24 is a float), so
// comparing stored floats compares the codes as hardware compares integers. Reversed Z stores the
// window depth itself, near 1 and far 0.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>

#include "clip.h"
#include "depth_test.h"
#include "state.h"
#include "wide.h"

namespace facet {

// A window depth as a unorm buffer of largest code `unormMax` = 2^N − 1 stores it:
// round(clamp(z_w, 0, 1)·(2^N − 1)) (OpenGL's float → unorm conversion, 4.6 §2.3.5.2), the product
// rounded to float first and then to the nearest integer, ties to even, in both the one-lane and the
// eight-lane form (so they agree bit for bit).
inline float unormDepthCode(float windowDepth, float unormMax) {
    return std::nearbyint(std::clamp(windowDepth, 0.0f, 1.0f) * unormMax);
}
inline Float8 unormDepthCode(Float8 windowDepth, float unormMax) {
    const Float8 scaled = min(max(windowDepth, 0.0f), 1.0f) * unormMax;
    // Round to nearest even by adding and removing 2^23, exact for 0 ≤ x < 2^23 (the float spacing there
    // reaches 1); from 2^23 on every float is already an integer.
    constexpr float kRound = 0x1p23f;
    return select(scaled < kRound, (scaled + kRound) - kRound, scaled);
}

template <DepthBufferFormat kFormat>
struct DepthFormatOf {
    using Stored = float;    // one pixel of the depth buffer
    using Stored8 = Float8;  // eight neighbouring pixels of one row, for the eight-lane test

    static constexpr DepthBufferFormat kFormatValue = kFormat;
    // N of a unorm format, 0 for the float ones.
    static constexpr int kUnormBits = kFormat == DepthBufferFormat::Unorm16   ? 16
                                      : kFormat == DepthBufferFormat::Unorm24 ? 24
                                                                              : 0;
    // 2^N − 1: the code of window depth 1.
    static constexpr float kUnormMax = kUnormBits ? float((1u << kUnormBits) - 1u) : 1.0f;

    // Smaller stored values are nearer the eye (the far plane is the largest depth); false for reversed Z.
    static constexpr bool kLessIsNearer = kFormat != DepthBufferFormat::ReversedFloat;
    // What clearing writes by default: the far plane, which every fragment in range passes under Less
    // (Greater for reversed Z): 1, the code 2^N − 1, or 0.
    static constexpr Stored kClear = kLessIsNearer ? kUnormMax : 0.0f;
    // r of a depth offset (DepthOffset::units): the smallest window-depth difference the buffer
    // resolves everywhere in [0, 1]. Unorm: one code, 1/(2^N − 1) (OpenGL 4.6 §14.6.5). Float, either
    // way round: the float spacing just below 1, 2^-24. (OpenGL takes 2^(e − 23) for a float buffer, e
    // the exponent of the triangle's largest depth; one r for all keeps a unit the same distance across
    // an orthographic shadow map, whose depth is linear.)
    static constexpr float kResolution = kUnormBits ? 1.0f / kUnormMax : 0x1p-24f;

    // The viewport's depth mapping (glDepthRange): z_w = n + d·(f − n), d clamped to [0, 1] as OpenGL
    // clamps window depth. d = (z_ndc + 1)/2 under OpenGL's −1..1 clip depth; d = z_ndc under reversed
    // Z's 0..1 (glClipControl GL_ZERO_TO_ONE), which spares the halving that would round away the
    // float precision reversed Z gains near 0.
    static float windowDepth(float ndcZ, float minDepth, float maxDepth) {
        float depth01;
        if constexpr (kLessIsNearer)
            depth01 = std::clamp((ndcZ + 1.0f) * 0.5f, 0.0f, 1.0f);
        else
            depth01 = std::clamp(ndcZ, 0.0f, 1.0f);
        return minDepth + depth01 * (maxDepth - minDepth);
    }

    // A fragment's window depth as the buffer stores it: float, itself; unorm, its code (unormDepthCode).
    static Stored store(float windowDepth) {
        if constexpr (kUnormBits)
            return unormDepthCode(windowDepth, kUnormMax);
        else
            return windowDepth;
    }
    static Stored8 store(Float8 windowDepth) {
        if constexpr (kUnormBits)
            return unormDepthCode(windowDepth, kUnormMax);
        else
            return windowDepth;
    }

    // The window depth a stored value stands for (for printing and the step mode's depth view).
    static float windowDepthOf(Stored stored) { return kUnormBits ? stored / kUnormMax : stored; }

    // The stored depths of eight neighbouring pixels of a row, row[0..7].
    static Stored8 load8(const Stored* row) {
        Stored8 stored;
        std::memcpy(&stored, row, sizeof stored);
        return stored;
    }

    // The depth test on the stored representation (glDepthFunc): a bool for one fragment, a lane mask
    // (all bits set where a lane passes) for eight. The fragment's depth is stored first, as hardware
    // converts it before comparing.
    static bool passes(CompareOp op, float fragmentDepth, Stored stored) {
        return depthTestPasses(op, store(fragmentDepth), stored);
    }
    static Int8 passes(CompareOp op, Float8 fragmentDepth, Stored8 stored) {
        return depthTestPasses(op, store(fragmentDepth), stored);
    }
};

// The default: 32-bit float, smaller is nearer (OpenGL's convention). Shadow maps always use it.
using DepthFormat = DepthFormatOf<DepthBufferFormat::Float>;

// Calls body(DepthFormatOf<format>{}) with the format as a type: the one switch that turns the per-draw
// choice into a template parameter.
template <class Body>
decltype(auto) withDepthFormat(DepthBufferFormat format, Body&& body) {
    switch (format) {
        case DepthBufferFormat::Unorm16:
            return body(DepthFormatOf<DepthBufferFormat::Unorm16>{});
        case DepthBufferFormat::Unorm24:
            return body(DepthFormatOf<DepthBufferFormat::Unorm24>{});
        case DepthBufferFormat::ReversedFloat:
            return body(DepthFormatOf<DepthBufferFormat::ReversedFloat>{});
        case DepthBufferFormat::Float:
            break;
    }
    return body(DepthFormat{});
}

// The clip-space depth range of `format`: reversed Z clips to 0 ≤ z ≤ w, the others to −w ≤ z ≤ w.
constexpr ClipDepthRange clipDepthRange(DepthBufferFormat format) {
    return format == DepthBufferFormat::ReversedFloat ? ClipDepthRange::ReversedZeroToW
                                                      : ClipDepthRange::MinusWToW;
}

// What clearing the depth buffer of `format` writes (the far plane).
inline float depthClearValue(DepthBufferFormat format) {
    return withDepthFormat(format, [](auto f) { return decltype(f)::kClear; });
}

// The window depth (in [0, 1], near 0 under OpenGL's convention, near 1 reversed) a stored value of
// `format` stands for.
inline float windowDepthOf(DepthBufferFormat format, float stored) {
    return withDepthFormat(format, [stored](auto f) { return decltype(f)::windowDepthOf(stored); });
}

// The compare that keeps the nearest surface, given the one written for OpenGL's convention (Less or
// LessEqual): mirrored to Greater or GreaterEqual for reversed Z, where nearer is larger.
inline CompareOp nearerPasses(DepthBufferFormat format, CompareOp lessIsNearerCompare) {
    if (format != DepthBufferFormat::ReversedFloat) return lessIsNearerCompare;
    switch (lessIsNearerCompare) {
        case CompareOp::Less:
            return CompareOp::Greater;
        case CompareOp::LessEqual:
            return CompareOp::GreaterEqual;
        case CompareOp::Greater:
            return CompareOp::Less;
        case CompareOp::GreaterEqual:
            return CompareOp::LessEqual;
        default:
            return lessIsNearerCompare;
    }
}

// What the back end's depth test needs of the draw's format: how a fragment's window depth is stored
// and compared. Float and reversed float store it as it is (the direction is the draw's compare); the
// unorm formats store a code whose largest value 2^N − 1 is held here, read per draw. So the back end
// is compiled for two depth codings rather than for every format (each costs a copy of the tile loop
// per shader), and the test is the same arithmetic as DepthFormatOf<format>'s, bit for bit.
// PerFragment: either, chosen per fragment — what the watched back end (the step mode, which is for
// reading, not speed) uses, so that it is compiled once per shader and observer.
enum class DepthCodingKind { Float, Unorm, PerFragment };

// The coding the unwatched back end is compiled with for a format: Unorm for the unorm formats, else Float.
constexpr DepthCodingKind depthCodingOf(DepthBufferFormat format) {
    return format == DepthBufferFormat::Unorm16 || format == DepthBufferFormat::Unorm24
               ? DepthCodingKind::Unorm
               : DepthCodingKind::Float;
}

template <DepthCodingKind kCoding>
struct DepthCoding {
    static constexpr DepthCodingKind kKind = kCoding;
    using Stored = float;
    using Stored8 = Float8;
    float unormMax = 1.0f;  // 2^N − 1 of a unorm format
    bool unorm = false;     // whether the format is a unorm one (PerFragment reads it)

    explicit DepthCoding(DepthBufferFormat format)
        : unormMax(withDepthFormat(format, [](auto f) { return decltype(f)::kUnormMax; })),
          unorm(depthCodingOf(format) == DepthCodingKind::Unorm) {}

    template <class Depth>  // float or Float8
    Depth store(Depth windowDepth) const {
        if constexpr (kKind == DepthCodingKind::Unorm)
            return unormDepthCode(windowDepth, unormMax);
        else if constexpr (kKind == DepthCodingKind::PerFragment)
            return unorm ? unormDepthCode(windowDepth, unormMax) : windowDepth;
        else
            return windowDepth;
    }
    static Stored8 load8(const Stored* row) { return DepthFormat::load8(row); }
    bool passes(CompareOp op, float fragmentDepth, Stored stored) const {
        return depthTestPasses(op, store(fragmentDepth), stored);
    }
    Int8 passes(CompareOp op, Float8 fragmentDepth, Stored8 stored) const {
        return depthTestPasses(op, store(fragmentDepth), stored);
    }
};

// Calls body(DepthCoding<Float or Unorm>) for the draw's format: the one switch from a format to the
// back end's template parameter.
template <class Body>
decltype(auto) withDepthCoding(DepthBufferFormat format, Body&& body) {
    if (depthCodingOf(format) == DepthCodingKind::Unorm)
        return body(DepthCoding<DepthCodingKind::Unorm>(format));
    return body(DepthCoding<DepthCodingKind::Float>(format));
}

}  // namespace facet
