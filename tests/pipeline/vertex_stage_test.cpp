// The vertex stage: every vertex shaded once, into its own slot, by vertex() or, for a shader that has
// it, by vertexBatch() eight at a time — the last group padded, its padding never written out.
#include "vertex_stage.h"

#include <vector>

#include <gtest/gtest.h>

#include "front_end.h"
#include "observer.h"
#include "thread_pool.h"

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

// The vertex stage's window positions, eight at a time and the tail one by one: every vertex inside the
// frustum gets toWindow's, whatever its place in a chunk, on one thread and two (breaks caught: a group
// or the tail left out, a group's positions read at another group's offset).
TEST(VertexStage, WindowPositionsAreToWindowsForEveryVertexInside) {
    for (std::size_t count : {5u, 8u, 13u, 8192u + 21u}) {
        std::vector<IndexedShader::Attributes> vertices(count);
        for (std::size_t i = 0; i < count; ++i) {
            const float t = static_cast<float>(i) / static_cast<float>(count);
            // Every seventh vertex to the right of the frustum.
            vertices[i] = {vec3(i % 7 == 3 ? 1.5f : 2.0f * t - 1.0f, 0.5f - t, t - 0.25f),
                           static_cast<float>(i)};
        }
        DrawState state;
        state.viewport = {3, 4, 640, 480, 0.0f, 1.0f};
        for (const int threads : {1, 2}) {
            ThreadPool pool(threads);
            IndexedShader::Uniforms uniforms;
            ShadedVertices shaded;
            std::vector<WindowVertex> window;
            NullObserver observer;
            constexpr bool kInOrder = false;
            runVertexStage<IndexedShader>(std::span<const IndexedShader::Attributes>(vertices), uniforms,
                                          state, pool, kInOrder, 8192, shaded, window, observer);
            ASSERT_EQ(window.size(), count);
            for (std::size_t i = 0; i < count; ++i) {
                EXPECT_EQ(shaded.outcodes[i], i % 7 == 3 ? kClipRight : 0) << i;
                if (shaded.outcodes[i] != 0) continue;
                const WindowVertex one =
                    toWindow(shaded.positions[i], state.viewport, state.raster.subpixelBits);
                EXPECT_EQ(window[i].xFixed, one.xFixed) << i;
                EXPECT_EQ(window[i].yFixed, one.yFixed) << i;
                EXPECT_EQ(window[i].z, one.z) << i;
                EXPECT_EQ(window[i].invW, one.invW) << i;
            }
        }
    }
}

}  // namespace
}  // namespace facet
