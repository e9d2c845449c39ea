#include "pipeline.h"

#include <algorithm>
#include <sstream>

namespace facet {

void validateDrawState(const DrawState& state, const Framebuffer& target, int tileSize) {
    if (tileSize < kBlockSize || tileSize % kBlockSize != 0)
        throw std::invalid_argument("tile size " + std::to_string(tileSize) +
                                    " is not a positive multiple of " + std::to_string(kBlockSize));
    const Viewport& vp = state.viewport;
    if (vp.width <= 0 || vp.height <= 0 || vp.x < 0 || vp.y < 0 || vp.x + vp.width > target.width() ||
        vp.y + vp.height > target.height() || target.width() > kMaxViewportSide ||
        target.height() > kMaxViewportSide) {
        std::ostringstream message;
        message << "viewport " << vp.width << "x" << vp.height << "+" << vp.x << "+" << vp.y
                << " does not fit the " << target.width() << "x" << target.height()
                << " framebuffer (each side at most " << kMaxViewportSide << ")";
        throw std::invalid_argument(message.str());
    }
    if (state.raster.subpixelBits < 0 || state.raster.subpixelBits > kMaxSubpixelBits)
        throw std::invalid_argument("subpixel bits must be 0.." + std::to_string(kMaxSubpixelBits));
    if (standardSamplePositions(state.samples).empty())
        throw std::invalid_argument("samples per pixel " + std::to_string(state.samples) +
                                    " is not 1, 2, 4, 8 or 16");
    if (state.samples > 1 && target.samples() != state.samples) {
        std::string message = "a draw of " + std::to_string(state.samples);
        message += " samples per pixel needs a framebuffer of as many (Framebuffer::useSamples), not ";
        message += std::to_string(target.samples());
        throw std::invalid_argument(message);
    }
    if (state.samples > 1 && state.output == FragmentOutput::AppendToLists)
        throw std::invalid_argument("multisampling cannot append to fragment lists, which are per pixel");
}

void throwIndexOutOfRange(std::size_t vertexCount, std::span<const std::uint32_t> indices) {
    for (std::size_t k = 0; k < indices.size(); ++k)
        if (indices[k] >= vertexCount)
            throw std::invalid_argument("index " + std::to_string(indices[k]) + " at position " +
                                        std::to_string(k) + " is out of range (" +
                                        std::to_string(vertexCount) + " vertices)");
}

}  // namespace facet
