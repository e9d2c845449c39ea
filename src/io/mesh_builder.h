// Welding and normals: the OBJ's polygons fan-triangulated, corners welded on their index triple, and
// normals computed where the file has none, smoothing only faces within the crease angle (MeshBuilder
// below says how and what it costs). Internal to the OBJ importer, which alone includes it.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "io/obj_import.h"
#include "io/obj_scan.h"
#include "scene/mesh.h"

namespace facet::obj {

constexpr std::uint32_t kNoVertex = std::numeric_limits<std::uint32_t>::max();

struct CornerKey {
    std::int32_t position, texcoord, normal;  // ObjCorner indices, -1 when absent
    bool operator==(const CornerKey&) const = default;
};

struct CornerKeyHash {
    std::size_t operator()(const CornerKey& k) const noexcept {
        std::uint64_t h = std::uint32_t(k.position);
        h = (h * 0x9E3779B97F4A7C15ull) ^ std::uint32_t(k.texcoord);
        h = (h * 0xC2B2AE3D27D4EB4Full) ^ std::uint32_t(k.normal);
        // splitmix64's finaliser: neighbouring indices must not share buckets.
        h ^= h >> 30;
        h *= 0xBF58476D1CE4E5B9ull;
        h ^= h >> 27;
        h *= 0x94D049BB133111EBull;
        h ^= h >> 31;
        return static_cast<std::size_t>(h);
    }
};

// The base vertex of each (position, texcoord, normal) triple seen: an open-addressing table with linear
// probing, its entries in one array: std::unordered_map allocates a node per distinct corner, which made
// welding the largest part of importing a large model. Which vertex a triple gets is decided by the
// builder (the order corners are first seen), never by the table.
class CornerWeldTable {
  public:
    explicit CornerWeldTable(std::size_t expectedKeys = 0) { rehash(std::bit_ceil(expectedKeys * 2 + 16)); }

    // The value slot of `key`, inserted with kNoVertex when new. Valid until the next call.
    std::uint32_t& slotFor(const CornerKey& key) {
        if ((size_ + 1) * 2 > entries_.size()) rehash(entries_.size() * 2);  // load factor at most 1/2
        const std::size_t mask = entries_.size() - 1;
        for (std::size_t i = CornerKeyHash{}(key)&mask;; i = (i + 1) & mask) {
            Entry& entry = entries_[i];
            if (entry.key.position == kEmpty) {
                entry.key = key;
                entry.value = kNoVertex;
                ++size_;
                return entry.value;
            }
            if (entry.key == key) return entry.value;
        }
    }

    std::size_t size() const { return size_; }

  private:
    static constexpr std::int32_t kEmpty = -1;  // no position index is negative once resolved
    struct Entry {
        CornerKey key{kEmpty, 0, 0};
        std::uint32_t value = kNoVertex;
    };

    void rehash(std::size_t capacity) {
        std::vector<Entry> old(capacity);
        old.swap(entries_);
        const std::size_t mask = entries_.size() - 1;
        for (const Entry& entry : old) {
            if (entry.key.position == kEmpty) continue;
            std::size_t i = CornerKeyHash{}(entry.key) & mask;
            while (entries_[i].key.position != kEmpty)
                i = (i + 1) & mask;
            entries_[i] = entry;
        }
    }

