// Micro-benchmarks of the per-fragment stages: the fragment shader of each shading frequency and
// reflection model (with the lighting's precision knobs), texture filtering, fog, blending into each
// colour buffer format, and the anti-aliasing resolve. Each calls the shaders' and the pipeline's own
// functions on deterministic random fragments (kSeed).
#include <algorithm>

#include "microbench/workload.h"
#include "pipeline/blend.h"
#include "pipeline/framebuffer.h"
#include "pipeline/texture.h"
#include "pipeline/thread_pool.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace facet::microbench {
namespace {

constexpr std::size_t kBatches = 8192;  // eight fragments each: 65 536 fragments per iteration
constexpr std::int64_t kFramePixels = std::int64_t{kFrameWidth} * kFrameHeight;

// A point of the sphere's front half (the one the camera 4 units away on +z sees) and its normal, in
// object space.
vec3 frontSpherePoint(std::mt19937& random) {
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    vec3 p;
    do {
        p = vec3(unit(random), unit(random), unit(random));
    } while (dot(p, p) > 1.0f || dot(p, p) < 1e-4f);
    p = normalize(p);
    p.z = std::abs(p.z);
    return p;
}

// Eight-lane fragments as the back end hands them to SurfaceShader<kFrequency>'s fragmentBatch: Phong
// shading's eye-space position, normal and uv; per-vertex shading's two colour parts, position and uv.
std::vector<FragmentBatch> fragmentBatches(ShadingFrequency frequency, const SurfaceUniforms& u) {
    std::mt19937 random(kSeed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<FragmentBatch> batches(kBatches);
    for (FragmentBatch& batch : batches) {
        batch.mask = 0xffu;
        for (int lane = 0; lane < kBlockSize; ++lane) {
            const vec3 p = frontSpherePoint(random);
            const vec3 eye = vec3(u.viewFromObject * vec4(p, 1.0f));
            const vec3 normal = u.normalFromObject * p;
            float values[kMaxVaryingFloats] = {};
            if (frequency == ShadingFrequency::Phong) {
                const float phong[] = {eye.x,    eye.y,    eye.z,        normal.x,
                                       normal.y, normal.z, unit(random), unit(random)};
                std::copy(std::begin(phong), std::end(phong), values);
            } else {
                const float perVertex[] = {0.8f * unit(random),
                                           0.8f * unit(random),
                                           0.8f * unit(random),
                                           0.2f * unit(random),
                                           0.2f * unit(random),
                                           0.2f * unit(random),
                                           eye.x,
                                           eye.y,
                                           eye.z,
                                           unit(random),
                                           unit(random)};
                std::copy(std::begin(perVertex), std::end(perVertex), values);
            }
            for (int k = 0; k < kMaxVaryingFloats; ++k)
                batch.varyings[k][lane] = values[k];
        }
    }
    return batches;
}

// ---- Fragment shader ------------------------------------------------------------------------------
// SurfaceShader<frequency>::fragmentBatch, two point lights, no texture (texture filtering is its own
// benchmark). Phong shading lights every fragment, so the reflection model and the lighting's knobs
// (--powers, --normalize, --fresnel) are its cost; Gouraud and flat shading only add the colours.

template <ShadingFrequency kFrequency>
void shadeAll(benchmark::State& state, const SurfaceUniforms& uniforms) {
    const std::vector<FragmentBatch> batches = fragmentBatches(kFrequency, uniforms);
    for (auto _ : state)
        for (const FragmentBatch& batch : batches) {
            Vec4x8 color = SurfaceShader<kFrequency>::fragmentBatch(batch, uniforms);
            benchmark::DoNotOptimize(color);
        }
}

void BM_FragmentShader(benchmark::State& state) {
    const auto frequency = static_cast<ShadingFrequency>(state.range(0));
    SurfaceUniforms uniforms = makeUniforms(4.0f, 0.1f);
    uniforms.reflection = static_cast<ReflectionModel>(state.range(1));
    uniforms.precision = static_cast<MathPrecision>(state.range(2));
    uniforms.normalization = static_cast<Normalization>(state.range(3));
    uniforms.brdf.fresnel = static_cast<FresnelModel>(state.range(4));
    switch (frequency) {
        case ShadingFrequency::Flat:
        case ShadingFrequency::Constant:  // the flat shader, unlit (never benchmarked)
            shadeAll<ShadingFrequency::Flat>(state, uniforms);
            break;
        case ShadingFrequency::Gouraud:
            shadeAll<ShadingFrequency::Gouraud>(state, uniforms);
            break;
        case ShadingFrequency::Phong:
            shadeAll<ShadingFrequency::Phong>(state, uniforms);
            break;
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kBatches * kBlockSize));
    state.SetLabel(joined({knob("--shading", frequency), knob("--reflection", uniforms.reflection),
                           knob("--powers", uniforms.precision), knob("--normalize", uniforms.normalization),
                           knob("--fresnel", uniforms.brdf.fresnel)}) +
                   ": fragments/s");
}
constexpr int kFast = int(MathPrecision::Fast), kExact = int(MathPrecision::Exact);
BENCHMARK(BM_FragmentShader)
    ->ArgNames({"shading", "reflection", "powers", "normalize", "fresnel"})
    ->Args({int(ShadingFrequency::Flat), int(ReflectionModel::BlinnPhong), kFast, int(Normalization::Exact),
            int(FresnelModel::Schlick)})
    ->Args({int(ShadingFrequency::Gouraud), int(ReflectionModel::BlinnPhong), kFast,
            int(Normalization::Exact), int(FresnelModel::Schlick)})
    ->Args({int(ShadingFrequency::Phong), int(ReflectionModel::Phong), kFast, int(Normalization::Exact),
            int(FresnelModel::Schlick)})
    ->Args({int(ShadingFrequency::Phong), int(ReflectionModel::BlinnPhong), kFast, int(Normalization::Exact),
            int(FresnelModel::Schlick)})
    ->Args({int(ShadingFrequency::Phong), int(ReflectionModel::BlinnPhong), kExact, int(Normalization::Exact),
            int(FresnelModel::Schlick)})
    ->Args({int(ShadingFrequency::Phong), int(ReflectionModel::BlinnPhong), kFast, int(Normalization::Fast),
            int(FresnelModel::Schlick)})
    ->Args({int(ShadingFrequency::Phong), int(ReflectionModel::CookTorrance), kFast,
            int(Normalization::Exact), int(FresnelModel::Schlick)})
    ->Args({int(ShadingFrequency::Phong), int(ReflectionModel::CookTorrance), kFast,
            int(Normalization::Exact), int(FresnelModel::Exact)})
    ->Args({int(ShadingFrequency::Phong), int(ReflectionModel::CookTorrance), kExact,
            int(Normalization::Exact), int(FresnelModel::Schlick)});

// ---- Texture filtering ----------------------------------------------------------------------------
// A 1024 × 1024 8-bit texture (random codes, with its mip chain) sampled the way the surface shaders
// sample a map, eight lanes at a time, at random uv with footprints from 0.5 to 16 texels (level of
// detail −1 to 4).

void BM_TextureFilter(benchmark::State& state) {
    const auto filter = static_cast<TextureFilter>(state.range(0));
    static const Texture texture = [] {
        Texture t;
        t.width = t.height = 1024;
        std::mt19937 random(kSeed);
        t.codes.resize(static_cast<std::size_t>(t.width) * t.height);
        for (Texture::Codes& c : t.codes)
            for (std::uint8_t& channel : c)
                channel = static_cast<std::uint8_t>(random() & 0xffu);
        for (int code = 0; code < 256; ++code)
            t.colorFromCode[code] = static_cast<float>(code) / 255.0f;
        buildMipChain(t);
        return t;
    }();
    struct Samples {
        Vec2x8 uv;
        TexCoordDerivativesT<Float8> derivatives;
    };
    std::vector<Samples> samples(kBatches);
    std::mt19937 random(kSeed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), lod(-1.0f, 4.0f);
    for (Samples& s : samples)
        for (int lane = 0; lane < kBlockSize; ++lane) {
            s.uv.x[lane] = unit(random);
            s.uv.y[lane] = unit(random);
            const float footprint = std::exp2(lod(random)) / static_cast<float>(texture.width);
            s.derivatives.dx.x[lane] = footprint;
            s.derivatives.dx.y[lane] = 0.0f;
            s.derivatives.dy.x[lane] = 0.0f;
            s.derivatives.dy.y[lane] = footprint;
        }
    for (auto _ : state)
        for (const Samples& s : samples) {
            Vec4x8 texel = detail::texels<Float8>(texture, s.uv, 0xffu, filter, 1.0f, s.derivatives);
            benchmark::DoNotOptimize(texel);
        }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kBatches * kBlockSize));
    state.SetLabel(knob("--texture-filter", filter) + ": samples/s");
}
BENCHMARK(BM_TextureFilter)
    ->ArgName("texture-filter")
    ->Arg(int(TextureFilter::Nearest))
    ->Arg(int(TextureFilter::Bilinear))
    ->Arg(int(TextureFilter::Trilinear));

