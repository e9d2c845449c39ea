#include "raycast/ray_scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include <embree3/rtcore.h>

namespace facet {

namespace {

// How many of `wanted` threads the system would start now (the calling thread counted, so at least 1):
// Embree aborts the process when it cannot start a thread of its pool (std::terminate after its
// error), so under a process limit (ulimit -u) it is asked for no more than the system gives.
int threadsTheSystemGives(int wanted) {
    std::vector<std::thread> probes;
    try {
        while (static_cast<int>(probes.size()) + 1 < wanted)
            probes.emplace_back([] {});
    } catch (const std::system_error&) {
    }
    for (std::thread& probe : probes)
        probe.join();
    return static_cast<int>(probes.size()) + 1;
}

// One Embree device for the process: creating one costs milliseconds and a thread pool.
RTCDevice sharedDevice() {
    static RTCDevice device = [] {
        const int wanted = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
        const int given = threadsTheSystemGives(wanted);
        // Embree's default (nullptr) is one thread per hardware thread, as `wanted`.
        const std::string config = "threads=" + std::to_string(given);
        RTCDevice created = rtcNewDevice(given < wanted ? config.c_str() : nullptr);
        if (!created)
            throw std::runtime_error("Embree could not start: error " +
                                     std::to_string(rtcGetDeviceError(nullptr)));
        rtcSetDeviceErrorFunction(
            created,
            [](void*, RTCError code, const char* message) {
                // Embree reports misuse here (a bad buffer, out of memory); the build or query that caused
                // it then fails, which the callers see as an empty result. Keep the first message.
                static std::once_flag reported;
                std::call_once(reported, [&] {
                    std::fprintf(stderr, "facet: Embree error %d: %s\n", int(code), message ? message : "");
                });
            },
            nullptr);
        return created;
    }();
    return device;
}

// Embree takes a ray only when every coordinate of its origin and direction lies within ±1.844e18
// (FLT_LARGE; RayK::valid in Embree's kernels/common/ray.h, asserted by Debian's build, which aborts on
// any other): beyond that, like NaN and infinity, a ray is never handed over. Eight-lane batches of
// fragments carry dead lanes whose positions are whatever the memory held, sometimes 1e22.
constexpr float kEmbreeLargest = 1.844e18f;
bool traceable(const vec3& v) {
    return std::abs(v.x) <= kEmbreeLargest && std::abs(v.y) <= kEmbreeLargest &&
           std::abs(v.z) <= kEmbreeLargest;  // false for NaN
}

// The extended intersection context of a camera ray: what the filter needs to cull and to collect.
struct FilterContext {
    RTCIntersectContext embree;  // first: Embree hands the filter a pointer to it
    const std::vector<std::vector<vec3>>* corners = nullptr;  // per Embree geometry: three per kept triangle
    RayScene::Culling culling;
    std::vector<RayHit>* collected = nullptr;  // allTransparent: every hit, each rejected to go on
    const std::vector<std::uint32_t>* meshOfGeometry = nullptr;
    const std::vector<std::vector<std::uint32_t>>* triangleOfPrimitive = nullptr;
};

}  // namespace

struct RayScene::Impl {
    RTCScene opaque = nullptr;
    RTCScene transparent = nullptr;
    bool anyTransparent = false;
    // Per geometry of each scene: its mesh and, per primitive, the mesh's triangle number and corners.
    struct Side {
        std::vector<std::uint32_t> meshOfGeometry;
        std::vector<std::vector<std::uint32_t>> triangleOfPrimitive;
        std::vector<std::vector<vec3>> corners;
        std::vector<std::uint32_t> geometryOfMesh;  // per mesh given: its geometry here, or kNone
    };
    Side sides[2];  // 0 opaque, 1 transparent