    std::vector<Entry> entries_;
    std::size_t size_ = 0;
};

// Builds the mesh in two steps. addPolygon fan-triangulates and welds corners on their (position,
// normal, texcoord) index triple into "base" vertices, and hands out corner ids, not vertex indices.
// finishNormals then gives each base vertex without a file normal its computed normal, one per
// smoothing group of the faces at its position: a base vertex whose corners fall into several groups
// is split, one vertex per group. Vertices are numbered in the order their first corner was added,
// so with nothing split (crease angle 180) the output is the plain welded mesh.
//
// The crease rule: a corner's normal is the normalised sum of the weights of the faces around its
// position whose unit normal is within the crease angle of its own face's. A face is the file's
// polygon: its vector area is the sum of its fan triangles' cross products, its direction that,
// normalised. A face's weight at one of its positions is, by VertexNormals: its whole vector area
// (polygon-area, the default), the cross products of its fan triangles that hold the position
// (triangle-area), or its unit normal times its interior angle there (angle). Faces count whether or
// not their corners have file normals; the face itself always counts.
//
// Cost. Only the faces at one position are compared, never all faces. With k faces at a position the
// exact rule compares every pair, O(k²) dot products, giving each face a 64-bit mask of the faces its
// corners' sum includes; corners with equal masks share a vertex. That is done while k <= kExactFaces
// (64): at most 32 dot products per (face, position) pair over the mesh, typically k ~ 6, so O(n) in
// the faces. At 180° every position is one group, summed in O(k). A crowded position (a fan apex, a
// pole with thousands of faces) below 180° is clustered greedily instead: in file order each face
// joins the earliest cluster whose first face is within the crease angle of it, or starts a new one;
// all faces of a cluster share one sum and vertex. A hash grid over the clusters' unit normals, with
// cells as wide as the chord of the crease angle, finds the candidates in the 27 cells around a
// normal, so each face costs O(1) (at most a few clusters fit in a cell, as their first faces are more
// than the crease angle apart): O(k) per crowded position. That differs from the exact rule only where
// "within the crease angle" is not transitive.
class MeshBuilder {
  public:
    MeshBuilder(const ObjGeometry& geometry, std::size_t cornerCount, float creaseAngleDegrees,
                VertexNormals weighting = VertexNormals::PolygonArea)
        : geometry_(geometry),
          weighting_(weighting),
          smoothAll_(creaseAngleDegrees >= 180.0f),
          creaseCos_(std::cos(double(creaseAngleDegrees) * (std::numbers::pi / 180.0)) - kCosTolerance),
          cellSize_(2.0 * std::sin(double(creaseAngleDegrees) * (std::numbers::pi / 360.0)) * 1.0001 + 1e-5) {
        const std::size_t positionCount = geometry.positions.size() / 3;
        plainVertex_.assign(positionCount, kNoVertex);
        welded_ = CornerWeldTable(cornerCount / 4);
        baseVertices_.reserve(cornerCount / 3 + 16);
        cornerVertex_.reserve(cornerCount);  // exact for triangles; polygons have more
        cornerIncidence_.reserve(cornerCount);
        incidencePosition_.reserve(cornerCount);
        incidenceFace_.reserve(cornerCount);

        // File normals, normalised once; a zero-length one counts as absent.
        const std::size_t normalCount = geometry.normals.size() / 3;
        fileNormals_.resize(normalCount);
        usableNormal_.assign(normalCount, false);
        for (std::size_t i = 0; i < normalCount; ++i) {
            const glm::dvec3 n(geometry.normals[3 * i], geometry.normals[3 * i + 1],
                               geometry.normals[3 * i + 2]);
            const double length = glm::length(n);
            if (length > 0.0 && std::isfinite(length)) {
                fileNormals_[i] = glm::vec3(n / length);
                usableNormal_[i] = true;
            }
        }
    }

    glm::dvec3 position(std::size_t index) const {
        const std::size_t i = index * 3;
        return {geometry_.positions[i], geometry_.positions[i + 1], geometry_.positions[i + 2]};
    }

    // Adds one polygon: fan-triangulated, degenerate triangles counted, the rest into `out` as corner
    // ids (vertexOf maps them to vertices after finishNormals). Returns the number of triangles kept.
    std::size_t addPolygon(const ObjCorner* corners, std::size_t count, std::vector<std::uint32_t>& out,
                           std::size_t& degenerate) {
        kept_.clear();
        keptCross_.clear();
        glm::dvec3 area(0.0);  // the polygon's vector area ×2: the sum of its fan triangles' cross products
        const glm::dvec3 p0 = position(std::size_t(corners[0].position));
        for (std::size_t i = 1; i + 1 < count; ++i) {
            const ObjCorner &a = corners[0], &b = corners[i], &c = corners[i + 1];
            if (a.position == b.position || b.position == c.position || a.position == c.position) {
                ++degenerate;
                continue;
            }
            // Doubles: a float cross product of 1e30-sized coordinates would overflow.
            const glm::dvec3 cross =
                glm::cross(position(std::size_t(b.position)) - p0, position(std::size_t(c.position)) - p0);
            if (cross == glm::dvec3(0.0)) {
                ++degenerate;
                continue;
            }
            area += cross;
            kept_.push_back(i);
            if (weighting_ == VertexNormals::TriangleArea) keptCross_.push_back(cross);
        }
        if (kept_.empty()) return 0;

        // Every position of the polygon gets its whole area once, whichever fan triangles it is in, so
        // that a cube's corner normal is the symmetric (1,1,1)/√3: one incidence per distinct position.
        const auto face = static_cast<std::uint32_t>(faceAreas_.size());
        faceAreas_.push_back(area);
        polygonIncidence_.resize(count);
        for (std::size_t i = 0; i < count; ++i) {
            std::size_t j = 0;
            while (corners[j].position != corners[i].position)
                ++j;
            if (j < i) {
                polygonIncidence_[i] = polygonIncidence_[j];
                continue;
            }
            polygonIncidence_[i] = static_cast<std::uint32_t>(incidenceFace_.size());
            incidencePosition_.push_back(static_cast<std::uint32_t>(corners[i].position));
            incidenceFace_.push_back(face);
        }
        if (weighting_ != VertexNormals::PolygonArea) addCornerWeights(corners, count, area);
        for (const std::size_t second : kept_) {
            for (const std::size_t c : {std::size_t(0), second, second + 1}) {
                out.push_back(static_cast<std::uint32_t>(cornerVertex_.size()));
                cornerVertex_.push_back(baseVertexFor(corners[c]));
                cornerIncidence_.push_back(polygonIncidence_[c]);
            }
        }
        return kept_.size();
    }