// ---- Fog ------------------------------------------------------------------------------------------
// applyFog on eight-lane lit colours at the sphere's eye-space points (2.9 to 4 units away): linear
// from 2 to 6, exp and exp² of density 0.3, with the exponential's precision (--powers).

template <MathPrecision kPrecision>
void fogAll(benchmark::State& state, const FogParams& fog, const std::vector<FragmentBatch>& batches) {
    for (auto _ : state)
        for (const FragmentBatch& batch : batches) {
            const Vec3x8 color{batch.varyings[0], batch.varyings[1], batch.varyings[2]};
            const Vec3x8 position{batch.varyings[6], batch.varyings[7], batch.varyings[8]};
            Vec3x8 fogged = applyFog<Float8, Vec3x8, kPrecision>(fog, color, position);
            benchmark::DoNotOptimize(fogged);
        }
}

void BM_Fog(benchmark::State& state) {
    // Per-vertex shading's fragments: a colour (the modulated part) and the eye-space position.
    static const std::vector<FragmentBatch> batches =
        fragmentBatches(ShadingFrequency::Gouraud, makeUniforms(4.0f, 0.1f));
    FogParams fog;
    fog.mode = static_cast<FogMode>(state.range(0));
    const auto precision = static_cast<MathPrecision>(state.range(1));
    fog.distance = static_cast<FogDistance>(state.range(2));
    fog.start = 2.0f;
    fog.end = 6.0f;
    fog.density = 0.3f;
    if (precision == MathPrecision::Exact)
        fogAll<MathPrecision::Exact>(state, fog, batches);
    else
        fogAll<MathPrecision::Fast>(state, fog, batches);
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kBatches * kBlockSize));
    // Fog is a scene key ("fog": {"mode": …}); its exponential's precision is --powers.
    state.SetLabel(joined({"fog " + std::string(nameOf(fog.mode)),
                           "distance " + std::string(nameOf(fog.distance)), knob("--powers", precision)}) +
                   ": fragments/s");
}
BENCHMARK(BM_Fog)
    ->ArgNames({"fog", "powers", "distance"})
    ->Args({int(FogMode::None), kFast, int(FogDistance::EyeDepth)})
    ->Args({int(FogMode::Linear), kFast, int(FogDistance::EyeDepth)})
    ->Args({int(FogMode::Linear), kFast, int(FogDistance::Radial)})
    ->Args({int(FogMode::Exponential), kFast, int(FogDistance::EyeDepth)})
    ->Args({int(FogMode::Exponential), kExact, int(FogDistance::EyeDepth)})
    ->Args({int(FogMode::ExponentialSquared), kFast, int(FogDistance::EyeDepth)})
    ->Args({int(FogMode::ExponentialSquared), kExact, int(FogDistance::EyeDepth)});

