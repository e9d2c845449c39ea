// The vertex stage: every vertex shaded once, into its own slot, by vertex() or, for a shader that has
// it, by vertexBatch() eight at a time — the last group padded, its padding never written out.
#include "vertex_stage.h"

#include <vector>

#include <gtest/gtest.h>

namespace facet {
namespace {

// position → (x, y, z, 1), varying = a value computed from the index carried in the attributes; the
// batch path counts how many times it ran so the test can see it was used.
struct IndexedShader {
    struct Attributes {
        vec3 position;
        float index;
    };
    struct Varyings {
        float twiceIndex;
        float lane;  // which lane of the batch shaded it (−1: vertex())
    };
    struct Uniforms {
        mutable int batches = 0;
    };
    static VertexOut<Varyings> vertex(const Attributes& in, const Uniforms&) {
        return {vec4(in.position, 1.0f), {2.0f * in.index, -1.0f}};
    }
    static vec4 fragment(const Varyings&, const Uniforms&) { return vec4(1.0f); }
    static void vertexBatch(const Attributes* in, const Uniforms& u, VertexOut<Varyings>* out) {
        ++u.batches;
        for (int lane = 0; lane < kVertexBatch; ++lane)
            out[lane] = {vec4(in[lane].position, 1.0f), {2.0f * in[lane].index, static_cast<float>(lane)}};
    }
};
static_assert(BatchVertexShader<IndexedShader>);

TEST(VertexStage, BatchesOfEightWithAPaddedTailShadeEveryVertexOnce) {
    for (std::size_t count : {1u, 7u, 8u, 9u, 16u, 17u, 100u}) {
        std::vector<IndexedShader::Attributes> vertices(count);
        for (std::size_t i = 0; i < count; ++i)
            vertices[i] = {vec3(0.1f * i, -0.2f * i, 0.5f), static_cast<float>(i)};
        IndexedShader::Uniforms uniforms;
        ShadedVertices out;
        shadeVertices<IndexedShader>(std::span<const IndexedShader::Attributes>(vertices), uniforms, out);
        ASSERT_EQ(out.size(), count);
        EXPECT_EQ(uniforms.batches, static_cast<int>((count + 7) / 8)) << count << " vertices";
        for (std::size_t i = 0; i < count; ++i) {
            EXPECT_EQ(out.positions[i], vec4(0.1f * i, -0.2f * i, 0.5f, 1.0f));
            EXPECT_EQ(out.varyingsOf(i)[0], 2.0f * i);
            EXPECT_EQ(out.varyingsOf(i)[1], static_cast<float>(i % 8)) << "vertex " << i;
        }
    }
}

// A range that starts inside the mesh (as the draw's chunks do) batches from its own start.
TEST(VertexStage, RangesShadeOnlyTheirVertices) {
    std::vector<IndexedShader::Attributes> vertices(30);
    for (std::size_t i = 0; i < vertices.size(); ++i)
        vertices[i] = {vec3(1.0f), static_cast<float>(i)};
    IndexedShader::Uniforms uniforms;
    ShadedVertices out;
    prepareShadedVertices<IndexedShader>(vertices.size(), out);
    std::fill(out.varyings.begin(), out.varyings.end(), -7.0f);
    shadeVertices<IndexedShader>(std::span<const IndexedShader::Attributes>(vertices), uniforms, 10, 21, out);
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        const bool inside = i >= 10 && i < 21;
        EXPECT_EQ(out.varyingsOf(i)[0], inside ? 2.0f * i : -7.0f) << i;
    }
    EXPECT_EQ(uniforms.batches, 2);
}

}  // namespace
}  // namespace facet