    // Groups the faces around each position that needs a computed normal, then numbers the final
    // vertices: a base vertex per smoothing group of its corners. Counts the computed normals and the
    // vertices split off by the crease angle.
    void finishNormals(std::size_t& normalsComputed, std::size_t& creaseSplits) {
        const std::vector<std::uint32_t> groupOf = groupFaces();

        // Final vertices, numbered by first corner. A base vertex's first group keeps it; further
        // groups (rare, at hard edges) are found through a map.
        const std::size_t baseCount = baseVertices_.size();
        std::vector<std::uint32_t> firstVertex(baseCount, kNoVertex), firstGroup(baseCount, kNoGroup);
        std::unordered_map<std::uint64_t, std::uint32_t> split;
        vertices_.reserve(baseCount);
        normalsComputed = creaseSplits = 0;
        for (std::size_t corner = 0; corner < cornerVertex_.size(); ++corner) {
            const std::uint32_t base = cornerVertex_[corner];
            const std::uint32_t group = computedNormal_[base] ? groupOf[cornerIncidence_[corner]] : kNoGroup;
            std::uint32_t* slot = &firstVertex[base];
            if (*slot != kNoVertex && firstGroup[base] != group) {
                slot = &split.try_emplace((std::uint64_t(base) << 32) | group, kNoVertex).first->second;
                if (*slot == kNoVertex) ++creaseSplits;
            }
            if (*slot == kNoVertex) {
                if (firstVertex[base] == kNoVertex) firstGroup[base] = group;
                *slot = static_cast<std::uint32_t>(vertices_.size());
                MeshVertex vertex = baseVertices_[base];
                if (group != kNoGroup) {
                    // Opposite faces can cancel (a two-sided sheet): then this corner's triangle's normal.
                    vertex.normal = groupNormals_[group] != glm::vec3(0.0f) ? groupNormals_[group]
                                                                            : triangleNormal(corner / 3);
                    ++normalsComputed;
                }
                vertices_.push_back(vertex);
            }
            cornerVertex_[corner] = *slot;
        }
    }

    // Records how the normals at trace->positions are made (finishNormals fills trace->groups).
    void trace(VertexNormalTrace* trace) {
        trace_ = trace;
        trace->weighting = weighting_;
        trace->creaseCosine = creaseCos_;
        trace->smoothAll = smoothAll_;
    }

    // The vertex of a corner id that addPolygon put in `out`; valid after finishNormals.
    std::uint32_t vertexOf(std::uint32_t corner) const { return cornerVertex_[corner]; }
    std::vector<MeshVertex> takeVertices() { return std::move(vertices_); }
    bool hasTexcoords() const { return hasTexcoords_; }

  private:
    // Faces whose normals' cosine falls short of the crease angle's by at most this still count as
    // within it (an angle of about 1e-6 radians at 0°): rounding must not split coplanar faces.
    static constexpr double kCosTolerance = 1e-12;
    static constexpr std::size_t kExactFaces = 64;  // the faces a 64-bit mask holds
    static constexpr std::uint32_t kNoGroup = std::numeric_limits<std::uint32_t>::max();

