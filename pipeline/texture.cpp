#include "texture.h"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace facet {

namespace {

// One output texel's share of the input texels along one side: input `first` onward, `weights` summing
// to 1.
struct Footprint {
    int first = 0;
    std::vector<float> weights;
};

// Side n → m = mipSide(n): output i covers input [i·n/m, (i + 1)·n/m), each input texel weighted by
// the length of it inside, divided by n/m. Even n: (½, ½); n = 1: the texel itself.
std::vector<Footprint> footprints(int n, int m) {
    std::vector<Footprint> out(static_cast<std::size_t>(m));
    const double scale = static_cast<double>(n) / m;
    for (int i = 0; i < m; ++i) {
        const double begin = i * scale, end = (i + 1) * scale;
        Footprint& f = out[static_cast<std::size_t>(i)];
        f.first = static_cast<int>(begin);
        for (int j = f.first; j < n && j < end; ++j) {
            const double overlap = std::min(end, j + 1.0) - std::max(begin, static_cast<double>(j));
            f.weights.push_back(static_cast<float>(overlap / scale));
        }
    }
    return out;
}

// Every alpha code's value, for nearestCode.
constexpr std::array<float, 256> kAlphaFromCode = [] {
    std::array<float, 256> table{};
    for (int code = 0; code < 256; ++code)
        table[static_cast<std::size_t>(code)] = alphaFromCode(code);
    return table;
}();

// The code whose table value is nearest `value` (the tables rise with the code).
std::uint8_t nearestCode(const std::array<float, 256>& table, float value) {
    const auto above = std::lower_bound(table.begin(), table.end(), value);
    if (above == table.begin()) return 0;
    if (above == table.end()) return 255;
    const auto below = above - 1;
    return static_cast<std::uint8_t>((value - *below <= *above - value ? below : above) - table.begin());
}

// The level below `above`, box-filtered in linear light (buildMipChain).
Texture nextLevel(const Texture& above) {
    Texture level;
    level.width = mipSide(above.width);
    level.height = mipSide(above.height);
    level.colorFromCode = above.colorFromCode;
    const std::vector<Footprint> columns = footprints(above.width, level.width);
    const std::vector<Footprint> rows = footprints(above.height, level.height);
    // Rows first: each input row filtered across to the new width, then the new rows down.
    std::vector<vec4> across(static_cast<std::size_t>(level.width) * above.height);
    for (int y = 0; y < above.height; ++y)
        for (int x = 0; x < level.width; ++x) {
            const Footprint& f = columns[static_cast<std::size_t>(x)];
            vec4 sum(0.0f);
            for (std::size_t k = 0; k < f.weights.size(); ++k)
                sum += f.weights[k] * above.texel(f.first + static_cast<int>(k), y);
            across[static_cast<std::size_t>(y) * level.width + x] = sum;
        }
    const std::size_t count = static_cast<std::size_t>(level.width) * level.height;
    std::vector<vec4> linear(count);
    for (int y = 0; y < level.height; ++y) {
        const Footprint& f = rows[static_cast<std::size_t>(y)];
        for (int x = 0; x < level.width; ++x) {
            vec4 sum(0.0f);
            for (std::size_t k = 0; k < f.weights.size(); ++k)
                sum += f.weights[k] *
                       across[static_cast<std::size_t>(f.first + static_cast<int>(k)) * level.width + x];
            linear[static_cast<std::size_t>(y) * level.width + x] = sum;
        }
    }
    if (above.codes.empty()) {
        level.texels = std::move(linear);
        return level;
    }
    level.codes.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        const vec4& c = linear[i];
        level.codes[i] = {nearestCode(level.colorFromCode, c.r), nearestCode(level.colorFromCode, c.g),
                          nearestCode(level.colorFromCode, c.b), nearestCode(kAlphaFromCode, c.a)};
    }
    return level;
}

}  // namespace

void buildMipChain(Texture& t) {
    if (t.empty() || !t.mipLevels.empty()) return;
    const Texture* above = &t;
    while (above->width > 1 || above->height > 1) {
        t.mipLevels.push_back(nextLevel(*above));
        above = &t.mipLevels.back();
    }
}

}  // namespace facet
