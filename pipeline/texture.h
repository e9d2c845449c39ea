// Textures: an RGBA image with repeat wrapping (GL_REPEAT) and texel centres at (i + ½)/size as in
// OpenGL, sampled with the draw's filter: nearest (GL_NEAREST), bilinear (GL_LINEAR) or trilinear
// (GL_LINEAR_MIPMAP_LINEAR over a mip chain). Read-only during a draw.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "glsl.h"
#include "names.h"
#include "wide.h"

namespace facet {

// How a texture is filtered (per draw: SurfaceUniforms::textureFilter). docs/trade.md weighs them.
enum class TextureFilter : std::uint8_t {
    Nearest,    // the texel containing uv (GL_NEAREST): one read, blocky up close, moiré far away
    Bilinear,   // the four nearest texels weighted (GL_LINEAR): smooth up close, moiré far away
    Trilinear,  // bilinear in the two mip levels around the footprint's size, blended
                // (GL_LINEAR_MIPMAP_LINEAR)
};
inline constexpr EnumName<TextureFilter> kTextureFilterNames[] = {{TextureFilter::Nearest, "nearest"},
                                                                  {TextureFilter::Bilinear, "bilinear"},
                                                                  {TextureFilter::Trilinear, "trilinear"}};
constexpr std::span<const EnumName<TextureFilter>> enumNames(TextureFilter) {
    return kTextureFilterNames;
}

// An 8-bit alpha code's value: code/255 as the image libraries read 8-bit data as float (code · (1/255)),
// and 255 exactly 1, opaque (the product rounds a hair away from it). Alpha is never display-encoded,
// so it needs no table: a sample computes it, eight lanes at once, where a table would cost a gather.
constexpr float alphaFromCode(int code) {
    return code == 255 ? 1.0f : static_cast<float>(code) * (1.0f / 255.0f);
}
// The same for eight codes (0–255), or sixteen, lane by lane the same bits.
inline Float8 alphaFromCode(Int8 code) {
    return select(code == 255, splat(1.0f), __builtin_convertvector(code, Float8) * (1.0f / 255.0f));
}
#if FACET_SIXTEEN_LANES
inline Floatx16 alphaFromCode(Intx16 code) {
    return select(code == 255, splatLanes<Floatx16>(1.0f),
                  __builtin_convertvector(code, Floatx16) * (1.0f / 255.0f));
}
#endif

// Texels are kept at their file's precision: an 8-bit file as its codes (4 bytes a texel, a quarter of
// float RGBA), decoded to linear values when sampled: R, G and B through a 256-entry table (sRGB-decoded,
// or code/255), alpha by alphaFromCode; float and 16-bit files as linear float RGBA.
struct Texture {
    using Codes = std::array<std::uint8_t, 4>;  // R, G, B, A

    int width = 0;
    int height = 0;
    // Row-major, row 0 at v = 1 (the top of the image file). Exactly one of the two is filled.
    std::vector<vec4> texels;                // linear RGBA
    std::vector<Codes> codes;                // 8-bit RGBA codes: colorFromCode, alphaFromCode
    std::array<float, 256> colorFromCode{};  // an R, G or B code's linear value (sRGB-decoded, or code/255)
    // Mip levels 1, 2, … down to 1×1 (level 0 is this texture), each in this texture's form: built by
    // buildMipChain() only for a texture some draw filters trilinearly; empty otherwise.
    std::vector<Texture> mipLevels;