    VertexNormalTrace* trace_ = nullptr;   // the step mode's record, usually none
    bool recording_ = false;               // the position being grouped is one trace_ asks for
    std::vector<std::size_t> recordedAt_;  // groupExactly, recording: face j's group in trace_->groups

    // The weights of the polygon just added at its positions (its incidences, the last added), under
    // the triangle-area and angle rules (polygon-area needs none: it is the face's area).
    void addCornerWeights(const ObjCorner* corners, std::size_t count, const glm::dvec3& area) {
        incidenceWeight_.resize(incidenceFace_.size(), glm::dvec3(0.0));
        if (weighting_ == VertexNormals::TriangleArea) {
            // Each kept fan triangle (0, i, i + 1) adds its cross product at its three positions.
            for (std::size_t t = 0; t < kept_.size(); ++t) {
                for (const std::size_t c : {std::size_t(0), kept_[t], kept_[t] + 1})
                    incidenceWeight_[polygonIncidence_[c]] += keptCross_[t];
            }
            return;
        }
        // Angle: n̂·θ at each corner, θ the angle between its two edges (atan2(|e1×e2|, e1·e2), in
        // [0, π]), reflex (2π − θ) where e1×e2 points against the polygon's normal. A repeated position
        // sums its corners' angles.
        const glm::dvec3 unit = unitNormal(area);
        for (std::size_t i = 0; i < count; ++i) {
            const glm::dvec3 p = position(std::size_t(corners[i].position));
            const glm::dvec3 toNext = position(std::size_t(corners[(i + 1) % count].position)) - p;
            const glm::dvec3 toPrevious =
                position(std::size_t(corners[(i + count - 1) % count].position)) - p;
            const glm::dvec3 cross = glm::cross(toNext, toPrevious);
            double angle = std::atan2(glm::length(cross), glm::dot(toNext, toPrevious));
            if (glm::dot(cross, unit) < 0.0) angle = 2.0 * std::numbers::pi - angle;
            incidenceWeight_[polygonIncidence_[i]] += unit * angle;
        }
    }

    // What a face adds to the normals at one of its positions (incidence i): see the class comment.
    const glm::dvec3& weightOf(std::uint32_t incidence) const {
        return weighting_ == VertexNormals::PolygonArea ? faceAreas_[incidenceFace_[incidence]]
                                                        : incidenceWeight_[incidence];
    }

    // A face's unit normal, or zero when its vector area is zero (opposite halves cancelling).
    static glm::dvec3 unitNormal(const glm::dvec3& area) {
        const double length = glm::length(area);
        return length > 0.0 && std::isfinite(length) ? area / length : glm::dvec3(0.0);
    }

    // Whether faces with unit normals `a` and `b` (zero: no direction) are smoothed together. A face
    // without a direction is smoothed with others only at 180°.
    bool within(const glm::dvec3& a, const glm::dvec3& b) const {
        return smoothAll_ || (a != glm::dvec3(0.0) && b != glm::dvec3(0.0) && glm::dot(a, b) >= creaseCos_);
    }

    // The normal of kept triangle t (corners 3t, 3t+1, 3t+2 as added), as its faceNormal was computed.
    glm::vec3 triangleNormal(std::size_t t) const {
        const auto at = [&](std::size_t corner) {
            return position(incidencePosition_[cornerIncidence_[corner]]);
        };
        const glm::dvec3 p0 = at(3 * t);
        return glm::vec3(glm::normalize(glm::cross(at(3 * t + 1) - p0, at(3 * t + 2) - p0)));
    }