// ---- Blending -------------------------------------------------------------------------------------
// One fragment per pixel of a 1920 × 1080 colour buffer blended into it with the mode, then rounded as
// the colour buffer's format stores it, as the back end writes a shaded fragment (the rounding only
// for a format other than float: the back end's kRoundColor). The buffer is restored between
// iterations, untimed, so repeated blends neither overflow nor sink into denormals.

template <bool kRoundColor>
void blendAll(benchmark::State& state, BlendMode mode, ColorBufferFormat format,
              const std::vector<vec4>& source, const std::vector<vec4>& initial) {
    std::vector<vec4> buffer = initial;
    for (auto _ : state) {
        state.PauseTiming();
        std::copy(initial.begin(), initial.end(), buffer.begin());
        state.ResumeTiming();
        for (std::size_t i = 0; i < buffer.size(); ++i) {
            vec4& destination = buffer[i];
            destination = blend(mode, source[i], destination);
            if constexpr (kRoundColor) destination = roundToColorBuffer(format, destination);
        }
        benchmark::DoNotOptimize(buffer.data());
        benchmark::ClobberMemory();
    }
}

void BM_Blend(benchmark::State& state) {
    const auto mode = static_cast<BlendMode>(state.range(0));
    const auto format = static_cast<ColorBufferFormat>(state.range(1));
    static const auto colors = [](std::uint32_t seed) {
        std::mt19937 random(seed);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        std::vector<vec4> c(static_cast<std::size_t>(kFramePixels));
        for (vec4& v : c)
            v = vec4(unit(random), unit(random), unit(random), unit(random));
        return c;
    };
    static const std::vector<vec4> source = colors(kSeed), initial = colors(kSeed + 1);
    if (format == ColorBufferFormat::Float)
        blendAll<false>(state, mode, format, source, initial);
    else
        blendAll<true>(state, mode, format, source, initial);
    state.SetItemsProcessed(state.iterations() * kFramePixels);
    // The blend mode is a scene key ("blend" of an object); the colour buffer is --color-buffer.
    state.SetLabel(joined({"blend " + std::string(nameOf(mode)), knob("--color-buffer", format)}) +
                   ": fragments/s");
}
BENCHMARK(BM_Blend)
    ->ArgNames({"blend", "color-buffer"})
    ->Args({int(BlendMode::Replace), int(ColorBufferFormat::Float)})
    ->Args({int(BlendMode::Over), int(ColorBufferFormat::Float)})
    ->Args({int(BlendMode::PremultipliedOver), int(ColorBufferFormat::Float)})
    ->Args({int(BlendMode::Additive), int(ColorBufferFormat::Float)})
    ->Args({int(BlendMode::Multiply), int(ColorBufferFormat::Float)})
    ->Args({int(BlendMode::Over), int(ColorBufferFormat::Half)})
    ->Args({int(BlendMode::Over), int(ColorBufferFormat::Unorm8)});

