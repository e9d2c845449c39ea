#include "state.h"

#include <ostream>

namespace facet {

std::ostream& operator<<(std::ostream& os, CullMode mode) {
    return os << nameOf(mode);
}

std::ostream& operator<<(std::ostream& os, FrontFace face) {
    return os << nameOf(face);
}

std::ostream& operator<<(std::ostream& os, ProvokingVertex vertex) {
    return os << nameOf(vertex);
}

std::ostream& operator<<(std::ostream& os, CompareOp op) {
    return os << nameOf(op);
}

std::ostream& operator<<(std::ostream& os, Interpolation mode) {
    return os << nameOf(mode);
}

std::ostream& operator<<(std::ostream& os, BlendMode mode) {
    return os << nameOf(mode);
}

std::ostream& operator<<(std::ostream& os, FragmentOutput output) {
    return os << nameOf(output);
}

std::ostream& operator<<(std::ostream& os, DepthBufferFormat format) {
    return os << nameOf(format);
}

std::ostream& operator<<(std::ostream& os, ColorBufferFormat format) {
    return os << nameOf(format);
}

std::ostream& operator<<(std::ostream& os, const DrawState& s) {
    const Viewport& vp = s.viewport;
    os << "viewport " << vp.width << "x" << vp.height << " at (" << vp.x << ", " << vp.y << "), depth range ["
       << vp.minDepth << ", " << vp.maxDepth << "]; cull " << s.raster.cull << " faces, front faces "
       << s.raster.frontFace << ", provoking vertex " << s.raster.provokingVertex << "; "
       << s.raster.subpixelBits << " sub-pixel bits; depth test " << (s.depth.testEnabled ? "on" : "off")
       << " (" << s.depth.compare << ", writes " << (s.depth.writeEnabled ? "on" : "off") << ")";
    // Formats other than the defaults only: what the step mode prints for a default draw is unchanged.
    if (s.depth.format != DepthBufferFormat::Float) os << "; " << s.depth.format << " depth buffer";
    if (s.colorBuffer != ColorBufferFormat::Float) os << "; " << s.colorBuffer << " colour buffer";
    if (s.samples > 1) os << "; " << s.samples << " samples per pixel";
    if (s.depth.offset.any())
        os << "; depth offset " << s.depth.offset.factor << "·slope + " << s.depth.offset.units << " units";
    return os << "; " << s.interpolation << " interpolation; blend " << s.blend << "; output " << s.output;
}

}  // namespace facet