    // Per incidence (face at a position) its smoothing group, an index into groupNormals_; kNoGroup
    // at positions where every vertex has a file normal.
    std::vector<std::uint32_t> groupFaces() {
        // Incidences by position (counting sort; stable, so each position's faces stay in file order),
        // only at positions with a computed normal.
        const std::size_t positionCount = plainVertex_.size();
        std::vector<char> needed(positionCount, 0);
        for (std::size_t v = 0; v < baseVertices_.size(); ++v) {
            if (computedNormal_[v]) needed[basePosition_[v]] = 1;
        }
        std::vector<std::uint32_t> start(positionCount + 1, 0);
        for (const std::uint32_t p : incidencePosition_) {
            if (needed[p]) ++start[p + 1];
        }
        for (std::size_t p = 0; p < positionCount; ++p)
            start[p + 1] += start[p];
        std::vector<std::uint32_t> byPosition(start[positionCount]);
        {
            std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
            for (std::size_t i = 0; i < incidencePosition_.size(); ++i) {
                const std::uint32_t p = incidencePosition_[i];
                if (needed[p]) byPosition[next[p]++] = static_cast<std::uint32_t>(i);
            }
        }

        std::vector<std::uint32_t> groupOf(incidencePosition_.size(), kNoGroup);
        groupNormals_.clear();
        for (std::size_t p = 0; p < positionCount; ++p) {
            const std::uint32_t* incidences = byPosition.data() + start[p];
            const std::size_t k = start[p + 1] - start[p];
            if (k == 0) continue;
            recording_ = trace_ && traced(p);
            if (smoothAll_) {
                smoothTogether(incidences, k, groupOf);
                continue;
            }
            units_.resize(k);
            for (std::size_t j = 0; j < k; ++j)
                units_[j] = unitNormal(faceAreas_[incidenceFace_[incidences[j]]]);
            if (k <= kExactFaces)
                groupExactly(incidences, k, groupOf);
            else
                groupByClusters(incidences, k, groupOf);
        }
        return groupOf;
    }

    // Crease angle 180: all k faces at a position in one group, summed in file order.
    void smoothTogether(const std::uint32_t* incidences, std::size_t k, std::vector<std::uint32_t>& groupOf) {
        glm::dvec3 sum(0.0);
        for (std::size_t j = 0; j < k; ++j)
            sum += weightOf(incidences[j]);
        const auto group = static_cast<std::uint32_t>(groupNormals_.size());
        groupNormals_.push_back(normalOfSum(sum));
        for (std::size_t j = 0; j < k; ++j)
            groupOf[incidences[j]] = group;
        if (recording_) {
            units_.resize(k);
            for (std::size_t j = 0; j < k; ++j)
                units_[j] = unitNormal(faceAreas_[incidenceFace_[incidences[j]]]);
            record(
                incidences, k, 0, [](std::size_t) { return true; }, sum, groupNormals_.back(), false);
        }
    }

    // The exact rule for k <= 64 faces at a position: one group per distinct set of faces summed.
    void groupExactly(const std::uint32_t* incidences, std::size_t k, std::vector<std::uint32_t>& groupOf) {
        masks_.assign(k, 0);
        for (std::size_t j = 0; j < k; ++j) {
            masks_[j] |= std::uint64_t(1) << j;
            for (std::size_t l = j + 1; l < k; ++l) {
                if (within(units_[j], units_[l])) {
                    masks_[j] |= std::uint64_t(1) << l;
                    masks_[l] |= std::uint64_t(1) << j;
                }
            }
        }
        for (std::size_t j = 0; j < k; ++j) {
            std::size_t same = 0;
            while (masks_[same] != masks_[j])
                ++same;
            if (same < j) {
                groupOf[incidences[j]] = groupOf[incidences[same]];
                // Recorded again from face j's side: the same faces and sum, j's cosines.
                if (recording_)
                    record(
                        incidences, k, j, [&](std::size_t l) { return ((masks_[j] >> l) & 1) != 0; },
                        trace_->groups[recordedAt_[same]].sum, groupNormals_[groupOf[incidences[j]]], false);
                continue;
            }
            glm::dvec3 sum(0.0);  // in file order, the order the faces were added in
            for (std::size_t l = 0; l < k; ++l) {
                if ((masks_[j] >> l) & 1) sum += weightOf(incidences[l]);
            }
            groupOf[incidences[j]] = static_cast<std::uint32_t>(groupNormals_.size());
            groupNormals_.push_back(normalOfSum(sum));
            if (recording_) {
                recordedAt_.resize(k);
                recordedAt_[j] = trace_->groups.size();
                record(
                    incidences, k, j, [&](std::size_t l) { return ((masks_[j] >> l) & 1) != 0; }, sum,
                    groupNormals_.back(), false);
            }
        }
    }

