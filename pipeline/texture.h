// Textures: an RGBA image sampled with bilinear filtering and repeat wrapping (GL_LINEAR, GL_REPEAT),
// texel centres at (i + ½)/size as in OpenGL. Read-only during a draw.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "glsl.h"

namespace facet {

// Texels are kept at their file's precision: an 8-bit file as its codes (4 bytes a texel, a quarter of
// float RGBA), decoded to linear values when sampled through a 256-entry table per channel kind; float
// and 16-bit files as linear float RGBA.
struct Texture {
    using Codes = std::array<std::uint8_t, 4>;  // R, G, B, A

    int width = 0;
    int height = 0;
    // Row-major, row 0 at v = 1 (the top of the image file). Exactly one of the two is filled.
    std::vector<vec4> texels;                // linear RGBA
    std::vector<Codes> codes;                // 8-bit RGBA codes, decoded by the tables below
    std::array<float, 256> colorFromCode{};  // an R, G or B code's linear value (sRGB-decoded, or code/255)
    std::array<float, 256> alphaFromCode{};  // an alpha code's value (code/255: alpha is not encoded)

    bool empty() const { return texels.empty() && codes.empty(); }
    std::size_t bytes() const { return texels.size() * sizeof(vec4) + codes.size() * sizeof(Codes); }
    vec4 texel(int x, int y) const {
        const std::size_t i = static_cast<std::size_t>(y) * width + x;
        if (codes.empty()) return texels[i];
        const Codes& c = codes[i];
        return {colorFromCode[c[0]], colorFromCode[c[1]], colorFromCode[c[2]], alphaFromCode[c[3]]};
    }
};

// texture(sampler, uv) in GLSL terms. v = 0 is the bottom row of the image, as OBJ texture coordinates
// and OpenGL expect.
inline vec4 sampleBilinear(const Texture& t, vec2 uv) {
    if (t.empty()) return vec4(1.0f);
    // Continuous texel coordinates, texel centres at integers; the image's first row is v = 1.
    const float u = uv.x * static_cast<float>(t.width) - 0.5f;
    const float v = (1.0f - uv.y) * static_cast<float>(t.height) - 0.5f;
    if (!std::isfinite(u) || !std::isfinite(v)) return vec4(0.0f);
    const float fu = std::floor(u), fv = std::floor(v);
    const float s = u - fu, r = v - fv;  // bilinear weights
    auto wrap = [](float i, int n) {
        const int m = static_cast<int>(std::fmod(i, static_cast<float>(n)));
        return m < 0 ? m + n : m;
    };
    const int x0 = wrap(fu, t.width), x1 = wrap(fu + 1.0f, t.width);
    const int y0 = wrap(fv, t.height), y1 = wrap(fv + 1.0f, t.height);
    return mix(mix(t.texel(x0, y0), t.texel(x1, y0), s), mix(t.texel(x0, y1), t.texel(x1, y1), s), r);
}

}  // namespace facet
