// Interpolation: a fragment's barycentrics, depth, 1/w and varyings at its sample.
// In: TriangleSetup (+ its varying planes) and the sample. Out: λ1, λ2 (λ0 = 1 − λ1 − λ2), window
// depth, 1/w, and the varyings as a flat float array.
//
// Every formula is written once, as a template on the lane type F: float for one fragment, Float8
// for eight (wide.h). The back end picks the lane width row by row (eight lanes when several
// fragments of a row survive the depth test, one when a sliver leaves one or two), so both widths
// must give the same bits: they run the same operations in the same order, and the perspective
// divide is an exact IEEE division in both (reciprocal()). An approximate reciprocal or any other
// speed/accuracy trade belongs here, chosen per draw for both widths, never by lane width.
#pragma once

#include "sample_position.h"
#include "types.h"
#include "wide.h"

namespace facet {

// λ1 and λ2 at the samples of an 8×8 block, from the exact edge values: λᵢ = Eᵢ / (2·area). The edge
// values at the block's first sample and their per-pixel steps are integers below 2^47, exact in
// double, so each λ is rounded once, to float, whichever row or lane it is.
// The eight columns are kept as two vectors of four doubles, one register each with AVX: a vector of
// eight doubles is wider than AVX2's registers, and GCC builds its splat of a scalar (1/(2·area) in
// every row) through the stack, eight stores read back as wider loads, a store-forwarding stall per
// row that made the AVX2 copy's block walk twice as slow as the AVX-512 one.
struct BlockBarycentrics {
    using Double4 = double __attribute__((vector_size(32)));
    double e1y, e2y;
    Double4 invArea;               // 1/(2·area) in every lane
    Double4 row0E1[2], row0E2[2];  // columns 0–3 and 4–7: E at the block's first row, e + column·eₓ

    BlockBarycentrics(const TriangleSetup& setup, int blockX, int blockY) {
        const double inverse = 1.0 / static_cast<double>(setup.doubleArea);
        invArea = Double4{inverse, inverse, inverse, inverse};
        const SamplePoint first = samplePosition(blockX, blockY);
        const auto e1 = static_cast<double>(setup.edges[1].at(first.x, first.y));
        const auto e2 = static_cast<double>(setup.edges[2].at(first.x, first.y));
        const auto e1x = static_cast<double>(setup.edges[1].a * kFixedOne);
        const auto e2x = static_cast<double>(setup.edges[2].a * kFixedOne);
        e1y = static_cast<double>(setup.edges[1].b * kFixedOne);
        e2y = static_cast<double>(setup.edges[2].b * kFixedOne);
        const Double4 columns[2] = {{0, 1, 2, 3}, {4, 5, 6, 7}};
        for (int half = 0; half < 2; ++half) {
            row0E1[half] = e1 + columns[half] * e1x;
            row0E2[half] = e2 + columns[half] * e2x;
        }
    }

    // The eight samples of block row `row`, lane = column: (e + column·eₓ + row·e_y) / (2·area), the
    // sums in that order (each term exact), once per block for the first two, per row for the last.
    void row(int row, Float8& b1, Float8& b2) const {
        const double down1 = row * e1y, down2 = row * e2y;
        b1 = toFloat8((row0E1[0] + down1) * invArea, (row0E1[1] + down1) * invArea);
        b2 = toFloat8((row0E2[0] + down2) * invArea, (row0E2[1] + down2) * invArea);
    }

