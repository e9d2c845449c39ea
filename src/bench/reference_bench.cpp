// facet bench --reference: the reference renderer's speed, Embree's ray casting alone, the BVH build, and
// what shadows cost the rasterizer per light. Medians of wall-clock and of CPU time, configurations
// alternating frame by frame, so that a shared machine's slow spells fall on all of them alike.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <memory>
#include <ostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "bench/bench.h"
#include "bench/process_stats.h"
#include "io/output_path.h"
#include "io/text_file.h"
#include "raycast/ray_scene.h"
#include "reference/reference.h"
#include "render/renderer.h"

namespace facet {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

constexpr int kMaxSlowReferenceFrames = 3;       // 16 samples per pixel: seconds per frame
constexpr int kMinBvhBuilds = 3;                 // a median needs a few
constexpr int kShadowLightCounts[] = {1, 2, 4};  // directional lights, all casting shadows or none
constexpr float kGroundSideOverModel = 2.0f;     // the ground quad's side, in model widths
constexpr float kGroundObjSide = 40.0f;          // models/fog-and-glass/ground.obj: 40 × 40 at y = 0
constexpr float kLightElevationDegrees = 55.0f;  // above the horizon: the shadows fall near, in view
constexpr float kFirstLightAzimuthDegrees = 30.0f;

// One row of the printed tables, and one line of the CSV (blank where a number does not apply).
struct Row {
    std::string part;           // "reference", "rays", "bvh" or "shadows"
    std::string configuration;  // no commas: "16 samples", "packets of 8 culling back", "map 2048"
    int threads = 0;
    int lights = 0;         // shadows: the scene's lights (all shadowing, or none for "none")
    int frames = 0;         // timed (rays: passes over the image's rays; bvh: builds)
    double medianMs = NAN;  // per frame (rays: per pass; bvh: per build)
    double buildMs = NAN;   // reference: its BVH build; shadows: prepareShadows (BVH or maps)
    double drawMs = NAN;    // shadows: renderFrame alone
    double megaRaysPerSecond = NAN;
    // CPU time of the whole process (every thread) per frame or pass, and rays per second of it: the rate
    // per busy core, which other processes sharing the machine change far less than the wall-clock one.
    double cpuMs = NAN;
    double megaRaysPerCpuSecond = NAN;
    double drawMsPerShadowingLight = NAN;  // shadows: of the draw alone (the BVH is shared by the lights)
    double msPerShadowingLight = NAN;      // shadows: of the whole frame, prepareShadows included
    double cpuMsPerShadowingLight = NAN;   // shadows: the same in CPU time
};

std::string csvNumber(double value) {
    if (std::isnan(value)) return "";
    std::ostringstream text;
    text << std::fixed << std::setprecision(3) << value;
    return text.str();
}

void writeCsv(const std::filesystem::path& path, const std::vector<Row>& rows) {
    std::string text =
        "part,configuration,threads,lights,frames,median_ms,build_ms,draw_ms,mrays_per_s,cpu_ms,mrays_"
        "per_cpu_s,draw_ms_per_shadowing_light,ms_per_shadowing_light,cpu_ms_per_shadowing_light\n";
    for (const Row& row : rows) {
        text += row.part;
        text += ',';
        text += row.configuration;
        text += ',' + std::to_string(row.threads);
        text += ',' + std::to_string(row.lights);
        text += ',' + std::to_string(row.frames);
        for (double value : {row.medianMs, row.buildMs, row.drawMs, row.megaRaysPerSecond, row.cpuMs,
                             row.megaRaysPerCpuSecond, row.drawMsPerShadowingLight, row.msPerShadowingLight,
                             row.cpuMsPerShadowingLight}) {
            text += ',';
            text += csvNumber(value);
        }
        text += '\n';
    }
    std::error_code error;
    if (path.has_parent_path() && classifyOutput(path).kind == OutputKind::AtomicFile)
        std::filesystem::create_directories(path.parent_path(), error);
    writeTextFile(path, text);  // its message names the file when it cannot
}

std::string threadsText(int threads) {
    return std::to_string(threads) + (threads == 1 ? " thread" : " threads");
}

// ---- the reference renderer ---------------------------------------------------------------------

std::vector<Row> benchReference(const PreparedScene& prepared, const std::vector<ThreadPool*>& pools,
                                int frames, std::ostream& out) {
    struct Config {
        int samples;  // N: N×N per pixel
        ThreadPool* pool;
        int frames;
        std::vector<double> ms, buildMs, renderMs, cpuMs;
        std::uint64_t cameraRays = 0;
    };
    std::vector<Config> configs;
    for (int samples : {1, 4})
        for (ThreadPool* pool : pools)
            configs.push_back({samples,
                               pool,
                               samples == 1 ? frames : std::min(frames, kMaxSlowReferenceFrames),
                               {},
                               {},
                               {},
                               {},
                               0});

    for (ThreadPool* pool : pools)  // warm-up: Embree's device, the pools' threads, the caches
        renderReference(prepared, ReferenceOptions{.samples = 1}, *pool);
    for (int round = 0; round < frames; ++round)
        for (Config& config : configs) {
            if (round >= config.frames) continue;
            ReferenceStats stats;
            const double cpuStart = processCpuMs();
            const auto start = Clock::now();
            renderReference(prepared, ReferenceOptions{.samples = config.samples}, *config.pool, &stats);
            config.ms.push_back(msSince(start));
            config.cpuMs.push_back(processCpuMs() - cpuStart);
            config.buildMs.push_back(stats.buildMilliseconds);
            config.renderMs.push_back(stats.renderMilliseconds);
            config.cameraRays = stats.cameraRays;
        }

    std::vector<Row> rows;
    out << "Reference renderer (facet render --renderer reference): a whole frame, its BVH build included;\n"
           "camera rays per second of tracing and shading (BVH excluded), and per CPU second of the whole\n"
           "frame (all threads' CPU time, BVH included)\n"
        << "  samples/pixel  threads  frames   ms/frame   BVH ms   M camera rays/s   CPU ms   M rays/CPU s\n";
    for (const Config& config : configs) {
        Row row;
        row.part = "reference";
        const int samples = config.samples * config.samples;
        row.configuration = std::to_string(samples) + (samples == 1 ? " sample" : " samples");
        row.threads = config.pool->threads();
        row.frames = config.frames;
        row.medianMs = median(config.ms);
        row.buildMs = median(config.buildMs);
        row.megaRaysPerSecond = static_cast<double>(config.cameraRays) / median(config.renderMs) / 1e3;
        row.cpuMs = median(config.cpuMs);
        row.megaRaysPerCpuSecond = static_cast<double>(config.cameraRays) / row.cpuMs / 1e3;
        out << "  " << std::setw(13) << samples << std::setw(9) << row.threads << std::setw(8) << row.frames
            << std::setw(11) << row.medianMs << std::setw(9) << row.buildMs << std::setw(18)
            << row.megaRaysPerSecond << std::setw(9) << std::setprecision(0) << row.cpuMs << std::setw(15)
            << std::setprecision(2) << row.megaRaysPerCpuSecond << "\n";
        rows.push_back(row);
    }
    out << std::endl;  // flushed: a long run shows its progress
    return rows;
}

// ---- the ray casting alone and the BVH build -----------------------------------------------------

// The camera rays of one sample per pixel (the pixel centres), as the reference casts them, row by row.
struct CameraRays {
    int width = 0, height = 0;
    std::vector<glm::dvec3> origins, directions;
    std::vector<double> tnear, tfar;
};

CameraRays pixelCentreRays(const PreparedScene& prepared) {
    const ReferenceCamera camera(prepared);
    CameraRays rays;
    rays.width = prepared.scene.width;
    rays.height = prepared.scene.height;
    const std::size_t count = static_cast<std::size_t>(rays.width) * rays.height;
    rays.origins.reserve(count);
    rays.directions.reserve(count);
    rays.tnear.reserve(count);
    rays.tfar.reserve(count);
    for (int y = 0; y < rays.height; ++y)
        for (int x = 0; x < rays.width; ++x) {
            const CameraRay ray = camera.ray({x + 0.5, y + 0.5});
            rays.origins.push_back(ray.origin);
            rays.directions.push_back(ray.direction);
            rays.tnear.push_back(ray.tnear);
            rays.tfar.push_back(ray.tfar);
        }
    return rays;
}

// The nearest opaque hit of every ray, rows spread over the pool: eight rays of a row at a time (as the
// reference casts them), or one at a time (a packet with one lane: Embree then traverses a single ray).
void castAll(const RayScene& scene, const CameraRays& rays, bool packets, RayScene::Culling culling,
             ThreadPool& pool, std::vector<RayHit>& hits) {
    hits.resize(rays.origins.size());
    const std::size_t width = static_cast<std::size_t>(rays.width);
    pool.parallelFor(static_cast<std::size_t>(rays.height), [&](std::size_t row, int) {
        const std::size_t end = (row + 1) * width;
        const std::size_t step = packets ? 8 : 1;
        for (std::size_t first = row * width; first < end; first += step) {
            const std::size_t count = std::min(step, end - first);
            scene.nearestOpaque8(&rays.origins[first], &rays.directions[first], &rays.tnear[first],
                                 &rays.tfar[first], (1u << count) - 1u, culling, &hits[first]);
        }
    });
}

std::vector<Row> benchRayCasting(const PreparedScene& prepared, const std::vector<ThreadPool*>& pools,
                                 int frames, std::ostream& out) {
    std::vector<std::vector<vec3>> positions;
    const std::vector<RayMesh> meshes = rayMeshes(prepared, positions);

    // The BVH build: Embree builds on its own threads (every CPU the process may use).
    std::vector<double> buildMs;
    std::size_t triangles = 0;
    for (int build = 0; build < std::max(frames, kMinBvhBuilds); ++build) {
        const RayScene scene(meshes);
        buildMs.push_back(scene.stats().buildMilliseconds);
        triangles = scene.stats().triangles;
    }
    const RayScene scene(meshes);
    const CameraRays rays = pixelCentreRays(prepared);
    const RayScene::Culling sceneCulling = ReferenceCamera(prepared).culling();
    const char* const sceneCullingName = sceneCulling.cullBack    ? "back"
                                         : sceneCulling.cullFront ? "front"
                                                                  : "none";

    struct Config {
        std::string name;
        bool packets;
        RayScene::Culling culling;
        ThreadPool* pool;
        std::vector<double> ms, cpuMs;
    };
    std::vector<Config> configs;
    for (bool packets : {true, false})
        for (bool culled : {true, false})
            for (ThreadPool* pool : pools) {
                std::string name = packets ? "packets of 8" : "single rays";
                name += culled ? std::string(" culling ") + sceneCullingName : " culling none";
                configs.push_back({name, packets, culled ? sceneCulling : RayScene::Culling{}, pool, {}, {}});
            }
    std::vector<RayHit> hits;
    for (Config& config : configs)  // warm-up
        castAll(scene, rays, config.packets, config.culling, *config.pool, hits);
    castAll(scene, rays, true, sceneCulling, *pools[0], hits);
    const auto hitCount =
        std::count_if(hits.begin(), hits.end(), [](const RayHit& hit) { return hit.hit(); });
    for (int round = 0; round < frames; ++round)
        for (Config& config : configs) {
            const double cpuStart = processCpuMs();
            const auto start = Clock::now();
            castAll(scene, rays, config.packets, config.culling, *config.pool, hits);
            config.ms.push_back(msSince(start));
            config.cpuMs.push_back(processCpuMs() - cpuStart);
        }

    std::vector<Row> rows;
    const double rayCount = static_cast<double>(rays.origins.size());
    out << "Ray casting alone: RayScene::nearestOpaque8 on the reference's camera rays, 1 per pixel ("
        << rays.origins.size() << " rays, " << std::setprecision(1) << 100.0 * double(hitCount) / rayCount
        << std::setprecision(2)
        << "% hit the model),\nmade beforehand; Embree in robust mode, culling by a "
           "filter function (\"culling none\": no filter)\n"
        << "  rays                          threads   ms/pass   M rays/s   CPU ms   M rays/CPU s\n";
    for (const Config& config : configs) {
        Row row;
        row.part = "rays";
        row.configuration = config.name;
        row.threads = config.pool->threads();
        row.frames = frames;
        row.medianMs = median(config.ms);
        row.megaRaysPerSecond = rayCount / row.medianMs / 1e3;
        row.cpuMs = median(config.cpuMs);
        row.megaRaysPerCpuSecond = rayCount / row.cpuMs / 1e3;
        out << "  " << std::left << std::setw(30) << row.configuration << std::right << std::setw(7)
            << row.threads << std::setw(10) << row.medianMs << std::setw(11) << row.megaRaysPerSecond
            << std::setw(9) << row.cpuMs << std::setw(15) << row.megaRaysPerCpuSecond << "\n";
        rows.push_back(row);
    }

    Row build;
    build.part = "bvh";
    build.configuration = std::to_string(triangles) + " triangles";
    build.frames = static_cast<int>(buildMs.size());
    build.medianMs = median(buildMs);
    build.threads = static_cast<int>(std::thread::hardware_concurrency());
    out << "\nBVH build (RayScene: Embree, robust, high quality, on Embree's own threads): " << triangles
        << " triangles, median " << build.medianMs << " ms of " << build.frames << " builds\n"
        << std::endl;
    rows.push_back(build);
    return rows;
}

// ---- shadows in the rasterizer -------------------------------------------------------------------

struct ShadowConfig {
    const char* name;
    ShadowMethod method;
    int mapSize;  // Map: texels per side
};
constexpr ShadowConfig kShadowConfigs[] = {{"none", ShadowMethod::None, 0},
                                           {"ray", ShadowMethod::Ray, 0},
                                           {"map 1024", ShadowMethod::Map, 1024},
                                           {"map 2048", ShadowMethod::Map, 2048},
                                           {"map 4096", ShadowMethod::Map, 4096}};

// The scene of the shadow timings: the model standing on a ground quad (kGroundSideOverModel of its
// larger horizontal extent), lit by `lights` directional lights spread evenly around it, from above.
Scene shadowScene(const Scene& scene, const PreparedScene& prepared, const std::filesystem::path& ground,
                  int lights) {
    vec3 low(INFINITY), high(-INFINITY);
    for (const PreparedDraw& draw : prepared.draws)
        for (const MeshVertex& v : draw.vertices) {
            const vec3 p = vec3(draw.worldFromObject * vec4(v.position, 1.0f));
            low = glm::min(low, p);
            high = glm::max(high, p);
        }
    Scene out = scene;
    ObjectSpec groundObject;
    groundObject.model = ground;
    const float side = kGroundSideOverModel * std::max(high.x - low.x, high.z - low.z);
    groundObject.worldFromObject =
        glm::scale(glm::translate(mat4(1.0f), vec3(0.5f * (low.x + high.x), low.y, 0.5f * (low.z + high.z))),
                   vec3(side / kGroundObjSide));
    out.objects.push_back(groundObject);
    out.lights.clear();
    out.shadows.reset();
    const float elevation = glm::radians(kLightElevationDegrees);
    for (int i = 0; i < lights; ++i) {
        const float azimuth = glm::radians(kFirstLightAzimuthDegrees + 360.0f * float(i) / float(lights));
        LightSpec light;
        light.type = LightKind::Directional;
        light.direction = -vec3(std::cos(elevation) * std::cos(azimuth), std::sin(elevation),
                                std::cos(elevation) * std::sin(azimuth));
        light.intensity = 1.0f / float(lights);  // the same total light
        out.lights.push_back(light);
    }
    return out;
}

std::vector<Row> benchShadows(const Scene& scene, const PreparedScene& prepared, const BenchOptions& options,
                              std::ostream& out) {
    struct Config {
        const ShadowConfig* shadows;
        int lights;
        PreparedScene* prepared;
        std::vector<double> prepareMs, drawMs, totalMs, cpuMs;
    };
    std::vector<PreparedScene> scenes;
    scenes.reserve(std::size(kShadowLightCounts));
    for (int lights : kShadowLightCounts)
        scenes.push_back(prepareScene(shadowScene(scene, prepared, options.ground, lights)));
    std::vector<Config> configs;
    for (std::size_t k = 0; k < std::size(kShadowLightCounts); ++k)
        for (const ShadowConfig& shadows : kShadowConfigs)
            configs.push_back({&shadows, kShadowLightCounts[k], &scenes[k], {}, {}, {}, {}});

    Framebuffer framebuffer(scene.width, scene.height);
    DrawContext context(options.threads);
    // One frame of a moving scene: its shadows (BVH or maps) made for the objects as placed now, then drawn.
    const auto frame = [&](Config& config, bool timed) {
        PreparedScene& p = *config.prepared;
        for (std::size_t i = 0; i < kMaxLights; ++i)
            p.shadowMethods[i] = int(i) < config.lights ? config.shadows->method : ShadowMethod::None;
        if (config.shadows->mapSize > 0) p.shadowMapOptions.size = config.shadows->mapSize;
        const double cpuStart = processCpuMs();
        const auto start = Clock::now();
        prepareShadows(p);
        const auto drawStart = Clock::now();
        renderFrame(p, framebuffer, context);
        if (!timed) return;
        config.prepareMs.push_back(std::chrono::duration<double, std::milli>(drawStart - start).count());
        config.drawMs.push_back(msSince(drawStart));
        config.totalMs.push_back(msSince(start));
        config.cpuMs.push_back(processCpuMs() - cpuStart);
    };
    for (Config& config : configs)
        frame(config, false);  // warm-up
    for (int round = 0; round < options.frames; ++round)
        for (Config& config : configs)
            frame(config, true);

    std::vector<Row> rows;
    out << "Shadows in the rasterizer: " << options.model.string() << " on a ground quad, " << scene.width
        << "x" << scene.height << ", " << threadsText(context.pool.threads()) << ", " << options.frames
        << " frames each;\n"
        << "a frame = prepareShadows (the BVH or the maps, rebuilt as for a moving scene) + renderFrame;\n"
        << "per shadowing light = (ms - ms of as many lights without shadows) / lights, of the draw alone\n"
        << "(the BVH is shared by all the lights), of the whole frame, and of its CPU time (all threads)\n"
        << "  shadows    lights   prepare ms   draw ms   frame ms   CPU ms   per light: draw ms   frame ms   "
           "CPU ms\n";
    double withoutShadows = NAN, drawWithoutShadows = NAN, cpuWithoutShadows = NAN;
    for (const Config& config : configs) {
        Row row;
        row.part = "shadows";
        row.configuration = config.shadows->name;
        row.threads = context.pool.threads();
        row.lights = config.lights;
        row.frames = options.frames;
        row.medianMs = median(config.totalMs);
        row.buildMs = median(config.prepareMs);
        row.drawMs = median(config.drawMs);
        row.cpuMs = median(config.cpuMs);
        if (config.shadows->method == ShadowMethod::None) {  // first of each light count
            withoutShadows = row.medianMs;
            drawWithoutShadows = row.drawMs;
            cpuWithoutShadows = row.cpuMs;
        } else {
            row.drawMsPerShadowingLight = (row.drawMs - drawWithoutShadows) / config.lights;
            row.msPerShadowingLight = (row.medianMs - withoutShadows) / config.lights;
            row.cpuMsPerShadowingLight = (row.cpuMs - cpuWithoutShadows) / config.lights;
        }
        out << "  " << std::left << std::setw(9) << row.configuration << std::right << std::setw(8)
            << row.lights << std::setw(13) << row.buildMs << std::setw(10) << row.drawMs << std::setw(11)
            << row.medianMs << std::setw(9) << std::setprecision(0) << row.cpuMs << std::setprecision(2);
        if (!std::isnan(row.msPerShadowingLight))
            out << std::setw(21) << row.drawMsPerShadowingLight << std::setw(11) << row.msPerShadowingLight
                << std::setw(9) << row.cpuMsPerShadowingLight;
        out << "\n";
        rows.push_back(row);
    }
    out << std::endl;
    return rows;
}

}  // namespace

