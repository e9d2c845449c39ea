#include "clip.h"

#include <cmath>

namespace facet {

float planeDistance(const vec4& p, std::uint8_t plane, ClipDepthRange depth) {
    const bool reversed = depth == ClipDepthRange::ReversedZeroToW;
    switch (plane) {
        case kClipLeft:
            return p.w + p.x;
        case kClipRight:
            return p.w - p.x;
        case kClipBottom:
            return p.w + p.y;
        case kClipTop:
            return p.w - p.y;
        case kClipNear:
            return reversed ? p.w - p.z : p.w + p.z;
        case kClipFar:
            return reversed ? p.z : p.w - p.z;
        case kClipW:
            return p.w - kMinClipW;
        default:
            return 0.0f;
    }
}

namespace {

// The vertex where the segment inside → outside meets the plane (clipEdgeT, clipEdgePoint), its
// varyings interpolated with the same t.
ClipVertex intersect(const ClipVertex& inside, float dInside, const ClipVertex& outside, float dOutside,
                     int varyingCount, const DepthFromW& fromW, ClipDepthRange depth) {
    const float t = clipEdgeT(dInside, dOutside);
    ClipVertex v;
    v.position = clipEdgePoint(inside.position, outside.position, t, fromW, depth);
    for (int k = 0; k < varyingCount; ++k)
        v.varyings[k] = inside.varyings[k] + t * (outside.varyings[k] - inside.varyings[k]);
    return v;
}

// One Sutherland–Hodgman pass: keeps the inside part of `in` with respect to one plane.
// Returns the number of vertices written to `out`.
int clipAgainstPlane(const ClipVertex* in, int count, std::uint8_t plane, ClipDepthRange depth,
                     const DepthFromW& fromW, int varyingCount, ClipVertex* out) {
    int written = 0;
    for (int i = 0; i < count; ++i) {
        const ClipVertex& current = in[i];
        const ClipVertex& next = in[(i + 1) % count];
        const float dCurrent = planeDistance(current.position, plane, depth);
        const float dNext = planeDistance(next.position, plane, depth);
        const bool currentInside = dCurrent >= 0.0f;
        const bool nextInside = dNext >= 0.0f;
        if (currentInside) out[written++] = current;
        if (currentInside && !nextInside)
            out[written++] = intersect(current, dCurrent, next, dNext, varyingCount, fromW, depth);
        else if (!currentInside && nextInside)
            out[written++] = intersect(next, dNext, current, dCurrent, varyingCount, fromW, depth);
    }
    return written;
}

}  // namespace

void clipPolygon(ClipPolygon& polygon, std::uint8_t planes, ClipDepthRange depth, const DepthFromW& fromW) {
    static constexpr std::uint8_t kOrder[] = {kClipLeft, kClipRight, kClipBottom, kClipTop,
                                              kClipNear, kClipFar,   kClipW};
    // Ping-pong between the polygon's own storage and a scratch polygon. Both have room for 3 + 7
    // vertices: a convex polygon cut by one plane gains at most one vertex.
    ClipPolygon scratch;
    ClipVertex* source = polygon.vertices.data();
    ClipVertex* target = scratch.vertices.data();
    int count = polygon.count;
    for (std::uint8_t plane : kOrder) {
        if (!(planes & plane) || count == 0) continue;
        // Skip a plane that no vertex is outside of: the polygon may touch it but is not cut.
        bool anyOutside = false;
        for (int i = 0; i < count; ++i)
            anyOutside |= planeDistance(source[i].position, plane, depth) < 0.0f;
        if (!anyOutside) continue;
        polygon.planesCut |= plane;
        count = clipAgainstPlane(source, count, plane, depth, fromW, polygon.varyingCount, target);
        std::swap(source, target);
    }
    if (count < 3) count = 0;
    for (int i = 0; i < count; ++i)
        if (computeOutcode(source[i].position, depth) & kNonFinite) count = 0;
    if (source != polygon.vertices.data())
        for (int i = 0; i < count; ++i)
            polygon.vertices[i] = source[i];
    polygon.count = count;
}

}  // namespace facet