  private:
    // Two vectors of four doubles, each rounded to float, as one vector of eight floats.
    static Float8 toFloat8(Double4 low, Double4 high) {
        using Float4 = float __attribute__((vector_size(16)));
        return __builtin_shufflevector(__builtin_convertvector(low, Float4),
                                       __builtin_convertvector(high, Float4), 0, 1, 2, 3, 4, 5, 6, 7);
    }
};

// λ = E / (2·area) in each lane of a patch (rasterize.h: patchCoverage), from its exact edge values:
// each E converted to double (exact), multiplied by inverse = 1/(2·area) and rounded once to float, the
// operations BlockBarycentrics does on the same E, so a pixel gets the same bits in either walk. The
// doubles are made four at a time, as there (the reason is in BlockBarycentrics' comment).
inline Float8 barycentricLanes(Int8 e, double inverse) {
    using Int4 = std::int32_t __attribute__((vector_size(16)));
    using Double4 = double __attribute__((vector_size(32)));
    using Float4 = float __attribute__((vector_size(16)));
    const Double4 invArea = {inverse, inverse, inverse, inverse};
    const Int4 low = __builtin_shufflevector(e, e, 0, 1, 2, 3),
               high = __builtin_shufflevector(e, e, 4, 5, 6, 7);
    const Float4 lowLambda = __builtin_convertvector(__builtin_convertvector(low, Double4) * invArea, Float4);
    const Float4 highLambda =
        __builtin_convertvector(__builtin_convertvector(high, Double4) * invArea, Float4);
    return __builtin_shufflevector(lowLambda, highLambda, 0, 1, 2, 3, 4, 5, 6, 7);
}
#if FACET_SIXTEEN_LANES
inline Floatx16 barycentricLanes(Intx16 e, double inverse) {
    const Int8 low = __builtin_shufflevector(e, e, 0, 1, 2, 3, 4, 5, 6, 7);
    const Int8 high = __builtin_shufflevector(e, e, 8, 9, 10, 11, 12, 13, 14, 15);
    return joinHalves(barycentricLanes(low, inverse), barycentricLanes(high, inverse));
}
#endif

// Window depth is an affine function of screen position: z = z0 + λ1·(z1 − z0) + λ2·(z2 − z0).
template <class F>
inline F interpolateDepth(const TriangleSetup& s, F b1, F b2) {
    return s.z0 + b1 * s.dz1 + b2 * s.dz2;
}

// 1/w is affine in screen space too: 1/w = 1/w0 + λ1·(1/w1 − 1/w0) + λ2·(1/w2 − 1/w0).
template <class F>
inline F interpolateInvW(const TriangleSetup& s, F b1, F b2) {
    return s.invW0 + b1 * s.dInvW1 + b2 * s.dInvW2;
}

// 1/x for the perspective divide: an exact IEEE division for one lane and eight alike (see the top).
template <class F>
inline F reciprocal(F x) {
    return 1.0f / x;
}

// Perspective-correct: a = (Σ λᵢ·aᵢ/wᵢ) / (Σ λᵢ/wᵢ); the planes already hold aᵢ/wᵢ (triangle_setup).
// Affine: a = Σ λᵢ·aᵢ, which is only right when w is the same at all three vertices.
// After clipping every wᵢ ≥ kMinClipW and λᵢ ≥ 0, so Σ λᵢ/wᵢ > 0 and the divide is safe.
// Flat varyings (the first s.flatVaryingCount) are copied: the provoking vertex's value, exactly.
// `planes` are the setup's 3 · varyingCount floats (types.h: a row of values at v0, a row of
// differences to v1, one to v2); out[k] receives varying k.
// kVaryings and kFlat, when given (≥ 0), are s.varyingCount and s.flatVaryingCount known when compiling
// (the back end's, from its shader), so that the loops unroll; the same operations either way.
template <class F, int kVaryings = -1, int kFlat = -1>
inline void interpolateVaryings(const TriangleSetup& s, const float* planes, F b1, F b2, F* out) {
    const int n = kVaryings >= 0 ? kVaryings : s.varyingCount;
    const int flat = kFlat >= 0 ? kFlat : s.flatVaryingCount;
    const float *atV0 = planes, *toV1 = planes + n, *toV2 = planes + 2 * n;
    for (int k = 0; k < flat; ++k)
        out[k] = lanes<F>(atV0[k]);
    if (s.perspective) {
        const F w = reciprocal(interpolateInvW(s, b1, b2));
        for (int k = flat; k < n; ++k)
            out[k] = (atV0[k] + b1 * toV1[k] + b2 * toV2[k]) * w;
    } else {
        for (int k = flat; k < n; ++k)
            out[k] = atV0[k] + b1 * toV1[k] + b2 * toV2[k];
    }
}

// The screen-space derivatives of two neighbouring varyings k, k + 1 (a texture coordinate pair), for
// a texture's level of detail (OpenGL 4.6 §8.14.1). Per triangle: the slopes in x and y (per pixel, y
// down the rows) of their planes A (a/w, or a itself when affine) and of W = 1/w, from λ1's and λ2's
// slopes ∂λᵢ/∂x = a_edge(i)·kFixedOne / (2·area), computed in double and rounded once.
struct VaryingPairSlopes {
    float ax[2] = {}, ay[2] = {};  // ∂A/∂x, ∂A/∂y of each of the two
    float wx = 0, wy = 0;          // ∂W/∂x, ∂W/∂y

    VaryingPairSlopes() = default;
    VaryingPairSlopes(const TriangleSetup& s, const float* planes, int k) {
        const double invArea = 1.0 / static_cast<double>(s.doubleArea);
        const double b1x = static_cast<double>(s.edges[1].a * kFixedOne) * invArea;
        const double b1y = static_cast<double>(s.edges[1].b * kFixedOne) * invArea;
        const double b2x = static_cast<double>(s.edges[2].a * kFixedOne) * invArea;
        const double b2y = static_cast<double>(s.edges[2].b * kFixedOne) * invArea;
        const float *toV1 = planes + s.varyingCount, *toV2 = planes + 2 * s.varyingCount;
        for (int i = 0; i < 2; ++i) {
            ax[i] = static_cast<float>(toV1[k + i] * b1x + toV2[k + i] * b2x);
            ay[i] = static_cast<float>(toV1[k + i] * b1y + toV2[k + i] * b2y);
        }
        wx = static_cast<float>(s.dInvW1 * b1x + s.dInvW2 * b2x);
        wy = static_cast<float>(s.dInvW1 * b1y + s.dInvW2 * b2y);
    }
};

// ∂a/∂x, ∂b/∂x, ∂a/∂y, ∂b/∂y of the pair (a, b) = `value` (as interpolateVaryings gave them) into
// out[0..3]. Perspective-correct, a = A/W: ∂a/∂x = (A_x − a·W_x)/W, the quotient rule with A = a·W;
// affine, the planes' slopes themselves. The same operations for one lane and eight: the same bits.
template <class F>
inline void interpolateDerivatives(const TriangleSetup& s, const VaryingPairSlopes& d, F b1, F b2,
                                   const F* value, F* out) {
    if (s.perspective) {
        const F w = reciprocal(interpolateInvW(s, b1, b2));
        out[0] = (d.ax[0] - value[0] * d.wx) * w;
        out[1] = (d.ax[1] - value[1] * d.wx) * w;
        out[2] = (d.ay[0] - value[0] * d.wy) * w;
        out[3] = (d.ay[1] - value[1] * d.wy) * w;
    } else {
        out[0] = lanes<F>(d.ax[0]);
        out[1] = lanes<F>(d.ax[1]);
        out[2] = lanes<F>(d.ay[0]);
        out[3] = lanes<F>(d.ay[1]);
    }
}

// Eight fragments at once, into a FragmentBatch (structure of arrays).
inline void interpolateVaryings(const TriangleSetup& s, const float* planes, Float8 b1, Float8 b2,
                                FragmentBatch& out) {
    interpolateVaryings<Float8>(s, planes, b1, b2, out.varyings);
}

}  // namespace facet
