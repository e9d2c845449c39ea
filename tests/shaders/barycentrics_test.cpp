// Barycentrics for a user shader's fragment part (Fragment::barycentric, GLSL's gl_BaryCoordEXT): a
// shader that declares kBarycentrics and outputs them, drawn by the pipeline, gives at every pixel the λ
// the observer's FragmentEvent reports for it, through big triangles (rows shaded whole), small ones
// (the queue, mixing triangles in a batch) and clipped ones; the one-lane entry passes FragmentInput's;
// shaders that do not ask get nothing written.
#include "float_bits.h"
#include "shaders/shader_module.h"

#include <bit>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

namespace facet {
namespace {

struct ShowBarycentrics {
    struct Uniforms : SceneUniforms {};
    template <class F>
    struct VaryingsT {
        LaneVec3<F> normal;
    };
    static constexpr VaryingName kVaryings[] = {{"N", 3}};
    static constexpr bool kBarycentrics = true;
    static VertexOut<VaryingsT<float>> vertex(const MeshVertex& in, const Uniforms& u) {
        return {u.clipFromObject * vec4(in.position, 1.0f), {in.normal}};
    }
    template <class F>
    static LaneVec4<F> fragment(const VaryingsT<F>&, const Uniforms&, Fragment<F>& gl) {
        return withAlpha(gl.barycentric, lanes<F>(1.0f));
    }
};

// The same without kBarycentrics.
struct NoBarycentrics : ShowBarycentrics {
    static constexpr bool kBarycentrics = false;
};

using Shown = user_shader::Adapter<ShowBarycentrics>;
static_assert(wantsBarycentrics<Shown>());
static_assert(!wantsBarycentrics<user_shader::Adapter<NoBarycentrics>>());
static_assert(!wantsBarycentrics<SurfaceShader<ShadingFrequency::Phong>>());
static_assert(!wantsBarycentrics<SurfaceShader<ShadingFrequency::Gouraud>>());

// The last written fragment of each pixel, as the observer saw it.
struct LastWritten : NullObserver {
    static constexpr bool enabled = true;
    std::map<std::pair<int, int>, FragmentEvent> at;
    int written = 0;
    void onFragment(const FragmentEvent& e) {
        if (e.fate != FragmentFate::Written) return;
        at[{e.x, e.y}] = e;
        ++written;
    }
};

using testing_shaders::bits;

// A frame of big, small and near-clipped triangles in perspective.
std::vector<MeshVertex> scene() {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), depth(-4.0f, -1.0f);
    std::vector<MeshVertex> v;
    auto add = [&](vec3 a, vec3 b, vec3 c) {
        for (const vec3& p : {a, b, c})
            v.push_back({p, vec3(0.0f, 0.0f, 1.0f), vec2(0.0f)});
    };
    add(vec3(-2.0f, -1.5f, -3.0f), vec3(2.0f, -1.0f, -3.5f), vec3(0.0f, 1.8f, -2.5f));  // big
    for (int i = 0; i < 40; ++i) {                                                      // small
        const vec3 c(u(rng) * 1.5f, u(rng) * 1.2f, depth(rng));
        add(c, c + vec3(0.08f * u(rng), 0.1f, 0.0f), c + vec3(0.1f, 0.05f * u(rng), 0.02f));
    }
    add(vec3(-0.5f, -0.5f, 0.5f), vec3(0.8f, -0.4f, -2.0f), vec3(0.0f, 0.7f, -1.5f));  // crosses near
    return v;
}

// What the fragment part read in gl.barycentric is, at every written fragment, the λ the observer
// reports (bit for bit: λ0 computed as (1 − λ1) − λ2 on both sides), and the unwatched draw writes the
// same image. Breaks caught: the batch's λ taken from the wrong slots when a queued batch mixes
// triangles, λ1 and λ2 swapped, λ0 computed in another order, a row shaded whole not filling them.
TEST(UserBarycentrics, FragmentReadsTheLambdaTheObserverReports) {
    Framebuffer plain(96, 72), watched(96, 72);
    plain.clearColor(vec4(0.0f));
    watched.clearColor(vec4(0.0f));
    DrawState state;
    state.viewport = {0, 0, 96, 72};
    state.raster.cull = CullMode::None;
    Shown::Uniforms u;
    u.clipFromObject = glm::perspective(glm::radians(60.0f), 96.0f / 72.0f, 0.1f, 20.0f);
    const std::vector<MeshVertex> vertices = scene();
    std::vector<std::uint32_t> indices(vertices.size());
    for (std::size_t i = 0; i < indices.size(); ++i)
        indices[i] = static_cast<std::uint32_t>(i);
    DrawContext plainContext, watchedContext;
    draw<Shown>(state, u, vertices, indices, plain, plainContext);
    LastWritten observer;
    draw<Shown>(state, u, vertices, indices, watched, watchedContext, observer);
    ASSERT_GT(observer.written, 500);
    for (const auto& [pixel, event] : observer.at) {
        for (int k = 0; k < 3; ++k)
            ASSERT_EQ(bits(event.shaded[k]), bits(event.barycentrics[k]))
                << "pixel " << pixel.first << ", " << pixel.second << " λ" << k;
        EXPECT_NEAR(event.barycentrics.x + event.barycentrics.y + event.barycentrics.z, 1.0f, 1e-5f);
        EXPECT_EQ(plain.color(pixel.first, pixel.second), event.shaded)
            << "pixel " << pixel.first << ", " << pixel.second;
    }
}

// The module's one-lane entry hands FragmentInput::barycentric to the fragment part (the step mode's
// trace); the pipeline's one-lane entry, which has none, leaves (⅓, ⅓, ⅓). Break caught: shadeFragment
// not copying them (the trace would show the centroid at every pixel).
TEST(UserBarycentrics, OneLaneEntriesPassThem) {
    const ShaderModule& module = user_shader::moduleOf<ShowBarycentrics>("ShowBarycentrics");
    const SceneUniforms scene;
    ShaderCall call;
    call.scene = &scene;
    const float varyings[3] = {0.0f, 0.0f, 1.0f};
    FragmentInput in;
    in.varyings = varyings;
    in.barycentric = vec3(0.125f, 0.5f, 0.375f);
    vec4 color;
    ASSERT_TRUE(module.shadeFragment(in, call, color, nullptr));
    EXPECT_EQ(color, vec4(0.125f, 0.5f, 0.375f, 1.0f));
    const vec4 centroid = Shown::fragment({vec3(0.0f, 0.0f, 1.0f)}, Shown::Uniforms{});
    EXPECT_EQ(centroid, vec4(vec3(1.0f / 3.0f), 1.0f));
}

// A shader that does not ask gets no barycentrics written into its batch (the built-in shaders' batch
// code does not change): the queue's interpolation leaves the batch's λ as they were. Break caught:
// the back end filling them for every shader (a cost for all of them).
TEST(UserBarycentrics, OnlyShadersThatAskGetThem) {
    detail::FragmentQueue queue;
    for (int lane = 0; lane < 8; ++lane) {
        queue.b1[lane] = 0.1f * lane;
        queue.b2[lane] = 0.05f * lane;
    }
    const Float8 sentinel = splat(-7.0f);
    queue.batch.barycentrics[0] = queue.batch.barycentrics[1] = sentinel;
    queue.batch.mask = 0;  // no slot live: only the λ copy can write
    detail::interpolateQueue<SurfaceShader<ShadingFrequency::Phong>, false>(queue);
    detail::interpolateQueue<user_shader::Adapter<NoBarycentrics>, false>(queue);
    for (int lane = 0; lane < 8; ++lane) {
        EXPECT_EQ(queue.batch.barycentrics[0][lane], -7.0f);
        EXPECT_EQ(queue.batch.barycentrics[1][lane], -7.0f);
    }
    detail::interpolateQueue<Shown, false>(queue);
    for (int lane = 0; lane < 8; ++lane) {
        EXPECT_EQ(queue.batch.barycentrics[0][lane], 0.1f * lane);
        EXPECT_EQ(queue.batch.barycentrics[1][lane], 0.05f * lane);
    }
}

}  // namespace
}  // namespace facet