// ---- Supersampling resolve ------------------------------------------------------------------------
// The renderer's resolve of --aa ssaaN (detail::accumulateSamplePass) on a 1920 × 1080 frame, one
// thread: each of the N sample passes added into the sum, the last one averaged into the colour buffer
// and rounded to its format. The drawing of the passes is not timed (it is the whole pipeline N times).

void BM_SupersampleResolve(benchmark::State& state) {
    const auto aa = static_cast<Antialiasing>(state.range(0));
    const auto format = static_cast<ColorBufferFormat>(state.range(1));
    const auto passes = static_cast<std::size_t>(samplesPerPixel(aa));
    Framebuffer target(kFrameWidth, kFrameHeight);
    target.clearColor(vec4(0.25f, 0.5f, 0.75f, 1.0f));
    std::vector<vec4> sum;
    ThreadPool pool(1);
    for (auto _ : state) {
        for (std::size_t pass = 0; pass < passes; ++pass)
            detail::accumulateSamplePass(target, sum, pass, passes, format, pool);
        benchmark::DoNotOptimize(sum.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * kFramePixels * static_cast<std::int64_t>(passes));
    state.SetLabel(joined({knob("--aa", aa), knob("--color-buffer", format)}) + ": samples/s");
}
BENCHMARK(BM_SupersampleResolve)
    ->ArgNames({"aa", "color-buffer"})
    ->Args({int(Antialiasing::Ssaa4), int(ColorBufferFormat::Float)})
    ->Args({int(Antialiasing::Ssaa16), int(ColorBufferFormat::Float)})
    ->Args({int(Antialiasing::Ssaa4), int(ColorBufferFormat::Unorm8)});

// ---- MSAA resolve ---------------------------------------------------------------------------------
// Framebuffer::resolveSamples on a 1920 × 1080 frame, one thread: each pixel's N per-sample colours
// summed pairwise, averaged and rounded to the colour buffer's format. The samples' values do not
// matter to its speed (no branch depends on them); the planes are allocated and cleared outside the
// timed loop, as the renderer does once per frame.

void BM_MsaaResolve(benchmark::State& state) {
    const auto aa = static_cast<Antialiasing>(state.range(0));
    const auto format = static_cast<ColorBufferFormat>(state.range(1));
    const int samples = samplesPerPixel(aa);
    Framebuffer target(kFrameWidth, kFrameHeight);
    target.useSamples(samples);
    ThreadPool pool(1);
    target.clear(vec4(0.25f, 0.5f, 0.75f, 1.0f), DepthFormat::kClear, pool);
    target.finishClear(pool);
    for (auto _ : state) {
        target.resolveSamples(format, pool);
        benchmark::DoNotOptimize(target.colorSpan().data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * kFramePixels * static_cast<std::int64_t>(samples));
    state.SetLabel(joined({knob("--aa", aa), knob("--color-buffer", format)}) + ": samples/s");
}
BENCHMARK(BM_MsaaResolve)
    ->ArgNames({"aa", "color-buffer"})
    ->Args({int(Antialiasing::Msaa4), int(ColorBufferFormat::Float)})
    ->Args({int(Antialiasing::Msaa16), int(ColorBufferFormat::Float)})
    ->Args({int(Antialiasing::Msaa4), int(ColorBufferFormat::Unorm8)});

}  // namespace
}  // namespace facet::microbench
