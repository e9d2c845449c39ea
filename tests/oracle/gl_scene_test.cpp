// The scene facet compare hands to OpenGL (oracle/gl_scene.h), built from a prepared scene.
#include "oracle/gl_scene.h"

#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "render/renderer.h"
#include "support/interleaved_quads.h"

namespace facet {
namespace {

using testing_support::interleavedQuadsScene;
using testing_support::opaqueVertexCount;
using testing_support::TempFolder;
using testing_support::writeInterleavedQuads;

// The scene handed to OpenGL keeps each run's compact vertex array, not a copy of its part's whole one:
// its vertices add up to at most the opaque parts' and three per transparent triangle, and each run's
// corners are, in order, those of its part's triangles back to front.
TEST(Render, GlSceneRunsCarryOnlyTheVerticesTheyUse) {
    TempFolder dir;
    const PreparedScene prepared = prepareScene(interleavedQuadsScene(writeInterleavedQuads(dir, 60)));
    const GlScene gl = toGlScene(prepared);
    std::size_t stored = 0;
    std::vector<MeshVertex> drawnCorners;
    for (const GlDraw& draw : gl.draws) {
        stored += draw.vertices.size();
        if (draw.depthWrite) continue;  // opaque
        for (const std::uint32_t index : draw.indices)
            drawnCorners.push_back(draw.vertices.at(index));
    }
    EXPECT_LE(stored, opaqueVertexCount(prepared) + 3 * prepared.transparentTriangles.size());

    FrameMemory keys;
    FrameStats unused;
    planFrame(prepared, TransparencyMode::Sorted, keys, unused);
    TransparencySorter sorter;
    SortStats sortStats;
    std::vector<MeshVertex> sortedCorners;
    for (const std::uint32_t t : sorter.sort(keys.keys, SortAlgorithm::InsertionWithMemory, sortStats)) {
        const TransparentTriangle& triangle = prepared.transparentTriangles[t];
        const PreparedDraw& d = prepared.draws[triangle.draw];
        for (int c = 0; c < 3; ++c)
            sortedCorners.push_back(d.vertices[d.indices[3 * triangle.triangle + c]]);
    }
    ASSERT_EQ(drawnCorners.size(), sortedCorners.size());
    EXPECT_EQ(
        std::memcmp(drawnCorners.data(), sortedCorners.data(), sortedCorners.size() * sizeof(MeshVertex)), 0);
}

}  // namespace
}  // namespace facet
