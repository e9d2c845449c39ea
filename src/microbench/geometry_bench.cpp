// Micro-benchmarks of the geometry stages: vertex stage, primitive assembly + clipping, triangle setup,
// rasterization, interpolation and the depth test, each over the knob values that change its cost.
// Every benchmark calls the pipeline's own stage functions (pipeline/*.h) on the workload's data.
#include <algorithm>
#include <bit>
#include <map>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>

#include "microbench/workload.h"
#include "pipeline/clip.h"
#include "pipeline/depth_format.h"
#include "pipeline/interpolate.h"
#include "pipeline/primitive_assembly.h"
#include "pipeline/rasterize.h"
#include "pipeline/triangle_setup.h"
#include "pipeline/vertex_stage.h"
#include "pipeline/viewport.h"
#include "scene/camera.h"

namespace facet::microbench {

// ---- The workload ---------------------------------------------------------------------------------

SphereMesh makeSphere(int rings, int segments) {
    SphereMesh mesh;
    constexpr float kPi = 3.14159265358979f;
    for (int i = 0; i <= rings; ++i) {
        const float theta = kPi * static_cast<float>(i) / static_cast<float>(rings);
        for (int j = 0; j <= segments; ++j) {
            const float phi = 2.0f * kPi * static_cast<float>(j) / static_cast<float>(segments);
            const vec3 p(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
            mesh.vertices.push_back({p, p,
                                     vec2(static_cast<float>(j) / static_cast<float>(segments),
                                          1.0f - static_cast<float>(i) / static_cast<float>(rings))});
        }
    }
    const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(i * (segments + 1) + j); };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            // Counter-clockwise seen from outside: the front faces survive back-face culling.
            mesh.indices.insert(mesh.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            mesh.indices.insert(mesh.indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return mesh;
}

SurfaceUniforms makeUniforms(float eyeDistance, float near, DepthBufferFormat depth) {
    Camera camera;
    camera.near = near;
    camera.far = 100.0f;
    camera.depthFormat = depth;
    camera.clipFromViewExact =
        glm::perspective(glm::radians(40.0), double(kFrameWidth) / kFrameHeight, double(near), 100.0);
    const mat4 clipFromView(drawnClipFromView(camera));
    const mat4 viewFromObject =
        glm::lookAt(vec3(0.0f, 0.0f, eyeDistance), vec3(0.0f), vec3(0.0f, 1.0f, 0.0f));
    SurfaceUniforms u;
    u.clipFromObject = clipFromView * viewFromObject;
    u.viewFromObject = viewFromObject;
    u.normalFromObject = glm::transpose(glm::inverse(mat3(viewFromObject)));
    u.globalAmbient = vec3(0.05f);
    u.lightCount = 2;
    u.lights[0].position = vec3(3.0f, 4.0f, 2.0f);
    u.lights[1].position = vec3(-4.0f, 1.0f, 1.0f);
    u.lights[1].diffuse = vec3(0.4f, 0.4f, 0.6f);
    u.material.ambient = vec3(0.2f);
    u.material.specular = vec3(0.6f);
    u.material.shininess = 32.0f;
    return u;
}

DrawState makeDrawState(DepthBufferFormat depth) {
    DrawState state;
    state.viewport = {0, 0, kFrameWidth, kFrameHeight};
    state.depth.format = depth;
    state.depth.compare = nearerPasses(depth, CompareOp::Less);
    return state;
}

namespace {

constexpr PixelRect kFrame{0, 0, kFrameWidth - 1, kFrameHeight - 1};
using PhongShader = SurfaceShader<ShadingFrequency::Phong>;

// The sphere through the vertex stage (Phong shading's shader) with the view of `uniforms`.
ShadedVertices shadeSphere(const SphereMesh& mesh, const SurfaceUniforms& uniforms, DepthBufferFormat depth) {
    ShadedVertices shaded;
    prepareShadedVertices<PhongShader>(mesh.vertices.size(), shaded);
    shadeVertices<PhongShader>(mesh.vertices, uniforms, 0, mesh.vertices.size(), shaded,
                               clipDepthRange(depth));
    return shaded;
}

// The window triangles of the sphere's triangles that no plane clips (all of them from 4 units away).
struct WindowTriangles {
    std::vector<WindowTriangle> triangles;
    std::vector<WindowVertex> vertices;
};
WindowTriangles windowTriangles(const SphereMesh& mesh, const ShadedVertices& shaded,
                                const DrawState& state) {
    WindowTriangles out;
    out.vertices.resize(shaded.size());
    for (std::size_t i = 0; i < shaded.size(); ++i)
        if (shaded.outcodes[i] == 0)
            out.vertices[i] =
                toWindow(shaded.positions[i], state.viewport, state.raster.subpixelBits, state.depth.format);
    for (std::size_t t = 0; t < mesh.triangles(); ++t) {
        const std::uint32_t* i = &mesh.indices[3 * t];
        if ((shaded.outcodes[i[0]] | shaded.outcodes[i[1]] | shaded.outcodes[i[2]]) != 0) continue;
        WindowTriangle window;
        window.varyingCount = shaded.varyingCount;
        window.provokingVaryings = shaded.varyingsOf(i[2]);
        for (int k = 0; k < 3; ++k) {
            window.vertices[k] = out.vertices[i[k]];
            window.varyings[k] = shaded.varyingsOf(i[k]);
        }
        out.triangles.push_back(window);
    }
    return out;
}

}  // namespace

const RasterizedSphere& rasterizedSphere(int rings, int segments, Interpolation interpolation) {
    static std::map<std::tuple<int, int, Interpolation>, RasterizedSphere> cache;
    const auto key = std::make_tuple(rings, segments, interpolation);
    if (const auto found = cache.find(key); found != cache.end()) return found->second;
    RasterizedSphere& out = cache[key];
    const SphereMesh mesh = makeSphere(rings, segments);
    DrawState state = makeDrawState();
    state.interpolation = interpolation;
    const ShadedVertices shaded = shadeSphere(mesh, makeUniforms(4.0f, 0.1f), state.depth.format);
    const WindowTriangles windows = windowTriangles(mesh, shaded, state);
    float planes[3 * kMaxVaryingFloats];
    for (const WindowTriangle& window : windows.triangles) {
        TriangleSetup setup;
        if (setupTriangle(window, state, setup, planes) != TriangleFate::Drawn) continue;
        setup.varyingPlaneOffset = static_cast<std::uint32_t>(out.planes.size());
        out.planes.insert(out.planes.end(), planes, planes + 3 * setup.varyingCount);
        const auto index = static_cast<std::uint32_t>(out.setups.size());
        out.setups.push_back(setup);
        rasterizeBlocks(setup, kFrame, [&](const CoverageBlock& block) {
            out.blocks.push_back({index, block});
            out.fragments += std::popcount(block.mask);
        });
    }
    return out;
}

namespace {

// ---- Vertex stage ---------------------------------------------------------------------------------
// The vertex shader of each shading frequency over a 256 × 512 sphere (131 585 vertices): Phong shading
// only transforms; Gouraud and flat shading light every vertex, so the reflection model is their cost.

template <ShadingFrequency kFrequency>
void shadeAllVertices(benchmark::State& state, const SphereMesh& mesh, const SurfaceUniforms& uniforms) {
    ShadedVertices shaded;
    for (auto _ : state) {
        shadeVertices<SurfaceShader<kFrequency>>(mesh.vertices, uniforms, shaded);
        benchmark::DoNotOptimize(shaded.positions.data());
        benchmark::DoNotOptimize(shaded.varyings.data());
        benchmark::ClobberMemory();
    }
}

void BM_VertexStage(benchmark::State& state) {
    static const SphereMesh mesh = makeSphere(256, 512);
    const auto frequency = static_cast<ShadingFrequency>(state.range(0));
    SurfaceUniforms uniforms = makeUniforms(4.0f, 0.1f);
    uniforms.reflection = static_cast<ReflectionModel>(state.range(1));
    switch (frequency) {
        case ShadingFrequency::Flat:
        case ShadingFrequency::Constant:  // the flat shader, unlit (never benchmarked)
            shadeAllVertices<ShadingFrequency::Flat>(state, mesh, uniforms);
            break;
        case ShadingFrequency::Gouraud:
            shadeAllVertices<ShadingFrequency::Gouraud>(state, mesh, uniforms);
            break;
        case ShadingFrequency::Phong:
            shadeAllVertices<ShadingFrequency::Phong>(state, mesh, uniforms);
            break;
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(mesh.vertices.size()));
    state.SetLabel(joined({knob("--shading", frequency), knob("--reflection", uniforms.reflection)}) +
                   ": vertices/s");
}
BENCHMARK(BM_VertexStage)
    ->ArgNames({"shading", "reflection"})
    ->Args({int(ShadingFrequency::Phong), int(ReflectionModel::BlinnPhong)})
    ->Args({int(ShadingFrequency::Flat), int(ReflectionModel::BlinnPhong)})
    ->Args({int(ShadingFrequency::Gouraud), int(ReflectionModel::Phong)})
    ->Args({int(ShadingFrequency::Gouraud), int(ReflectionModel::BlinnPhong)})
    ->Args({int(ShadingFrequency::Gouraud), int(ReflectionModel::CookTorrance)});

// ---- Primitive assembly + clipping ----------------------------------------------------------------
// The triangles of a 64 × 128 sphere seen from 1.6 units with the near plane at 1: the view cuts the
// sphere on every side and the near plane cuts off its cap. Only the triangles that cross a plane are
// timed (the front end sends the others past the clipper): assembled from the shaded vertices, then
// clipped, in the clip-space depth range of the depth buffer format.

void BM_Clip(benchmark::State& state) {
    static const SphereMesh mesh = makeSphere(64, 128);
    const auto format = static_cast<DepthBufferFormat>(state.range(0));
    const ShadedVertices shaded = shadeSphere(mesh, makeUniforms(1.6f, 1.0f, format), format);
    std::vector<std::array<std::uint32_t, 3>> crossing;
    for (std::size_t t = 0; t < mesh.triangles(); ++t) {
        const std::array<std::uint32_t, 3> i = {mesh.indices[3 * t], mesh.indices[3 * t + 1],
                                                mesh.indices[3 * t + 2]};
        const std::uint8_t all = shaded.outcodes[i[0]] & shaded.outcodes[i[1]] & shaded.outcodes[i[2]];
        const std::uint8_t any = shaded.outcodes[i[0]] | shaded.outcodes[i[1]] | shaded.outcodes[i[2]];
        if (trivialReject(all, any) == TriangleFate::Drawn && any != 0) crossing.push_back(i);
    }
    ClipPolygon polygon;
    std::int64_t pieces = 0;
    for (auto _ : state) {
        for (const auto& i : crossing) {
            assembleTriangle(shaded, i, polygon);
            clipPolygon(polygon, shaded.outcodes[i[0]] | shaded.outcodes[i[1]] | shaded.outcodes[i[2]],
                        clipDepthRange(format));
            pieces += polygon.count;
            benchmark::DoNotOptimize(polygon);
        }
    }
    benchmark::DoNotOptimize(pieces);
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(crossing.size()));
    state.SetLabel(knob("--depth", format) + ", " + std::to_string(crossing.size()) +
                   " triangles crossing a plane: triangles/s");
}
BENCHMARK(BM_Clip)
    ->ArgName("depth")
    ->Arg(int(DepthBufferFormat::Float))
    ->Arg(int(DepthBufferFormat::ReversedFloat));

// ---- Triangle setup -------------------------------------------------------------------------------
// Culling and setup (edge functions, bounds, depth, 1/w and varying planes) of every triangle of a
// 256 × 512 sphere 4 units away (half of them back faces, culled), snapped to the sub-pixel grid.

void BM_Setup(benchmark::State& state) {
    static const SphereMesh mesh = makeSphere(256, 512);
    static const ShadedVertices shaded =
        shadeSphere(mesh, makeUniforms(4.0f, 0.1f), DepthBufferFormat::Float);
    DrawState drawState = makeDrawState();
    drawState.raster.subpixelBits = static_cast<int>(state.range(0));
    const WindowTriangles windows = windowTriangles(mesh, shaded, drawState);
    TriangleSetup setup;
    float planes[3 * kMaxVaryingFloats];
    std::int64_t drawn = 0;
    for (auto _ : state) {
        for (const WindowTriangle& window : windows.triangles) {
            drawn += setupTriangle(window, drawState, setup, planes) == TriangleFate::Drawn;
            benchmark::DoNotOptimize(setup);
            benchmark::DoNotOptimize(planes);
        }
    }
    benchmark::DoNotOptimize(drawn);
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(windows.triangles.size()));
    state.SetLabel(knob("--subpixel-bits", state.range(0)) + ": triangles/s");
}
BENCHMARK(BM_Setup)->ArgName("subpixel-bits")->Arg(8)->Arg(4)->Arg(0);

// ---- Rasterization --------------------------------------------------------------------------------
// rasterizeBlocks over the whole 1920 × 1080 frame for every set-up triangle of spheres of three
// tessellations: the same ~430 000 covered pixels in triangles of ~3, ~50 and ~800 pixels, so the table
// shows the cost per triangle against the cost per pixel.

void BM_Rasterize(benchmark::State& state) {
    const RasterizedSphere& sphere =
        rasterizedSphere(static_cast<int>(state.range(0)), static_cast<int>(2 * state.range(0)),
                         Interpolation::PerspectiveCorrect);
    std::int64_t covered = 0;
    for (auto _ : state) {
        for (const TriangleSetup& setup : sphere.setups)
            rasterizeBlocks(setup, kFrame,
                            [&](const CoverageBlock& block) { covered += std::popcount(block.mask); });
        benchmark::DoNotOptimize(covered);
    }
    state.SetItemsProcessed(state.iterations() * sphere.fragments);
    state.SetLabel(std::to_string(sphere.setups.size()) + " triangles, " +
                   std::to_string(sphere.fragments / static_cast<std::int64_t>(sphere.setups.size())) +
                   " px each: fragments/s");
}
BENCHMARK(BM_Rasterize)->ArgName("rings")->Arg(16)->Arg(64)->Arg(256);

// ---- Interpolation --------------------------------------------------------------------------------
// For every covered block of a 64 × 128 sphere: barycentrics, depth and the eight varyings of Phong
// shading, a row of eight lanes at a time as the back end does, perspective-correct or affine; with
// trilinear filtering, also the texture coordinates' screen-space derivatives.

template <bool kDerivatives>
void interpolateAll(benchmark::State& state, const RasterizedSphere& sphere) {
    constexpr int kUv = PerPixelSurface::kDerivativeVarying;
    FragmentBatch batch;
    for (auto _ : state) {
        for (const RasterizedSphere::Block& block : sphere.blocks) {
            const TriangleSetup& setup = sphere.setups[block.setup];
            const float* planes = sphere.planes.data() + setup.varyingPlaneOffset;
            const BlockBarycentrics barycentrics(setup, block.coverage.x, block.coverage.y);
            VaryingPairSlopes slopes;
            if constexpr (kDerivatives) slopes = VaryingPairSlopes(setup, planes, kUv);
            for (int row = 0; row < kBlockSize; ++row) {
                if (((block.coverage.mask >> (row * kBlockSize)) & 0xffu) == 0) continue;
                Float8 b1{}, b2{};
                barycentrics.row(row, b1, b2);
                Float8 z = interpolateDepth(setup, b1, b2);
                interpolateVaryings(setup, planes, b1, b2, batch);
                if constexpr (kDerivatives)
                    interpolateDerivatives<Float8>(setup, slopes, b1, b2, &batch.varyings[kUv],
                                                   batch.uvDerivatives);
                benchmark::DoNotOptimize(z);
                benchmark::DoNotOptimize(batch);
            }
        }
    }
}

void BM_Interpolate(benchmark::State& state) {
    const auto interpolation = static_cast<Interpolation>(state.range(0));
    const auto filter = static_cast<TextureFilter>(state.range(1));
    const RasterizedSphere& sphere = rasterizedSphere(64, 128, interpolation);
    if (filter == TextureFilter::Trilinear)
        interpolateAll<true>(state, sphere);
    else
        interpolateAll<false>(state, sphere);
    state.SetItemsProcessed(state.iterations() * sphere.fragments);
    state.SetLabel(joined({knob("--interpolation", interpolation), knob("--texture-filter", filter)}) +
                   ": fragments/s");
}
BENCHMARK(BM_Interpolate)
    ->ArgNames({"interpolation", "texture-filter"})
    ->Args({int(Interpolation::PerspectiveCorrect), int(TextureFilter::Bilinear)})
    ->Args({int(Interpolation::Affine), int(TextureFilter::Bilinear)})
    ->Args({int(Interpolation::PerspectiveCorrect), int(TextureFilter::Trilinear)});

// ---- Depth test -----------------------------------------------------------------------------------
// The early depth test and depth write of every covered row of a 64 × 128 sphere into a cleared
// 1920 × 1080 depth buffer, eight lanes at a time, through the depth coding the back end compiles for
// the format (DepthCoding: float or unorm with the format's scale). Reversed Z gets the window depths
// it stores, 1 − z, and its compare, greater. The clear between iterations is not timed.

void BM_DepthTest(benchmark::State& state) {
    const auto format = static_cast<DepthBufferFormat>(state.range(0));
    const RasterizedSphere& sphere = rasterizedSphere(64, 128, Interpolation::PerspectiveCorrect);
    struct Row {
        int x, y;
        unsigned mask;
        Float8 z;
    };
    std::vector<Row> rows;
    for (const RasterizedSphere::Block& block : sphere.blocks) {
        const TriangleSetup& setup = sphere.setups[block.setup];
        const BlockBarycentrics barycentrics(setup, block.coverage.x, block.coverage.y);
        for (int row = 0; row < kBlockSize; ++row) {
            const auto mask = static_cast<unsigned>(block.coverage.mask >> (row * kBlockSize)) & 0xffu;
            if (!mask) continue;
            Float8 b1{}, b2{};
            barycentrics.row(row, b1, b2);
            Float8 z = interpolateDepth(setup, b1, b2);
            if (format == DepthBufferFormat::ReversedFloat) z = 1.0f - z;
            rows.push_back({block.coverage.x, block.coverage.y + row, mask, z});
        }
    }
    const CompareOp compare = nearerPasses(format, CompareOp::Less);
    std::vector<float> buffer(static_cast<std::size_t>(kFrameWidth) * kFrameHeight);
    std::int64_t passedCount = 0;
    withDepthCoding(format, [&](const auto& depth) {
        for (auto _ : state) {
            state.PauseTiming();
            std::fill(buffer.begin(), buffer.end(), depthClearValue(format));
            state.ResumeTiming();
            for (const Row& row : rows) {
                float* stored = buffer.data() + static_cast<std::size_t>(row.y) * kFrameWidth + row.x;
                const unsigned passed =
                    row.mask & signMask(depth.passes(compare, row.z, depth.load8(stored)));
                passedCount += std::popcount(passed);
                for (int lane = 0; lane < kBlockSize; ++lane)
                    if ((passed >> lane) & 1u) stored[lane] = depth.store(row.z[lane]);
            }
            benchmark::DoNotOptimize(buffer.data());
            benchmark::ClobberMemory();
        }
    });
    benchmark::DoNotOptimize(passedCount);
    state.SetItemsProcessed(state.iterations() * sphere.fragments);
    state.SetLabel(knob("--depth", format) + ": fragments/s");
}
BENCHMARK(BM_DepthTest)
    ->ArgName("depth")
    ->Arg(int(DepthBufferFormat::Float))
    ->Arg(int(DepthBufferFormat::Unorm16))
    ->Arg(int(DepthBufferFormat::Unorm24))
    ->Arg(int(DepthBufferFormat::ReversedFloat));

}  // namespace

}  // namespace facet::microbench