    ~Impl() {
        if (opaque) rtcReleaseScene(opaque);
        if (transparent) rtcReleaseScene(transparent);
    }
};

namespace {

// The filter of camera rays: drops culled faces; when collecting, records the hit and rejects it so the
// traversal goes on to the next.
void cameraRayFilter(const RTCFilterFunctionNArguments* args) {
    const FilterContext& context = *reinterpret_cast<const FilterContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        const unsigned geometry = RTCHitN_geomID(args->hit, args->N, i);
        const unsigned primitive = RTCHitN_primID(args->hit, args->N, i);
        if (context.culling.cullBack || context.culling.cullFront) {
            const std::vector<vec3>& corners = (*context.corners)[geometry];
            const glm::dvec3 a(corners[3 * primitive]), b(corners[3 * primitive + 1]),
                c(corners[3 * primitive + 2]);
            const glm::dvec3 normal = glm::cross(b - a, c - a);  // counter-clockwise: towards the front
            const glm::dvec3 direction(RTCRayN_dir_x(args->ray, args->N, i),
                                       RTCRayN_dir_y(args->ray, args->N, i),
                                       RTCRayN_dir_z(args->ray, args->N, i));
            const bool front = glm::dot(normal, direction) < 0.0;
            if ((front && context.culling.cullFront) || (!front && context.culling.cullBack)) {
                args->valid[i] = 0;
                continue;
            }
        }
        if (context.collected) {
            context.collected->push_back({(*context.meshOfGeometry)[geometry],
                                          (*context.triangleOfPrimitive)[geometry][primitive],
                                          RTCRayN_tfar(args->ray, args->N, i)});
            args->valid[i] = 0;
        }
    }
}

}  // namespace

RayScene::RayScene(std::span<const RayMesh> meshes) : impl_(std::make_unique<Impl>()) {
    const auto start = std::chrono::steady_clock::now();
    RTCDevice device = sharedDevice();
    impl_->opaque = rtcNewScene(device);
    impl_->transparent = rtcNewScene(device);
    for (RTCScene scene : {impl_->opaque, impl_->transparent}) {
        rtcSetSceneFlags(scene,
                         RTCSceneFlags(RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION));
        rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    }
    for (std::size_t m = 0; m < meshes.size(); ++m) {
        const RayMesh& mesh = meshes[m];
        const std::size_t triangles = mesh.indices.size() / 3;
        stats_.triangles += triangles;
        Impl::Side& side = impl_->sides[mesh.opaque ? 0 : 1];
        std::vector<std::uint32_t> kept;
        std::vector<vec3> corners;
        kept.reserve(triangles);
        corners.reserve(3 * triangles);
        for (std::size_t t = 0; t < triangles; ++t) {
            bool usable = true;
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t index = mesh.indices[3 * t + k];
                if (index >= mesh.positions.size()) {
                    ++stats_.indexOutOfRange;
                    usable = false;
                    break;
                }
                if (!traceable(mesh.positions[index])) {  // NaN, infinite, or beyond Embree's range
                    ++stats_.nonFiniteSkipped;
                    usable = false;
                    break;
                }
            }
            if (!usable) continue;
            kept.push_back(static_cast<std::uint32_t>(t));
            for (int k = 0; k < 3; ++k)
                corners.push_back(mesh.positions[mesh.indices[3 * t + k]]);
        }
        if (kept.empty()) continue;
        // Each kept triangle gets its own three vertices: the BVH sees only finite positions.
        RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), corners.size()));
        auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), kept.size()));
        if (!vertices || !indices) {
            rtcReleaseGeometry(geometry);
            throw std::runtime_error("Embree could not allocate the BVH's buffers (out of memory?)");
        }
        for (std::size_t v = 0; v < corners.size(); ++v) {
            vertices[3 * v] = corners[v].x;
            vertices[3 * v + 1] = corners[v].y;
            vertices[3 * v + 2] = corners[v].z;
            indices[v] = static_cast<unsigned>(v);
        }
        rtcCommitGeometry(geometry);
        const unsigned id = rtcAttachGeometry(mesh.opaque ? impl_->opaque : impl_->transparent, geometry);
        rtcReleaseGeometry(geometry);
        if (side.meshOfGeometry.size() <= id) {
            side.meshOfGeometry.resize(id + 1, RayHit::kNone);
            side.triangleOfPrimitive.resize(id + 1);
            side.corners.resize(id + 1);
        }
        side.meshOfGeometry[id] = static_cast<std::uint32_t>(m);
        side.geometryOfMesh.resize(meshes.size(), RayHit::kNone);
        side.geometryOfMesh[m] = id;
        side.triangleOfPrimitive[id] = std::move(kept);
        side.corners[id] = std::move(corners);
        if (!mesh.opaque) impl_->anyTransparent = true;
    }
    rtcCommitScene(impl_->opaque);
    rtcCommitScene(impl_->transparent);
    stats_.buildMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