    // Greedy clusters for a crowded position (see the class comment).
    void groupByClusters(const std::uint32_t* incidences, std::size_t k,
                         std::vector<std::uint32_t>& groupOf) {
        struct Cluster {
            glm::dvec3 unit;  // its first face's
            glm::dvec3 sum;
        };
        std::vector<Cluster> clusters;
        std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;  // cell → clusters starting in it
        const auto cellOf = [&](const glm::dvec3& n) {
            // |n| <= 1 and cellSize_ >= 1e-5: each coordinate's cell fits 21 bits after the offset.
            return glm::ivec3(glm::floor(n / cellSize_)) + glm::ivec3(1 << 20);
        };
        const auto key = [](glm::ivec3 c) {
            return std::uint64_t(c.x) << 42 | std::uint64_t(c.y) << 21 | std::uint64_t(c.z);
        };
        std::vector<std::uint32_t> clusterOf(k);
        for (std::size_t j = 0; j < k; ++j) {
            const glm::dvec3& n = units_[j];
            std::uint32_t found = kNoGroup;
            if (n != glm::dvec3(0.0)) {
                const glm::ivec3 cell = cellOf(n);
                for (int dx = -1; dx <= 1; ++dx) {
                    for (int dy = -1; dy <= 1; ++dy) {
                        for (int dz = -1; dz <= 1; ++dz) {
                            const auto it = grid.find(key(cell + glm::ivec3(dx, dy, dz)));
                            if (it == grid.end()) continue;
                            for (const std::uint32_t c : it->second) {
                                if (c < found && within(clusters[c].unit, n)) found = c;
                            }
                        }
                    }
                }
            }
            if (found == kNoGroup) {
                found = static_cast<std::uint32_t>(clusters.size());
                clusters.push_back({n, glm::dvec3(0.0)});
                if (n != glm::dvec3(0.0)) grid[key(cellOf(n))].push_back(found);
            }
            clusters[found].sum += weightOf(incidences[j]);
            clusterOf[j] = found;
        }
        const auto firstGroup = static_cast<std::uint32_t>(groupNormals_.size());
        for (const Cluster& cluster : clusters)
            groupNormals_.push_back(normalOfSum(cluster.sum));
        if (recording_) {
            for (std::uint32_t c = 0; c < clusters.size(); ++c) {
                const auto own = static_cast<std::size_t>(std::find(clusterOf.begin(), clusterOf.end(), c) -
                                                          clusterOf.begin());
                record(
                    incidences, k, own, [&](std::size_t l) { return clusterOf[l] == c; }, clusters[c].sum,
                    groupNormals_[firstGroup + c], true);
            }
        }
        for (std::size_t j = 0; j < k; ++j)
            groupOf[incidences[j]] = firstGroup + clusterOf[j];
    }

    // The step mode's record of a corner's file values (VertexNormalTrace::FileCorner).
    void recordFileCorner(const ObjCorner& corner) const {
        VertexNormalTrace::FileCorner c;
        c.positionIndex = corner.position;
        c.position = glm::vec3(position(static_cast<std::size_t>(corner.position)));
        if (corner.texcoord >= 0) {
            const std::size_t t = static_cast<std::size_t>(corner.texcoord) * 2;
            c.texcoordIndex = corner.texcoord;
            c.uv = glm::vec2(geometry_.texcoords[t], geometry_.texcoords[t + 1]);
        }
        if (corner.normal >= 0) {
            const std::size_t n = static_cast<std::size_t>(corner.normal);
            c.normalIndex = corner.normal;
            c.normal = glm::vec3(geometry_.normals[3 * n], geometry_.normals[3 * n + 1],
                                 geometry_.normals[3 * n + 2]);
            c.unitNormal = usableNormal_[n] ? fileNormals_[n] : glm::vec3(0.0f);
        }
        trace_->fileCorners.push_back(c);
    }

    // Whether position p is one trace_ asks for.
    bool traced(std::size_t p) const {
        if (trace_->all) return true;
        const glm::vec3 at(position(p));
        return std::find(trace_->positions.begin(), trace_->positions.end(), at) != trace_->positions.end();
    }

    // Records a group at a traced position: the k faces there (units_ holds their unit normals), `own`
    // the one whose neighbourhood it is, `in(l)` whether face l is summed, the sum and normal as computed.
    template <class In>
    void record(const std::uint32_t* incidences, std::size_t k, std::size_t own, In in, const glm::dvec3& sum,
                const glm::vec3& normal, bool clustered) {
        VertexNormalTrace::Group group;
        group.position = glm::vec3(position(incidencePosition_[incidences[own]]));
        group.ownFace = incidenceFace_[incidences[own]];
        group.sum = sum;
        group.normal = normal;
        group.clustered = clustered;
        for (std::size_t l = 0; l < k; ++l)
            group.faces.push_back({incidenceFace_[incidences[l]], units_[l], weightOf(incidences[l]),
                                   glm::dot(units_[own], units_[l]), in(l)});
        trace_->groups.push_back(std::move(group));
    }

