// The scene's triangles for ray queries, through Intel Embree (robust mode): the shadow rays of both
// renderers and the exact reference renderer's camera rays. A ray caster only; Facet's own pipeline
// never sees this. Built only when a scene asks for it (a shadowing light, or the reference).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "pipeline/glsl.h"
#include "pipeline/wide.h"

namespace facet {

// One mesh to trace: positions (eye space, rounded to float once) and a triangle list.
struct RayMesh {
    std::span<const vec3> positions;
    std::span<const std::uint32_t> indices;  // three per triangle
    bool opaque = true;  // opaque meshes cast shadows and stop camera rays; the others are see-through
};

struct RaySceneStats {
    std::size_t triangles = 0;  // given
    // A corner with a NaN or infinite coordinate, or one beyond Embree's range (±1.8e18): never handed over.
    std::size_t nonFiniteSkipped = 0;
    std::size_t indexOutOfRange = 0;  // a corner index beyond the mesh's positions: never handed either
    double buildMilliseconds = 0;     // both BVHs
};

// Where a ray meets a triangle: which mesh (its index in the list given to the constructor) and which
// triangle of it (its number in that mesh's index list), at ray parameter t.
struct RayHit {
    static constexpr std::uint32_t kNone = 0xffffffffu;
    std::uint32_t mesh = kNone;
    std::uint32_t triangle = kNone;
    float t = 0;
    bool hit() const { return mesh != kNone; }
};

class RayScene {
  public:
    // Builds one BVH over the opaque meshes and one over the others (robust mode: rays through a shared
    // edge or vertex never slip between its triangles). Triangles with a non-finite corner are left
    // out (counted in stats), so Embree never sees a NaN.
    explicit RayScene(std::span<const RayMesh> meshes);
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;

    const RaySceneStats& stats() const { return stats_; }
    bool hasTransparent() const;

    // Whether an opaque triangle lies on the segment origin + t·direction, t in (tnear, tfar).
    // A non-finite origin, direction or range, or a coordinate beyond Embree's ±1.844e18, is never traced:
    // it reports "not occluded".
    bool occluded(const vec3& origin, const vec3& direction, float tnear, float tfar) const;
    // Eight such rays at once (an 8-wide Embree packet); lanes outside `lanes` (bit i: lane i) are not
    // traced. Returns the occluded lanes as bits. The lanes come by reference: this function is compiled
    // for baseline x86-64 and called from every copy of the frame's code (render/frame_kernels.h), and
    // a Float8 by value travels in a register with AVX and in memory without.
    unsigned occluded8(const Vec3x8& origin, const Vec3x8& direction, const Float8& tnear, const Float8& tfar,
                       unsigned lanes) const;

    // Camera rays. Facing: the winding of a triangle as the ray sees it decides whether it is culled:
    // cullBack drops triangles whose corners run clockwise seen from the ray's origin side
    // (counter-clockwise is the front, as OpenGL's default), cullFront the others.
    struct Culling {
        bool cullBack = false;
        bool cullFront = false;
    };
    // The nearest opaque triangle on each of up to eight rays (bit i of `lanes`: ray i is traced;
    // the others' hits are left as they are). Rays of one packet are traced together.
    void nearestOpaque8(const glm::dvec3* origins, const glm::dvec3* directions, const double* tnear,
                        const double* tfar, unsigned lanes, Culling culling, RayHit* hits) const;
    // Every see-through triangle on the ray with t in (tnear, tfar), nearest first (ties in mesh, then
    // triangle order); each crossing of a surface once: a triangle met twice, or the triangles of one
    // mesh around an edge or vertex they share, met there at the same t, are listed once (the first).
    void allTransparent(const glm::dvec3& origin, const glm::dvec3& direction, double tnear, double tfar,
                        Culling culling, std::vector<RayHit>& hits) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    RaySceneStats stats_;
};

}  // namespace facet