RayScene::~RayScene() = default;

bool RayScene::hasTransparent() const {
    return impl_->anyTransparent;
}

bool RayScene::occluded(const vec3& origin, const vec3& direction, float tnear, float tfar) const {
    if (!traceable(origin) || !traceable(direction) || !std::isfinite(tnear) || std::isnan(tfar) ||
        !(tnear <= tfar))
        return false;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    ray.org_x = origin.x;
    ray.org_y = origin.y;
    ray.org_z = origin.z;
    ray.dir_x = direction.x;
    ray.dir_y = direction.y;
    ray.dir_z = direction.z;
    ray.tnear = tnear;
    ray.tfar = tfar;
    ray.mask = 0xffffffffu;
    rtcOccluded1(impl_->opaque, &context, &ray);
    return ray.tfar == -std::numeric_limits<float>::infinity();
}

unsigned RayScene::occluded8(const Vec3x8& origin, const Vec3x8& direction, const Float8& tnear,
                             const Float8& tfar, unsigned lanes) const {
    alignas(32) int valid[8];
    alignas(32) RTCRay8 rays{};
    bool any = false;
    for (int i = 0; i < 8; ++i) {
        const vec3 o(origin.x[i], origin.y[i], origin.z[i]);
        const vec3 d(direction.x[i], direction.y[i], direction.z[i]);
        const bool traced = ((lanes >> i) & 1) && traceable(o) && traceable(d) && std::isfinite(tnear[i]) &&
                            !std::isnan(tfar[i]) && tnear[i] <= tfar[i];
        valid[i] = traced ? -1 : 0;
        any |= traced;
        rays.org_x[i] = traced ? o.x : 0.0f;
        rays.org_y[i] = traced ? o.y : 0.0f;
        rays.org_z[i] = traced ? o.z : 0.0f;
        rays.dir_x[i] = traced ? d.x : 0.0f;
        rays.dir_y[i] = traced ? d.y : 0.0f;
        rays.dir_z[i] = traced ? d.z : 1.0f;
        rays.tnear[i] = traced ? tnear[i] : 0.0f;
        rays.tfar[i] = traced ? tfar[i] : 0.0f;
        rays.mask[i] = 0xffffffffu;
    }
    if (!any) return 0;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcOccluded8(valid, impl_->opaque, &context, &rays);
    unsigned occludedLanes = 0;
    for (int i = 0; i < 8; ++i)
        if (valid[i] && rays.tfar[i] == -std::numeric_limits<float>::infinity()) occludedLanes |= 1u << i;
    return occludedLanes;
}

void RayScene::nearestOpaque8(const glm::dvec3* origins, const glm::dvec3* directions, const double* tnear,
                              const double* tfar, unsigned lanes, Culling culling, RayHit* hits) const {
    alignas(32) int valid[8];
    alignas(32) RTCRayHit8 rays{};
    for (int i = 0; i < 8; ++i) {
        // A ray with a non-finite origin, direction or range is never handed to Embree: it meets nothing.
        const bool traced = ((lanes >> i) & 1) && traceable(vec3(origins[i])) &&
                            traceable(vec3(directions[i])) && std::isfinite(float(tnear[i])) &&
                            !std::isnan(tfar[i]) && tnear[i] <= tfar[i];
        valid[i] = traced ? -1 : 0;
        rays.ray.org_x[i] = traced ? float(origins[i].x) : 0.0f;
        rays.ray.org_y[i] = traced ? float(origins[i].y) : 0.0f;
        rays.ray.org_z[i] = traced ? float(origins[i].z) : 0.0f;
        rays.ray.dir_x[i] = traced ? float(directions[i].x) : 0.0f;
        rays.ray.dir_y[i] = traced ? float(directions[i].y) : 0.0f;
        rays.ray.dir_z[i] = traced ? float(directions[i].z) : 1.0f;
        rays.ray.tnear[i] = traced ? float(tnear[i]) : 0.0f;
        rays.ray.tfar[i] = traced ? float(tfar[i]) : 0.0f;
        rays.ray.mask[i] = 0xffffffffu;
        rays.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    }
    FilterContext context;
    rtcInitIntersectContext(&context.embree);
    const Impl::Side& side = impl_->sides[0];
    if (culling.cullBack || culling.cullFront) {
        context.embree.filter = cameraRayFilter;
        context.corners = &side.corners;
        context.culling = culling;
    }
    rtcIntersect8(valid, impl_->opaque, &context.embree, &rays);
    for (int i = 0; i < 8; ++i) {
        if (!((lanes >> i) & 1)) continue;
        if (!valid[i]) {
            hits[i] = RayHit{};
            continue;
        }
        const unsigned geometry = rays.hit.geomID[i];
        if (geometry == RTC_INVALID_GEOMETRY_ID) {
            hits[i] = RayHit{};
            continue;
        }
        hits[i] = {side.meshOfGeometry[geometry], side.triangleOfPrimitive[geometry][rays.hit.primID[i]],
                   rays.ray.tfar[i]};
    }
}