    bool empty() const { return texels.empty() && codes.empty(); }
    std::size_t bytes() const {
        std::size_t total = texels.size() * sizeof(vec4) + codes.size() * sizeof(Codes);
        for (const Texture& level : mipLevels)
            total += level.bytes();
        return total;
    }
    int levelCount() const { return 1 + static_cast<int>(mipLevels.size()); }
    const Texture& level(int i) const { return i == 0 ? *this : mipLevels[static_cast<std::size_t>(i - 1)]; }
    // Always inlined, as is sampleBilinear: out of line, a vec4 comes back in two registers that the
    // caller joins through memory, a store-forwarding stall per texel (a quarter of a textured frame).
    [[gnu::always_inline]] vec4 texel(int x, int y) const {
        const std::size_t i = static_cast<std::size_t>(y) * width + x;
        if (codes.empty()) return texels[i];
        const Codes& c = codes[i];
        return {colorFromCode[c[0]], colorFromCode[c[1]], colorFromCode[c[2]], alphaFromCode(c[3])};
    }
};

// The size of the mip level below a side of n texels: floor(n/2), at least 1 (OpenGL 4.6 §8.14.3).
constexpr int mipSide(int n) {
    return std::max(1, n / 2);
}

// Builds t.mipLevels (once: a texture that has them keeps them). Each level is a box filter of the one
// above in linear light: 8-bit texels are decoded through their tables, averaged, and re-encoded to the
// nearest code of the same table, so a level costs a quarter of the one above in the file's form
// (4/3 of the texture in all) rather than 16 bytes a texel as float RGBA. A side of even length n
// halves exactly (each texel the mean of 2×2); an odd one (floor halving to m = (n − 1)/2) gives each
// new texel the area of the old row it covers, [i·n/m, (i + 1)·n/m), so the odd texel's weight is
// shared by its neighbours and every old texel counts in proportion to its area.
void buildMipChain(Texture& t);

namespace detail {

inline int wrapTexel(float i, int n) {
    const int m = static_cast<int>(std::fmod(i, static_cast<float>(n)));
    return m < 0 ? m + n : m;
}

// wrapTexel(i, n) and wrapTexel(i + 1, n) for an integer-valued i (a floor), as bilinear filtering
// needs them. Below 2^24 every integer is a float, so fmod, i + 1 and the int remainder are all exact
// and agree: the remainder costs a fraction of fmodf's call, and the second index follows from the
// first. Beyond, wrapTexel as it is.
inline void wrapTexelPair(float i, int n, int& first, int& second) {
    // Inside the texture (texture coordinates in [0, 1), the common case): no remainder, whose integer
    // division would cost more than the rest of the sample.
    if (i >= 0.0f && i < static_cast<float>(n - 1)) {
        first = static_cast<int>(i);
        second = first + 1;
        return;
    }
    if (std::abs(i) < 16777216.0f) {
        int m = static_cast<int>(i) % n;
        if (m < 0) m += n;
        first = m;
        second = m + 1 == n ? 0 : m + 1;
        return;
    }
    first = wrapTexel(i, n);
    second = wrapTexel(i + 1.0f, n);
}

}  // namespace detail

// texture(sampler, uv) with GL_LINEAR in GLSL terms. v = 0 is the bottom row of the image, as OBJ
// texture coordinates and OpenGL expect.
[[gnu::always_inline]] inline vec4 sampleBilinear(const Texture& t, vec2 uv) {
    if (t.empty()) return vec4(1.0f);
    // Continuous texel coordinates, texel centres at integers; the image's first row is v = 1.
    const float u = uv.x * static_cast<float>(t.width) - 0.5f;
    const float v = (1.0f - uv.y) * static_cast<float>(t.height) - 0.5f;
    if (!std::isfinite(u) || !std::isfinite(v)) return vec4(0.0f);
    const float fu = std::floor(u), fv = std::floor(v);
    const float s = u - fu, r = v - fv;  // bilinear weights
    int x0, x1, y0, y1;
    detail::wrapTexelPair(fu, t.width, x0, x1);
    detail::wrapTexelPair(fv, t.height, y0, y1);
    return mix(mix(t.texel(x0, y0), t.texel(x1, y0), s), mix(t.texel(x0, y1), t.texel(x1, y1), s), r);
}

// The same at eight points at once, or sixteen (F: the lanes; bit i of liveLanes: lane i is a fragment;
// the others, whose uv may be anything, are opaque white). The lanes give sampleBilinear's bits: the same
// operations in the same order, lane by lane. When every live lane's four texels lie inside the texture
// without wrapping (the common case), the weights are computed for all the lanes at once and the texels
// gathered; otherwise each live lane is sampled alone.
template <WideLanes F>
[[gnu::always_inline]] inline WideVec4<F> sampleBilinear(const Texture& t, const WideVec2<F>& uv,
                                                         unsigned liveLanes) {
    using Int = WideMask<F>;
    constexpr int kLanes = LaneTraits<F>::kCount;
    constexpr unsigned kAllLanes = (1u << kLanes) - 1u;
    const F one = splatLanes<F>(1.0f);
    // No live lane: nothing to read (below, dead lanes read texel 0 and its neighbours, which exist only
    // when some live lane has shown the texture to be at least 2×2).
    if (t.empty() || liveLanes == 0) return {one, one, one, one};
    const F u = uv.x * static_cast<float>(t.width) - 0.5f;
    const F v = (1.0f - uv.y) * static_cast<float>(t.height) - 0.5f;
    // 0 ≤ u < width − 1 is 0 ≤ ⌊u⌋ ≤ width − 2: the texel and its right neighbour without wrapping
    // (wrapTexelPair's first case); false for NaN and ±∞.
    const Int live = laneMaskOf<F>(liveLanes);
    const Int inside = (u >= 0.0f) & (u < static_cast<float>(t.width - 1)) & (v >= 0.0f) &
                       (v < static_cast<float>(t.height - 1));
    if (signMask(inside | ~live) != kAllLanes) {
        WideVec4<F> texel{one, one, one, one};
        for (int lane = 0; lane < kLanes; ++lane) {
            if (!((liveLanes >> lane) & 1)) continue;
            const vec4 c = sampleBilinear(t, vec2(uv.x[lane], uv.y[lane]));
            texel.x[lane] = c.r;
            texel.y[lane] = c.g;
            texel.z[lane] = c.b;
            texel.w[lane] = c.a;
        }
        return texel;
    }
    // Dead lanes read texel 0 (their uv may be out of range or NaN) and are made white at the end.
    const Int x0 = __builtin_convertvector(select(live, u, 0.0f), Int);  // ⌊u⌋: u ≥ 0
    const Int y0 = __builtin_convertvector(select(live, v, 0.0f), Int);
    const F s = u - __builtin_convertvector(x0, F), r = v - __builtin_convertvector(y0, F);
    const Int i00 = y0 * t.width + x0, i10 = i00 + 1, i01 = i00 + t.width, i11 = i01 + 1;
    // mix(mix(t00, t10, s), mix(t01, t11, s), r), GLM's mix(x, y, a) = x·(1 − a) + y·a, per channel.
    const F notS = 1.0f - s, notR = 1.0f - r;
    auto filter = [&](F t00, F t10, F t01, F t11) {
        return select(live, (t00 * notS + t10 * s) * notR + (t01 * notS + t11 * s) * r, one);
    };
    if (t.codes.empty()) {
        // Linear float RGBA: channel k of texel i is float 4·i + k.
        const float* f = &t.texels[0].x;
        auto channel = [&](int k) {
            return filter(gather(f, i00 * 4 + k), gather(f, i10 * 4 + k), gather(f, i01 * 4 + k),
                          gather(f, i11 * 4 + k));
        };
        return {channel(0), channel(1), channel(2), channel(3)};
    }
    // 8-bit codes: one word per texel, R in its lowest byte (Codes' order in memory, little-endian),
    // R, G and B decoded through the colour table, alpha (the top byte) computed.
    const Int c00 = gatherWords(t.codes.data(), i00), c10 = gatherWords(t.codes.data(), i10),
              c01 = gatherWords(t.codes.data(), i01), c11 = gatherWords(t.codes.data(), i11);
    auto color = [&](int shift) {
        auto decode = [&](Int c) { return lookupByteCodes(t.colorFromCode, (c >> shift) & 0xff); };
        return filter(decode(c00), decode(c10), decode(c01), decode(c11));
    };
    auto alpha = [&](Int c) { return alphaFromCode((c >> 24) & 0xff); };
    return {color(0), color(8), color(16), filter(alpha(c00), alpha(c10), alpha(c01), alpha(c11))};
}

// GL_NEAREST: the texel whose square [i, i + 1)/size contains uv.
inline vec4 sampleNearest(const Texture& t, vec2 uv) {
    if (t.empty()) return vec4(1.0f);
    const float u = uv.x * static_cast<float>(t.width);
    const float v = (1.0f - uv.y) * static_cast<float>(t.height);
    if (!std::isfinite(u) || !std::isfinite(v)) return vec4(0.0f);
    return t.texel(detail::wrapTexel(std::floor(u), t.width), detail::wrapTexel(std::floor(v), t.height));
}

// The level of detail λ = log2 ρ of OpenGL 4.6 §8.14.1, from uv's screen-space derivatives (per pixel):
//   ρ = max(√((∂u/∂x·w)² + (∂v/∂x·h)²), √((∂u/∂y·w)² + (∂v/∂y·h)²))
// the longer side of the pixel's footprint in level-0 texels (w × h). Not clamped: −∞ for a point.
inline float textureLod(const Texture& t, vec2 uvDx, vec2 uvDy) {
    const vec2 size(static_cast<float>(t.width), static_cast<float>(t.height));
    const vec2 dx = uvDx * size, dy = uvDy * size;
    const float rho = std::sqrt(std::max(dot(dx, dx), dot(dy, dy)));
    return std::log2(rho);
}

// GL_LINEAR_MIPMAP_LINEAR: λ clamped to [0, levels − 1]; bilinear in level ⌊λ⌋ and the next, mixed
// by λ's fraction (§8.14.2–3). λ ≤ 0 is magnification: level 0 alone (GL_LINEAR, the magnification
// filter). A texture without a mip chain is its level 0 only.
inline vec4 sampleTrilinear(const Texture& t, vec2 uv, vec2 uvDx, vec2 uvDy) {
    if (t.empty()) return vec4(1.0f);
    const float lod = textureLod(t, uvDx, uvDy);
    // NaN derivatives (uv not finite) sample level 0, which answers as bilinear does.
    if (!(lod > 0.0f)) return sampleBilinear(t, uv);
    const int last = t.levelCount() - 1;
    if (lod >= static_cast<float>(last)) return sampleBilinear(t.level(last), uv);
    const int fine = static_cast<int>(lod);
    const float blend = lod - static_cast<float>(fine);
    return mix(sampleBilinear(t.level(fine), uv), sampleBilinear(t.level(fine + 1), uv), blend);
}

}  // namespace facet