    // A group's normal: its normalised sum, or zero when the faces cancel.
    static glm::vec3 normalOfSum(const glm::dvec3& sum) {
        const double length = glm::length(sum);
        return length > 0.0 && std::isfinite(length) ? glm::vec3(sum / length) : glm::vec3(0.0f);
    }

    std::uint32_t baseVertexFor(const ObjCorner& corner) {
        int normal = corner.normal;
        if (normal >= 0 && !usableNormal_[static_cast<std::size_t>(normal)]) normal = -1;
        const int texcoord = corner.texcoord;
        const std::size_t positionIndex = static_cast<std::size_t>(corner.position);

        // Most meshes have positions only: an array beats hashing there.
        std::uint32_t* slot;
        if (texcoord < 0 && normal < 0) {
            slot = &plainVertex_[positionIndex];
        } else {
            slot = &welded_.slotFor(CornerKey{corner.position, texcoord, normal});
        }
        if (*slot != kNoVertex) return *slot;
        if (trace_ && (trace_->fileCornersOfAll || traced(positionIndex))) recordFileCorner(corner);

        MeshVertex vertex;
        vertex.position = glm::vec3(position(positionIndex));
        vertex.uv = glm::vec2(0.0f);
        if (texcoord >= 0) {
            const std::size_t t = static_cast<std::size_t>(texcoord) * 2;
            vertex.uv = glm::vec2(geometry_.texcoords[t], geometry_.texcoords[t + 1]);
            hasTexcoords_ = true;
        }
        vertex.normal = normal >= 0 ? fileNormals_[static_cast<std::size_t>(normal)] : glm::vec3(0.0f);
        *slot = static_cast<std::uint32_t>(baseVertices_.size());
        baseVertices_.push_back(vertex);
        basePosition_.push_back(static_cast<std::uint32_t>(positionIndex));
        computedNormal_.push_back(normal < 0);
        return *slot;
    }

    const ObjGeometry& geometry_;
    const VertexNormals weighting_;
    const bool smoothAll_;    // crease angle 180: one group per position
    const double creaseCos_;  // within the crease angle: dot of the unit normals >= this
    const double cellSize_;   // of the cluster grid: the chord of the crease angle, with a margin
    std::vector<glm::vec3> fileNormals_;
    std::vector<bool> usableNormal_;
    std::vector<std::uint32_t> plainVertex_;  // per position: its base vertex without texcoord or normal
    CornerWeldTable welded_;
    std::vector<MeshVertex> baseVertices_;     // welded on the index triple, computed normals still zero
    std::vector<std::uint32_t> basePosition_;  // per base vertex: its position index
    std::vector<bool> computedNormal_;         // per base vertex: no usable file normal
    std::vector<glm::dvec3> faceAreas_;        // per face (kept polygon): its vector area ×2
    std::vector<std::uint32_t> incidencePosition_, incidenceFace_;  // per (face, distinct position of it)
    std::vector<glm::dvec3> incidenceWeight_;     // per incidence: its weight; empty under polygon-area
    std::vector<std::uint32_t> cornerVertex_;     // per corner id: its base vertex; its vertex once finished
    std::vector<std::uint32_t> cornerIncidence_;  // per corner id: its (face, position) incidence
    std::vector<glm::vec3> groupNormals_;         // per smoothing group; zero when its faces cancel
    std::vector<MeshVertex> vertices_;            // the final vertices
    std::vector<std::size_t> kept_;      // scratch: the kept fan triangles (0, i, i + 1) of a polygon
    std::vector<glm::dvec3> keptCross_;  // scratch, triangle-area only: their cross products
    std::vector<std::uint32_t> polygonIncidence_;  // scratch: per polygon corner, its incidence
    std::vector<glm::dvec3> units_;                // scratch: unit normals of the faces at one position
    std::vector<std::uint64_t> masks_;  // scratch: per face at a position, the faces it smooths with
    bool hasTexcoords_ = false;
};

}  // namespace facet::obj