void RayScene::allTransparent(const glm::dvec3& origin, const glm::dvec3& direction, double tnear,
                              double tfar, Culling culling, std::vector<RayHit>& hits) const {
    hits.clear();
    if (!impl_->anyTransparent || !traceable(vec3(origin)) || !traceable(vec3(direction)) || !(tnear <= tfar))
        return;
    const Impl::Side& side = impl_->sides[1];
    FilterContext context;
    rtcInitIntersectContext(&context.embree);
    context.embree.filter = cameraRayFilter;
    context.corners = &side.corners;
    context.culling = culling;
    context.collected = &hits;
    context.meshOfGeometry = &side.meshOfGeometry;
    context.triangleOfPrimitive = &side.triangleOfPrimitive;
    RTCRayHit ray{};
    ray.ray.org_x = float(origin.x);
    ray.ray.org_y = float(origin.y);
    ray.ray.org_z = float(origin.z);
    ray.ray.dir_x = float(direction.x);
    ray.ray.dir_y = float(direction.y);
    ray.ray.dir_z = float(direction.z);
    ray.ray.tnear = float(tnear);
    ray.ray.tfar = float(tfar);
    ray.ray.mask = 0xffffffffu;
    ray.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->transparent, &context.embree, &ray);
    std::sort(hits.begin(), hits.end(), [](const RayHit& a, const RayHit& b) {
        if (a.t != b.t) return a.t < b.t;
        if (a.mesh != b.mesh) return a.mesh < b.mesh;
        return a.triangle < b.triangle;
    });
    // One crossing of a surface is listed once: a triangle met twice (a high-quality BVH may hold it in
    // two leaves), and the triangles of one mesh met at the same t through a corner they share (a ray
    // through a shared edge or vertex: robust mode reports every triangle around it), which would
    // otherwise blend one pane twice along its edges. Same t: within a few float ulps, as each triangle's
    // t comes from its own plane.
    const auto cornersOf = [&](const RayHit& hit) {
        const std::uint32_t geometry = side.geometryOfMesh[hit.mesh];
        const std::vector<std::uint32_t>& triangles = side.triangleOfPrimitive[geometry];
        const auto primitive = static_cast<std::size_t>(
            std::lower_bound(triangles.begin(), triangles.end(), hit.triangle) - triangles.begin());
        return &side.corners[geometry][3 * primitive];
    };
    const auto sameCrossing = [&](const RayHit& a, const RayHit& b) {
        if (a.mesh != b.mesh) return false;
        if (a.triangle == b.triangle) return true;
        const vec3* p = cornersOf(a);
        const vec3* q = cornersOf(b);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                if (p[i] == q[j]) return true;
        return false;
    };
    std::size_t kept = 0;
    for (std::size_t i = 0; i < hits.size(); ++i) {
        bool duplicate = false;
        // Sorted by t: the hits at about the same t are the last ones kept.
        const float sameT = 4.0f * std::numeric_limits<float>::epsilon() * std::abs(hits[i].t);
        for (std::size_t k = kept; k-- > 0 && hits[i].t - hits[k].t <= sameT;)
            if (sameCrossing(hits[k], hits[i])) {
                duplicate = true;
                break;
            }
        if (!duplicate) hits[kept++] = hits[i];
    }
    hits.resize(kept);
}

}  // namespace facet
