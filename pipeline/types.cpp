#include "types.h"

#include <ostream>
#include <string>

namespace facet {

DrawStats& DrawStats::operator+=(const DrawStats& o) {
    vertices += o.vertices;
    triangles += o.triangles;
    trianglesClipped += o.trianglesClipped;
    trianglesRejected += o.trianglesRejected;
    trianglesCulled += o.trianglesCulled;
    trianglesZeroArea += o.trianglesZeroArea;
    trianglesMissingSamples += o.trianglesMissingSamples;
    trianglesRasterized += o.trianglesRasterized;
    patchWalks += o.patchWalks;
    fragmentsShaded += o.fragmentsShaded;
    fragmentsShadedBy16 += o.fragmentsShadedBy16;
    fragmentsDepthFailed += o.fragmentsDepthFailed;
    fragmentsDiscarded += o.fragmentsDiscarded;
    fragmentsWritten += o.fragmentsWritten;
    fragmentsStored += o.fragmentsStored;
    tilesDrawn += o.tilesDrawn;
    return *this;
}

std::string clipPlaneNames(std::uint8_t planes) {
    static constexpr const char* kNames[] = {"left", "right", "bottom", "top",
                                             "near", "far",   "w",      "non-finite"};
    std::string names;
    for (int bit = 0; bit < 8; ++bit) {
        if (!(planes & (1u << bit))) continue;
        if (!names.empty()) names += "+";
        names += kNames[bit];
    }
    return names.empty() ? "none" : names;
}

namespace {
std::ostream& print(std::ostream& os, const vec4& v) {
    return os << "(" << v.x << ", " << v.y << ", " << v.z << ", " << v.w << ")";
}
}  // namespace

std::ostream& operator<<(std::ostream& os, const ClipVertex& v) {
    return print(os << "clip ", v.position);
}

std::ostream& operator<<(std::ostream& os, const ClipPolygon& polygon) {
    os << "polygon of " << polygon.count << " vertices, planes cut: " << clipPlaneNames(polygon.planesCut);
    for (int i = 0; i < polygon.count; ++i)
        os << "\n  v" << i << " " << polygon.vertices[i];
    return os;
}

std::ostream& operator<<(std::ostream& os, const WindowVertex& v) {
    return os << "window (" << v.window.x << ", " << v.window.y << ") snapped (" << v.xFixed << "/"
              << kFixedOne << ", " << v.yFixed << "/" << kFixedOne << ") z " << v.z << " 1/w " << v.invW;
}

std::ostream& operator<<(std::ostream& os, const WindowTriangle& t) {
    os << "window triangle";
    for (int i = 0; i < 3; ++i)
        os << "\n  v" << i << " " << t.vertices[i];
    return os;
}

std::ostream& operator<<(std::ostream& os, const EdgeFunction& e) {
    return os << "E(x,y) = " << e.a << "·x + " << e.b << "·y + " << e.c
              << (e.bias() ? " (not top-left: bias −1)" : " (top-left)");
}

std::ostream& operator<<(std::ostream& os, const TriangleSetup& s) {
    os << "setup: 2·area " << s.doubleArea << ", " << (s.frontFacing ? "front" : "back")
       << "-facing, pixels x " << s.minX << ".." << s.maxX << " y " << s.minY << ".." << s.maxY << ", "
       << (s.perspective ? "perspective-correct" : "affine") << ", " << s.varyingCount << " varying floats";
    for (int i = 0; i < 3; ++i)
        os << "\n  edge " << i << ": " << s.edges[i];
    return os;
}

std::ostream& operator<<(std::ostream& os, const CoverageBlock& b) {
    os << "block at (" << b.x << ", " << b.y << ")" << (b.fullyCovered ? ", fully covered" : "");
    for (int row = 0; row < kBlockSize; ++row) {
        os << "\n  ";
        for (int column = 0; column < kBlockSize; ++column)
            os << (((b.mask >> (row * kBlockSize + column)) & 1) ? '#' : '.');
    }
    return os;
}

std::ostream& operator<<(std::ostream& os, const CoverageEvent& e) {
    os << "sample (" << e.x << ", " << e.y << ") of triangle " << e.triangle << ": "
       << (e.covered ? "covered" : "not covered") << (e.culled ? " (culled: would have been)" : "")
       << "; E =";
    for (int i = 0; i < 3; ++i) {
        os << " " << e.edgeValues[static_cast<std::size_t>(i)];
        if ((e.tiedEdges >> i) & 1)
            os << ((e.topLeftEdges >> i) & 1 ? " (tie on a top-left edge: inside)" : " (tie: outside)");
    }
    return os;
}

std::ostream& operator<<(std::ostream& os, const ResolveEvent& e) {
    os << "resolve (" << e.x << ", " << e.y << "): " << e.fragments.size() << " fragments, farthest first";
    print(os << "; colour ", e.colorBefore);
    for (const ResolvedFragment& f : e.fragments) {
        os << "\n  #" << f.submission << " depth " << f.depth << " " << f.blend;
        print(os << " ", f.color);
        print(os << " -> ", f.colorAfter);
    }
    return os;
}

std::ostream& operator<<(std::ostream& os, FragmentFate fate) {
    switch (fate) {
        case FragmentFate::Written:
            return os << "written";
        case FragmentFate::DepthFailed:
            return os << "failed the depth test";
        case FragmentFate::Discarded:
            return os << "discarded by the fragment shader";
        case FragmentFate::Stored:
            return os << "stored in the pixel's fragment list";
        case FragmentFate::Dropped:
            return os << "dropped: its tile's fragment pool is full";
    }
    return os << "?";
}

std::ostream& operator<<(std::ostream& os, const FragmentEvent& e) {
    os << "fragment (" << e.x << ", " << e.y << ") of triangle " << e.triangle << ": λ (" << e.barycentrics.x
       << ", " << e.barycentrics.y << ", " << e.barycentrics.z << "), 1/w " << e.invW << ", depth " << e.depth
       << " vs stored " << e.depthBefore << ", " << e.fate;
    if (e.fate == FragmentFate::Written || e.fate == FragmentFate::Stored) {
        print(os << "; shaded ", e.shaded);
        print(os << ", colour ", e.colorBefore);
        print(os << " -> ", e.colorAfter);
    }
    return os;
}

std::ostream& operator<<(std::ostream& os, TriangleFate fate) {
    switch (fate) {
        case TriangleFate::Drawn:
            return os << "drawn";
        case TriangleFate::NonFinite:
            return os << "dropped: a vertex is NaN or infinite";
        case TriangleFate::OutsideFrustum:
            return os << "rejected: wholly outside one frustum plane";
        case TriangleFate::ClippedAway:
            return os << "clipped away";
        case TriangleFate::ZeroArea:
            return os << "culled: zero area after snapping";
        case TriangleFate::MissesSamples:
            return os << "skipped: covers no pixel centre";
        case TriangleFate::Culled:
            return os << "culled: faces away";
    }
    return os << "?";
}

std::ostream& operator<<(std::ostream& os, const DrawStats& s) {
    return os << s.vertices << " vertices, " << s.triangles << " triangles (" << s.trianglesClipped
              << " clipped, " << s.trianglesRejected << " rejected, " << s.trianglesCulled << " culled, "
              << s.trianglesZeroArea << " zero-area, " << s.trianglesMissingSamples
              << " between pixel centres, " << s.trianglesRasterized << " rasterized, " << s.patchWalks
              << " tile walks as patches), " << s.fragmentsShaded << " fragments shaded ("
              << s.fragmentsShadedBy16 << " sixteen at a time, " << s.fragmentsDepthFailed
              << " failed depth, " << s.fragmentsDiscarded << " discarded, " << s.fragmentsWritten
              << " written, " << s.fragmentsStored << " stored)";
}

}  // namespace facet
