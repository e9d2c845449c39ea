#include "state.h"

#include <ostream>

namespace facet {

std::ostream& operator<<(std::ostream& os, CullMode mode) {
    switch (mode) {
        case CullMode::None:
            return os << "none";
        case CullMode::Back:
            return os << "back";
        case CullMode::Front:
            return os << "front";
    }
    return os << "?";
}

std::ostream& operator<<(std::ostream& os, FrontFace face) {
    return os << (face == FrontFace::CounterClockwise ? "counter-clockwise" : "clockwise");
}

std::ostream& operator<<(std::ostream& os, ProvokingVertex vertex) {
    return os << (vertex == ProvokingVertex::Last ? "last" : "first");
}

std::ostream& operator<<(std::ostream& os, CompareOp op) {
    static constexpr const char* kNames[] = {"never",   "less",      "equal",         "less-equal",
                                             "greater", "not-equal", "greater-equal", "always"};
    return os << kNames[static_cast<int>(op)];
}

std::ostream& operator<<(std::ostream& os, Interpolation mode) {
    return os << (mode == Interpolation::PerspectiveCorrect ? "perspective-correct" : "affine");
}

std::ostream& operator<<(std::ostream& os, BlendMode mode) {
    switch (mode) {
        case BlendMode::Replace:
            return os << "replace";
        case BlendMode::Additive:
            return os << "additive";
        case BlendMode::Over:
            return os << "over";
        case BlendMode::PremultipliedOver:
            return os << "premultiplied over";
        case BlendMode::Multiply:
            return os << "multiply";
    }
    return os << "?";
}

std::ostream& operator<<(std::ostream& os, FragmentOutput output) {
    return os << (output == FragmentOutput::Blend ? "blend" : "append to fragment lists");
}

std::ostream& operator<<(std::ostream& os, const DrawState& s) {
    const Viewport& vp = s.viewport;
    return os << "viewport " << vp.width << "x" << vp.height << " at (" << vp.x << ", " << vp.y
              << "), depth range [" << vp.minDepth << ", " << vp.maxDepth << "]; cull " << s.raster.cull
              << " faces, front faces " << s.raster.frontFace << ", provoking vertex "
              << s.raster.provokingVertex << "; " << s.raster.subpixelBits << " sub-pixel bits; depth test "
              << (s.depth.testEnabled ? "on" : "off") << " (" << s.depth.compare << ", writes "
              << (s.depth.writeEnabled ? "on" : "off") << "); " << s.interpolation << " interpolation; blend "
              << s.blend << "; output " << s.output;
}

}  // namespace facet