void runReferenceBench(const BenchOptions& options, std::ostream& out) {
    checkOutput(options.csv, true);  // before the minutes of measuring
    const Scene scene = benchScene(options);
    const PreparedScene prepared = prepareScene(scene);
    // The reference and the ray casting on 1, 2, 4, ... threads up to --threads (the hardware's count
    // when not given).
    std::vector<std::unique_ptr<ThreadPool>> ownedPools;
    std::vector<ThreadPool*> pools;
    for (const int threads : threadSweep(options.threads)) {
        ownedPools.push_back(std::make_unique<ThreadPool>(threads));
        pools.push_back(ownedPools.back().get());
    }

    out << std::fixed << std::setprecision(2);
    out << "Reference renderer, ray casting and shadows: " << options.model.string() << " ("
        << prepared.triangleCount << " triangles) at " << scene.width << "x" << scene.height << ", "
        << std::thread::hardware_concurrency()
        << " hardware threads; medians of wall-clock ms,\nconfigurations alternating frame by frame\n\n";
    std::vector<Row> rows = benchReference(prepared, pools, options.frames, out);
    for (const Row& row : benchRayCasting(prepared, pools, options.frames, out))
        rows.push_back(row);
    for (const Row& row : benchShadows(scene, prepared, options, out))
        rows.push_back(row);
    writeCsv(options.csv, rows);
    out << "wrote " << options.csv.string() << "\n";
}

}  // namespace facet
