#include "bench/bench.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <iomanip>
#include <limits>
#include <optional>
#include <ostream>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <unordered_map>
#include <vector>

#include <fcntl.h>
#include <sched.h>
#include <unistd.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <glm/gtc/matrix_transform.hpp>

#include "base/errors.h"
#include "io/image_io.h"
#include "oracle/mesa_peer.h"
#include "pipeline/color.h"
#include "render/renderer.h"
#include "render/transparency_sort.h"

namespace facet {

namespace {

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace

namespace {

// The scene a benchmark draws: options.model (an OBJ file or a scene) at the options' size.
Scene benchScene(const BenchOptions& options) {
    if (options.frames < 1) throw InputError("--frames must be at least 1");
    Scene scene = loadSceneOrModel(options.model);
    scene.width = options.width;
    scene.height = options.height;
    return scene;
}

}  // namespace

void runBench(const BenchOptions& options, std::ostream& out) {
    const Scene scene = benchScene(options);
    const PreparedScene prepared = prepareScene(scene);

    Framebuffer framebuffer(scene.width, scene.height);
    DrawContext context(options.threads);
    DrawStats stats = renderFrame(prepared, framebuffer, context);  // warm-up: caches, buffers, threads

    using Clock = std::chrono::steady_clock;
    std::vector<double> frameMs, clearMs;
    for (int i = 0; i < options.frames; ++i) {
        const auto start = Clock::now();
        stats = renderFrame(prepared, framebuffer, context);
        const auto end = Clock::now();
        frameMs.push_back(std::chrono::duration<double, std::milli>(end - start).count());

        const auto clearStart = Clock::now();
        framebuffer.clear(prepared.clearColor, 1.0f, context.pool);  // as renderFrame clears
        clearMs.push_back(std::chrono::duration<double, std::milli>(Clock::now() - clearStart).count());
    }

    out << std::fixed << std::setprecision(2);
    out << "model      " << options.model.string() << "\n";
    out << "image      " << scene.width << "x" << scene.height << ", " << context.pool.threads()
        << (context.pool.threads() == 1 ? " thread" : " threads") << ", built-in Blinn-Phong shader\n";
    out << "triangles  " << prepared.triangleCount << " (" << stats.trianglesRasterized
        << " rasterized after culling and clipping)\n";
    out << "fragments  " << stats.fragmentsShaded << " shaded, " << stats.fragmentsWritten << " written, "
        << stats.fragmentsDepthFailed << " rejected by the depth test\n";
    out << "frames     " << options.frames << " timed after 1 warm-up\n";
    out << "ms/frame   median " << median(frameMs) << "  min "
        << *std::min_element(frameMs.begin(), frameMs.end()) << "  max "
        << *std::max_element(frameMs.begin(), frameMs.end()) << "\n";
    out << "clear only median " << median(clearMs) << " ms (colour + depth)\n";
}

// ---------------------------------------------------------------------------------------------------
// facet bench --transparency

void runTransparencyBench(const BenchOptions& options, std::ostream& out) {
    Scene scene = benchScene(options);
    scene.pipeline.cull = CullChoice::None;  // see-through: the back faces show
    for (ObjectSpec& object : scene.objects)
        object.material.opacity = 0.5f;
    PreparedScene prepared = prepareScene(scene);
    Framebuffer framebuffer(scene.width, scene.height);
    DrawContext context(options.threads);

    out << "Transparency modes on a turntable of " << options.model.string()
        << ", every surface at opacity 0.5, culling off,\n"
        << scene.width << "x" << scene.height << ", " << context.pool.threads()
        << (context.pool.threads() == 1 ? " thread" : " threads") << ", " << options.degreesPerFrame
        << " deg per frame, " << options.frames << " frames after 1 warm-up; medians of wall-clock ms.\n";
    out << prepared.transparentTriangles.size() << " transparent triangles.\n\n";
    out << std::fixed << std::setprecision(2);
    out << "  mode        ms/frame   sort ms   resolve ms   draws   fragments stored   longest list   lists "
           "hold\n";

    struct Mode {
        const char* name;
        TransparencyMode mode;
    };
    for (const Mode mode :
         {Mode{"sorted", TransparencyMode::Sorted}, Mode{"unsorted", TransparencyMode::Unsorted},
          Mode{"exact", TransparencyMode::Exact}}) {
        prepared.scene.transparency.mode = mode.mode;
        FrameMemory memory;
        setTurntable(prepared, 0.0f);
        FrameStats stats = renderFrame(prepared, framebuffer, context, memory);  // warm-up
        std::vector<double> frameMs, sortMs, resolveMs;
        for (int frame = 1; frame <= options.frames; ++frame) {
            setTurntable(prepared, options.degreesPerFrame * static_cast<float>(frame));
            const auto start = std::chrono::steady_clock::now();
            stats = renderFrame(prepared, framebuffer, context, memory);
            frameMs.push_back(
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
            sortMs.push_back(stats.sortMilliseconds);
            resolveMs.push_back(stats.resolveMilliseconds);
        }
        out << "  " << std::left << std::setw(10) << mode.name << std::right << std::setw(10)
            << median(frameMs) << std::setw(10) << median(sortMs) << std::setw(13) << median(resolveMs)
            << std::setw(8) << stats.transparentRuns << std::setw(19) << stats.fragmentLists.fragments
            << std::setw(15) << stats.fragmentLists.longestList << std::setw(9) << std::setprecision(1)
            << static_cast<double>(stats.fragmentLists.bytesHeld) / (1024.0 * 1024.0) << " MiB"
            << std::setprecision(2) << "\n";
    }
    out << "\nsorted: back to front by insertion sort from the previous frame's order; unsorted: file order "
           "(wrong "
           "where\nsurfaces overlap, the floor under the other two); exact: per-pixel lists sorted by depth, "
           "right even "
           "where\ntriangles intersect. The colour and depth buffers ("
        << std::setprecision(1) << static_cast<double>(scene.width) * scene.height * 20.0 / (1024.0 * 1024.0)
        << " MiB) are the same for all three.\n";
}

// ---------------------------------------------------------------------------------------------------
// facet bench --vs-mesa

namespace {

namespace fs = std::filesystem;
using glm::dvec2;

constexpr int kWarmUpFrames = 2;  // per renderer: llvmpipe compiles its shader variants on the first draw
constexpr int kChartWidth = 1400;
constexpr int kChartHeight = 640;
constexpr double kMiB = 1024.0 * 1024.0;

// CPU time of the whole process (every thread), to show how many cores a frame kept busy.
double processCpuMs() {
    timespec now{};
    ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) * 1e3 + static_cast<double>(now.tv_nsec) * 1e-6;
}

// Keeps the process on `threads` of the CPUs it may use, where it may use more, so that neither
// renderer can keep more than `threads` cores busy (llvmpipe's binning thread and raster threads, or
// any helper thread, share them). Threads inherit the set from the thread that starts them, so this
// must come before any is started. The previous set is restored at the end.
class CpuLimit {
  public:
    explicit CpuLimit(int threads) {
        CPU_ZERO(&saved_);
        if (::sched_getaffinity(0, sizeof saved_, &saved_) != 0) return;
        available_ = CPU_COUNT(&saved_);
        if (threads >= available_) return;
        cpu_set_t limited;
        CPU_ZERO(&limited);
        for (int cpu = 0, kept = 0; cpu < CPU_SETSIZE && kept < threads; ++cpu) {
            if (!CPU_ISSET(cpu, &saved_)) continue;
            CPU_SET(cpu, &limited);
            if (kept++) cpus_ += ',';
            cpus_ += std::to_string(cpu);
        }
        limited_ = ::sched_setaffinity(0, sizeof limited, &limited) == 0;
    }
    ~CpuLimit() {
        if (limited_) ::sched_setaffinity(0, sizeof saved_, &saved_);
    }
    CpuLimit(const CpuLimit&) = delete;
    CpuLimit& operator=(const CpuLimit&) = delete;

    bool limited() const { return limited_; }
    int available() const { return available_; }  // CPUs the process may use without the limit
    std::string cpus() const {                    // "CPU 0", "CPUs 0,1"
        std::string text = cpus_.find(',') == std::string::npos ? "CPU " : "CPUs ";
        text += cpus_;
        return text;
    }

  private:
    cpu_set_t saved_;
    int available_ = 0;
    bool limited_ = false;
    std::string cpus_;  // "0" or "0,1"
};

// Memory ----------------------------------------------------------------------------------------------

// A field of /proc/self/status in MiB ("VmRSS", "VmHWM": "VmHWM:    123456 kB"); −1 where unavailable.
double statusMiB(std::string_view key) {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.size() > key.size() && line.compare(0, key.size(), key) == 0 && line[key.size()] == ':')
            return std::strtod(line.c_str() + key.size() + 1, nullptr) / 1024.0;
    return -1.0;
}

// Resets the kernel's resident-set high-water mark (VmHWM) to the current resident set: writing "5" to
// /proc/self/clear_refs (Linux ≥ 4.0, proc(5)). False where that is not possible.
bool resetPeakResidentSet() {
    const int file = ::open("/proc/self/clear_refs", O_WRONLY);
    if (file < 0) return false;
    const bool written = ::write(file, "5", 1) == 1;
    ::close(file);
    return written;
}

// Hands freed heap memory back to the system, so the resident set reflects what is in use.
void trimHeap() {
#if defined(__GLIBC__)
    ::malloc_trim(0);
#endif
}

// Scenes ----------------------------------------------------------------------------------------------

struct BenchScene {
    std::string name;   // printed: the model's file name, or "icosphere"
    std::string sweep;  // "" for the three named scenes, else "triangles" or "resolution"
    fs::path model;
    int width = 0;
    int height = 0;

    // Facet alone, before Mesa is loaded.
    std::size_t triangles = 0;
    double peakMiB = -1.0;    // resident-set high-water mark of the process during the render
    double beforeMiB = -1.0;  // resident set before the scene was loaded
    double framebufferMiB = 0.0, meshMiB = 0.0, textureMiB = 0.0;

    // Frames alternating between the two renderers (medians; NaN for Mesa when it is missing).
    double facetMs = 0.0, facetCpuMs = 0.0;
    double mesaMs = std::numeric_limits<double>::quiet_NaN(), mesaCpuMs = mesaMs;
    std::optional<ImageAgreement> agreement;
};

BenchScene benchScene(std::string name, std::string sweep, fs::path model, int width, int height) {
    BenchScene scene;
    scene.name = std::move(name);
    scene.sweep = std::move(sweep);
    scene.model = std::move(model);
    scene.width = width;
    scene.height = height;
    return scene;
}

// The OBJ file under `folder` (recursively) with the most triangles, counting an 'f' statement of k
// corners as k − 2 triangles, as the importer fans it. Ties go to the first path in sorted order.
std::pair<fs::path, std::size_t> largestModel(const fs::path& folder) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(folder))
        if (entry.is_regular_file() && entry.path().extension() == ".obj") files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    std::pair<fs::path, std::size_t> best{{}, 0};
    for (const fs::path& file : files) {
        std::ifstream in(file);
        std::string line;
        std::size_t triangles = 0;
        while (std::getline(in, line)) {
            const std::size_t start = line.find_first_not_of(" \t");
            if (start == std::string::npos || line[start] != 'f' || start + 1 >= line.size() ||
                (line[start + 1] != ' ' && line[start + 1] != '\t'))
                continue;
            std::size_t corners = 0;
            bool inWord = false;
            for (std::size_t i = start + 1; i < line.size(); ++i) {
                const bool space = line[i] == ' ' || line[i] == '\t' || line[i] == '\r';
                corners += !space && !inWord;
                inWord = !space;
            }
            if (corners >= 3) triangles += corners - 2;
        }
        if (triangles > best.second) best = {file, triangles};
    }
    return best;
}

// Writes a unit icosphere as an OBJ with normals: each of the icosahedron's 20 faces cut into n²
// triangles (a frequency-n geodesic grid), n = round(√(triangles / 20)), the points pushed out onto
// the sphere. Faces wind counter-clockwise seen from outside. Returns the triangle count, 20·n².
std::size_t writeIcosphereObj(const fs::path& path, std::size_t targetTriangles) {
    const int n = std::clamp(static_cast<int>(std::lround(std::sqrt(targetTriangles / 20.0))), 1, 4095);
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    const std::array<vec3, 12> corners = {vec3(-1, t, 0), vec3(1, t, 0), vec3(-1, -t, 0), vec3(1, -t, 0),
                                          vec3(0, -1, t), vec3(0, 1, t), vec3(0, -1, -t), vec3(0, 1, -t),
                                          vec3(t, 0, -1), vec3(t, 0, 1), vec3(-t, 0, -1), vec3(-t, 0, 1)};
    const int faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                              {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                              {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                              {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};

    // A grid point is named by its integer weights on the icosahedron's corners, so a point on an edge
    // shared by two faces is found again, not duplicated: key = sorted (corner, weight) pairs, 16 bits each.
    std::unordered_map<std::uint64_t, std::uint32_t> pointIndex;
    std::vector<vec3> points;
    std::vector<std::uint32_t> indices;
    indices.reserve(static_cast<std::size_t>(60) * n * n);
    auto gridPoint = [&](const int corner[3], int wA, int wB, int wC) {
        std::array<std::pair<int, int>, 3> weights = {{{corner[0], wA}, {corner[1], wB}, {corner[2], wC}}};
        for (auto& [c, w] : weights)
            if (w == 0) c = 15;  // absent corners sort last, all alike
        std::sort(weights.begin(), weights.end());
        std::uint64_t key = 0;
        for (const auto& [c, w] : weights)
            key = (key << 20) | (static_cast<std::uint64_t>(c) << 16) | w;
        auto [it, inserted] = pointIndex.try_emplace(key, static_cast<std::uint32_t>(points.size()));
        if (inserted) {
            vec3 p(0.0f);
            for (const auto& [c, w] : weights)
                if (w) p += static_cast<float>(w) * corners[c];
            points.push_back(normalize(p));
        }
        return it->second;
    };
    for (const auto& face : faces) {
        int corner[3] = {face[0], face[1], face[2]};
        const vec3 A = corners[corner[0]], B = corners[corner[1]], C = corners[corner[2]];
        if (dot(cross(B - A, C - A), A + B + C) < 0.0f) std::swap(corner[1], corner[2]);
        // P(a, b) = ((n − a − b)·A + a·B + b·C) / n; both triangle shapes of the grid keep the face's
        // winding.
        auto P = [&](int a, int b) { return gridPoint(corner, n - a - b, a, b); };
        for (int b = 0; b < n; ++b)
            for (int a = 0; a + b < n; ++a) {
                indices.insert(indices.end(), {P(a, b), P(a + 1, b), P(a, b + 1)});
                if (a + b + 2 <= n)
                    indices.insert(indices.end(), {P(a + 1, b), P(a + 1, b + 1), P(a, b + 1)});
            }
    }

    // The OBJ text: on the unit sphere the normal is the position.
    std::string text = "# icosphere, frequency " + std::to_string(n) + ", written by facet bench\n";
    char number[32];
    auto append = [&](float v) {
        text += ' ';
        text.append(number, std::to_chars(number, number + sizeof number, v).ptr);
    };
    for (const char* kind : {"v", "vn"})
        for (const vec3& p : points) {
            text += kind;
            append(p.x);
            append(p.y);
            append(p.z);
            text += '\n';
        }
    for (std::size_t i = 0; i < indices.size(); i += 3) {
        text += 'f';
        for (int k = 0; k < 3; ++k) {
            const std::string index = std::to_string(indices[i + k] + 1);
            text += ' ';
            text += index;
            text += "//";
            text += index;
        }
        text += '\n';
    }
    std::ofstream(path, std::ios::binary) << text;
    return indices.size() / 3;
}

// A folder for the generated models, removed with everything in it at the end.
class TempFolder {
  public:
    TempFolder() : path_(fs::temp_directory_path() / ("facet-bench-" + std::to_string(::getpid()))) {
        fs::remove_all(path_);
        fs::create_directories(path_);
    }
    ~TempFolder() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;
    const fs::path& path() const { return path_; }

  private:
    fs::path path_;
};

// The benchmark's lighting: one white point light above and to the left of the eye, at half the eye's
// distance to the target (so it lights every model from the same direction whatever its size), in place
// of the renderer's default directional key light. Both renderers read these uniforms.
void useOnePointLight(PreparedScene& prepared) {
    const Camera& camera = prepared.camera;
    const float distance = length(camera.target - camera.eye);
    const vec3 positionWorld =
        vec3(inverse(camera.viewFromWorld) * vec4(-0.5f * distance, 0.5f * distance, 0.0f, 1.0f));
    LightSpec light;
    light.type = LightType::Point;
    light.position = positionWorld;
    prepared.scene.lights = {light};
    LightParams eyeSpace;  // lights live in eye space in the uniforms
    eyeSpace.kind = LightKind::Point;
    eyeSpace.position = vec3(camera.viewFromWorld * vec4(positionWorld, 1.0f));
    eyeSpace.diffuse = eyeSpace.specular = vec3(1.0f);  // white: linear 1
    for (PreparedDraw& draw : prepared.draws) {
        draw.uniforms.lightCount = 1;
        draw.uniforms.lights[0] = eyeSpace;
    }
}

PreparedScene prepareBenchScene(const BenchScene& bench) {
    Scene scene = sceneForModel(bench.model);
    scene.width = bench.width;
    scene.height = bench.height;
    PreparedScene prepared = prepareScene(scene);
    useOnePointLight(prepared);
    return prepared;
}

// Facet's memory for one scene, measured before Mesa is loaded (Mesa would share the process): the
// resident-set peak while a fresh DrawContext and Framebuffer render two frames of the loaded scene.
void measureFacetMemory(BenchScene& bench, int threads) {
    trimHeap();
    bench.beforeMiB = statusMiB("VmRSS");
    const PreparedScene prepared = prepareBenchScene(bench);
    trimHeap();  // the importer's temporaries
    bench.triangles = prepared.triangleCount;
    std::size_t meshBytes = 0, textureBytes = 0;
    for (const PreparedDraw& draw : prepared.draws)
        meshBytes += draw.vertices.size() * sizeof(MeshVertex) + draw.indices.size() * sizeof(std::uint32_t);
    for (const auto& texture : prepared.textures)
        textureBytes += texture->bytes();
    bench.meshMiB = static_cast<double>(meshBytes) / kMiB;
    bench.textureMiB = static_cast<double>(textureBytes) / kMiB;
    bench.framebufferMiB =
        static_cast<double>(bench.width) * bench.height * (sizeof(vec4) + sizeof(float)) / kMiB;

    const bool reset = resetPeakResidentSet();
    {
        DrawContext context(threads);
        Framebuffer framebuffer(bench.width, bench.height);
        renderFrame(prepared, framebuffer, context);
        renderFrame(prepared, framebuffer, context);
        if (reset) bench.peakMiB = statusMiB("VmHWM");
    }
}

// Where the two images differ, both are written beside the CSV for a look.
void writeDisagreement(const BenchScene& bench, const LinearImage& facet, const LinearImage& mesa,
                       const fs::path& folder, std::ostream& out) {
    const std::string stem =
        "bench-" + bench.name + "-" + std::to_string(bench.width) + "x" + std::to_string(bench.height);
    writeImage(folder / (stem + "-facet.png"), facet);
    writeImage(folder / (stem + "-mesa.png"), mesa);
    out << "    the images differ: see " << (folder / (stem + "-facet.png")).string() << " and "
        << (folder / (stem + "-mesa.png")).string() << "\n";
}

// Loads the scene into both renderers, warms both up, checks that their images agree, then times
// `frames` frames of each, alternating (and alternating which goes first) so that both see the same
// machine state. Uploads and the check are not timed.
void timeScene(BenchScene& bench, MesaPeer* mesa, DrawContext& context, int frames,
               const fs::path& imageFolder, std::ostream& out) {
    const PreparedScene prepared = prepareBenchScene(bench);
    Framebuffer framebuffer(bench.width, bench.height);
    if (mesa) mesa->load(toGlScene(prepared));
    for (int i = 0; i < kWarmUpFrames; ++i) {
        renderFrame(prepared, framebuffer, context);
        if (mesa) mesa->renderFrame();
    }

    // The same picture on both sides, or the times compare different work.
    if (mesa) {
        const LinearImage facetImage = toImage(framebuffer);
        const LinearImage mesaImage = mesa->readImage();
        const float tolerance = mesa->floatColor() ? 1e-5f : 0.5f / 255.0f + 1e-5f;
        bench.agreement = compareImages(facetImage, mesaImage, prepared.clearColor, tolerance);
        if (!bench.agreement->agrees()) writeDisagreement(bench, facetImage, mesaImage, imageFolder, out);
    }

    using Clock = std::chrono::steady_clock;
    std::vector<double> facetMs, facetCpuMs, mesaMs, mesaCpuMs;
    auto timeFacet = [&] {
        const double cpu = processCpuMs();
        const auto start = Clock::now();
        renderFrame(prepared, framebuffer, context);
        facetMs.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
        facetCpuMs.push_back(processCpuMs() - cpu);
    };
    auto timeMesa = [&] {
        const double cpu = processCpuMs();
        const auto start = Clock::now();
        mesa->renderFrame();
        mesaMs.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
        mesaCpuMs.push_back(processCpuMs() - cpu);
    };
    for (int i = 0; i < frames; ++i) {
        const bool mesaFirst = mesa && i % 2 == 1;
        if (mesaFirst) timeMesa();
        timeFacet();
        if (mesa && !mesaFirst) timeMesa();
    }
    bench.facetMs = median(facetMs);
    bench.facetCpuMs = median(facetCpuMs);
    if (mesa) {
        bench.mesaMs = median(mesaMs);
        bench.mesaCpuMs = median(mesaCpuMs);
        mesa->unload();
    }
}

// One line of times, memory and agreement per scene, then one of CPU time and image agreement.
void printScene(const BenchScene& bench, int nameWidth, std::ostream& out) {
    std::ostringstream size;
    size << bench.width << "x" << bench.height;
    out << std::fixed << "  " << std::left << std::setw(nameWidth) << bench.name << std::right
        << std::setw(10) << size.str() << std::setw(9) << bench.triangles << " tris   facet "
        << std::setprecision(2) << std::setw(7) << bench.facetMs << " ms";
    if (!std::isnan(bench.mesaMs))
        out << "   mesa " << std::setw(7) << bench.mesaMs << " ms   ratio " << bench.facetMs / bench.mesaMs;
    if (bench.peakMiB >= 0.0) {
        out << "   peak " << std::setprecision(0) << bench.peakMiB << " MiB, +"
            << bench.peakMiB - bench.beforeMiB << " for the scene (framebuffer " << std::setprecision(1)
            << bench.framebufferMiB << " MiB + mesh " << bench.meshMiB << " MiB";
        if (bench.textureMiB > 0.0) out << " + textures " << bench.textureMiB << " MiB";
        out << ")";
    }
    out << "\n"
        << std::string(2 + nameWidth, ' ') << std::setprecision(2) << "cpu/frame: facet " << bench.facetCpuMs
        << " ms";
    if (!std::isnan(bench.mesaCpuMs)) out << ", mesa " << bench.mesaCpuMs << " ms";
    if (bench.agreement) {
        const ImageAgreement& a = *bench.agreement;
        out << std::setprecision(3) << "   images " << (a.agrees() ? "agree" : "DIFFER") << ": coverage "
            << 100.0 * a.coverageAgreement << "% same, colour " << 100.0 * a.colorWithinTolerance
            << "% within " << std::setprecision(2) << ImageAgreement::kColorTolerance << ", mean |diff| "
            << std::defaultfloat << a.meanColorDifference;
    }
    out << std::endl;  // flushed: a long run shows its progress
}

// CSV --------------------------------------------------------------------------------------------------

void writeCsv(const fs::path& path, const std::vector<BenchScene>& scenes) {
    std::ostringstream text;
    text << "sweep,triangles,width,height,facet_ms,mesa_ms,ratio\n" << std::fixed << std::setprecision(3);
    for (const BenchScene& s : scenes) {
        if (s.sweep.empty()) continue;
        text << s.sweep << "," << s.triangles << "," << s.width << "," << s.height << "," << s.facetMs << ",";
        if (!std::isnan(s.mesaMs))
            text << s.mesaMs << "," << s.facetMs / s.mesaMs;
        else
            text << ",";
        text << "\n";
    }
    // Written beside the destination and renamed into place, like the images.
    const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::error_code error;
    fs::create_directories(folder, error);
    std::string tempName = ".";  // hidden, and named by process ("out/.bench-scaling.csv.tmp-1234")
    tempName += path.filename().string();
    tempName += ".tmp-" + std::to_string(::getpid());
    const fs::path temp = folder / tempName;
    {
        std::ofstream file(temp, std::ios::binary);
        file << text.str();
        if (!file.flush()) {
            fs::remove(temp, error);
            throw InputError(path.string() + ": cannot write");
        }
    }
    fs::rename(temp, path, error);
    if (error) {
        fs::remove(temp, error);
        throw InputError(path.string() + ": cannot write");
    }
}

// Chart ------------------------------------------------------------------------------------------------
// Drawn by hand into a LinearImage: lines, discs, rectangles and a 5×7 bitmap font.

struct Glyph {
    char c;
    std::array<std::uint8_t, 7> rows;  // top to bottom, bit 4 is the leftmost column
};

// The classic 5×7 character-LCD shapes: digits, capitals and a little punctuation (lower case is drawn
// as upper case).
constexpr Glyph kFont[] = {
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}}, {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}}, {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}}, {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}}, {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}}, {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'A', {0x0E, 0x11, 0x11, 0x11, 0x1F, 0x11, 0x11}}, {'B', {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E}},
    {'C', {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}}, {'D', {0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C}},
    {'E', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}}, {'F', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10}},
    {'G', {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}}, {'H', {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
    {'I', {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}}, {'J', {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C}},
    {'K', {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}}, {'L', {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F}},
    {'M', {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}}, {'N', {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}},
    {'O', {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}}, {'P', {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10}},
    {'Q', {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D}}, {'R', {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11}},
    {'S', {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}}, {'T', {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},
    {'U', {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}}, {'V', {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04}},
    {'W', {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A}}, {'X', {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11}},
    {'Y', {0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04}}, {'Z', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}}, {',', {0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08}},
    {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}}, {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}},
    {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}}, {'/', {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00}},
    {':', {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}}, {'%', {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03}},
    {'=', {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}}, {'<', {0x02, 0x04, 0x08, 0x10, 0x08, 0x04, 0x02}},
    {'>', {0x08, 0x04, 0x02, 0x01, 0x02, 0x04, 0x08}},
};

// A colour given as 8-bit sRGB, as a colour picker shows it, in the image's linear light.
vec4 srgb8(int r, int g, int b) {
    return vec4(srgbToLinear(r / 255.0f), srgbToLinear(g / 255.0f), srgbToLinear(b / 255.0f), 1.0f);
}

class Canvas {
  public:
    Canvas(int width, int height, vec4 background) {
        image_.width = width;
        image_.height = height;
        image_.pixels.assign(static_cast<std::size_t>(width) * height, background);
    }
    const LinearImage& image() const { return image_; }

    void fillRect(int x0, int y0, int x1, int y1, vec4 color) {  // [x0, x1) × [y0, y1)
        for (int y = std::max(y0, 0); y < std::min(y1, image_.height); ++y)
            for (int x = std::max(x0, 0); x < std::min(x1, image_.width); ++x)
                image_.at(x, y) = color;
    }
    void disc(vec2 centre, float radius, vec4 color) {
        for (int y = static_cast<int>(std::floor(centre.y - radius)); y <= centre.y + radius; ++y)
            for (int x = static_cast<int>(std::floor(centre.x - radius)); x <= centre.x + radius; ++x) {
                const vec2 d = vec2(x + 0.5f, y + 0.5f) - centre;
                if (dot(d, d) <= radius * radius) fillRect(x, y, x + 1, y + 1, color);
            }
    }
    void line(vec2 a, vec2 b, float width, vec4 color) {  // discs stamped every half pixel
        const int steps = std::max(1, static_cast<int>(std::ceil(2.0f * length(b - a))));
        for (int i = 0; i <= steps; ++i)
            disc(mix(a, b, static_cast<float>(i) / steps), 0.5f * width, color);
    }
    static int textWidth(std::string_view text, int scale) {
        return static_cast<int>(text.size()) * 6 * scale;
    }
    void text(int x, int y, std::string_view text, int scale, vec4 color) {  // (x, y): top left
        for (const char raw : text) {
            const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(raw)));
            for (const Glyph& glyph : kFont) {
                if (glyph.c != c) continue;
                for (int row = 0; row < 7; ++row)
                    for (int column = 0; column < 5; ++column)
                        if (glyph.rows[row] & (0x10 >> column))
                            fillRect(x + column * scale, y + row * scale, x + (column + 1) * scale,
                                     y + (row + 1) * scale, color);
            }
            x += 6 * scale;
        }
    }

  private:
    LinearImage image_;
};

struct Series {
    std::string name;
    vec4 color;
    std::vector<dvec2> points;  // data units
};

// 1, 2 or 5 times a power of ten, about range / ticks.
double niceStep(double range, int ticks) {
    const double raw = range / ticks;
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    const double normal = raw / magnitude;
    return (normal <= 1.0 ? 1.0 : normal <= 2.0 ? 2.0 : normal <= 5.0 ? 5.0 : 10.0) * magnitude;
}

std::string formatTick(double value, double step) {
    const int decimals = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
    std::ostringstream text;
    text << std::fixed << std::setprecision(decimals) << value;
    return text.str();
}

std::string formatCount(double value) {  // 1000 → "1K", 1000000 → "1M"
    if (value >= 1e6) return formatTick(value / 1e6, 1.0) + "M";
    if (value >= 1e3) return formatTick(value / 1e3, 1.0) + "K";
    return formatTick(value, 1.0);
}

// One panel: y = ms from 0, x linear from 0 or logarithmic over decades; a line with point markers per
// series, grid lines at the ticks, a legend in the top-left corner of the plot.
void drawPanel(Canvas& canvas, int left, int top, int width, int height, const std::string& title,
               const std::string& xLabel, bool logX, const std::vector<Series>& series) {
    const vec4 ink = srgb8(20, 20, 20), grid = srgb8(225, 225, 225);
    const int plotLeft = left + 80, plotRight = left + width - 40;
    const int plotTop = top + 40, plotBottom = top + height - 60;
    canvas.text(left + (width - Canvas::textWidth(title, 2)) / 2, top + 8, title, 2, ink);

    // Ranges and ticks.
    double maxX = 0.0, minX = std::numeric_limits<double>::max(), maxY = 0.0;
    for (const Series& s : series)
        for (const dvec2& p : s.points) {
            if (std::isnan(p.y)) continue;
            maxX = std::max(maxX, p.x);
            minX = std::min(minX, p.x);
            maxY = std::max(maxY, p.y);
        }
    if (maxY <= 0.0 || maxX <= 0.0) return;
    const double yStep = niceStep(1.05 * maxY, 5);
    const double yMax = std::ceil(1.05 * maxY / yStep) * yStep;
    double xLow = 0.0, xHigh = 0.0, xStep = 0.0;
    if (logX) {
        xLow = std::log10(minX) - 0.15;
        xHigh = std::log10(maxX) + 0.15;
    } else {
        xStep = niceStep(maxX, 5);
        xHigh = std::ceil(1.02 * maxX / xStep) * xStep;
    }
    auto toPixel = [&](dvec2 p) {
        const double x = logX ? std::log10(p.x) : p.x;
        return vec2(static_cast<float>(plotLeft + (x - xLow) / (xHigh - xLow) * (plotRight - plotLeft)),
                    static_cast<float>(plotBottom - p.y / yMax * (plotBottom - plotTop)));
    };

    // Grid, axes and tick labels.
    for (double y = 0.0; y <= yMax + 0.5 * yStep; y += yStep) {
        const int py = static_cast<int>(std::lround(toPixel({logX ? 1.0 : 0.0, y}).y));
        canvas.fillRect(plotLeft, py, plotRight, py + 1, grid);
        const std::string label = formatTick(y, yStep);
        canvas.text(plotLeft - 10 - Canvas::textWidth(label, 2), py - 7, label, 2, ink);
    }
    std::vector<std::pair<double, std::string>> xTicks;
    if (logX) {
        for (int decade = static_cast<int>(std::ceil(xLow)); decade <= xHigh; ++decade)
            xTicks.emplace_back(std::pow(10.0, decade), formatCount(std::pow(10.0, decade)));
    } else {
        for (double x = 0.0; x <= xHigh + 0.5 * xStep; x += xStep)
            xTicks.emplace_back(x, formatTick(x, xStep));
    }
    for (const auto& [x, label] : xTicks) {
        const int px = static_cast<int>(std::lround(toPixel({x, 0.0}).x));
        canvas.fillRect(px, plotTop, px + 1, plotBottom, grid);
        canvas.fillRect(px, plotBottom, px + 1, plotBottom + 6, ink);
        canvas.text(px - Canvas::textWidth(label, 2) / 2, plotBottom + 12, label, 2, ink);
    }
    canvas.fillRect(plotLeft, plotTop, plotLeft + 2, plotBottom + 1, ink);
    canvas.fillRect(plotLeft, plotBottom, plotRight, plotBottom + 2, ink);
    canvas.text(plotLeft + (plotRight - plotLeft - Canvas::textWidth(xLabel, 2)) / 2, plotBottom + 36, xLabel,
                2, ink);
    canvas.text(left + 4, plotTop - 22, "MS", 2, ink);

    // Series, then the legend.
    int legendY = plotTop + 12;
    for (const Series& s : series) {
        std::vector<vec2> pixels;
        for (const dvec2& p : s.points)
            if (!std::isnan(p.y)) pixels.push_back(toPixel(p));
        if (pixels.empty()) continue;
        for (std::size_t i = 1; i < pixels.size(); ++i)
            canvas.line(pixels[i - 1], pixels[i], 3.0f, s.color);
        for (const vec2& p : pixels)
            canvas.disc(p, 6.0f, s.color);
        canvas.line(vec2(plotLeft + 16, legendY + 7), vec2(plotLeft + 56, legendY + 7), 3.0f, s.color);
        canvas.disc(vec2(plotLeft + 36, legendY + 7), 6.0f, s.color);
        canvas.text(plotLeft + 68, legendY, s.name, 2, ink);
        legendY += 26;
    }
}

LinearImage drawScalingChart(const std::vector<BenchScene>& scenes, int threads, bool withMesa,
                             const std::string& resolutionModel) {
    const vec4 facetColor = srgb8(230, 110, 20), mesaColor = srgb8(40, 100, 200), ink = srgb8(20, 20, 20);
    Canvas canvas(kChartWidth, kChartHeight, vec4(1.0f));
    const std::string heading = std::string(withMesa ? "FACET VS MESA LLVMPIPE" : "FACET (MESA NOT FOUND)") +
                                ": MEDIAN MS PER FRAME, " + std::to_string(threads) +
                                (threads == 1 ? " THREAD" : " THREADS") + (withMesa ? " EACH" : "");
    canvas.text((kChartWidth - Canvas::textWidth(heading, 3)) / 2, 14, heading, 3, ink);

    auto seriesOf = [&](const std::string& sweep, bool triangles) {
        std::vector<Series> series = {{"FACET", facetColor, {}}};
        if (withMesa) series.push_back({"MESA LLVMPIPE", mesaColor, {}});
        for (const BenchScene& s : scenes) {
            if (s.sweep != sweep) continue;
            const double x = triangles ? static_cast<double>(s.triangles) : s.width * double(s.height) / 1e6;
            series[0].points.emplace_back(x, s.facetMs);
            if (withMesa) series[1].points.emplace_back(x, s.mesaMs);
        }
        return series;
    };
    const int panelWidth = kChartWidth / 2, panelTop = 50, panelHeight = kChartHeight - panelTop;
    drawPanel(canvas, 0, panelTop, panelWidth, panelHeight, "TRIANGLES: ICOSPHERE AT 1920X1080",
              "TRIANGLES (LOG SCALE)", true, seriesOf("triangles", true));
    drawPanel(canvas, panelWidth, panelTop, panelWidth, panelHeight, "RESOLUTION: " + resolutionModel,
              "MEGAPIXELS", false, seriesOf("resolution", false));
    return canvas.image();
}

}  // namespace

void runMesaComparison(const BenchOptions& options, std::ostream& out) {
    if (options.frames < 1) throw InputError("--frames must be at least 1");
    if (options.model.extension() != ".obj")
        throw InputError(options.model.string() +
                         ": --vs-mesa takes an OBJ model (it builds the scenes itself)");
    checkImageDestination(options.chart, kChartWidth, kChartHeight);
    if (!fs::is_directory(options.sharedModels))
        throw InputError(options.sharedModels.string() +
                         ": no such folder (the benchmark's models; run facet from the repository's folder)");
    const int threads = options.threads > 0
                            ? options.threads
                            : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    const CpuLimit cpuLimit(threads);  // before any thread is started, so that every thread inherits it
    trimHeap();
    const double startMiB = statusMiB("VmRSS");

    // 1. The scenes: three named ones, then the two sweeps.
    TempFolder temp;
    const std::string mainName = options.model.stem().string();
    const auto [largest, largestTriangles] = largestModel(options.sharedModels);
    if (largest.empty()) throw InputError(options.sharedModels.string() + ": no OBJ models found");
    std::vector<BenchScene> scenes;
    scenes.push_back(benchScene(mainName, "", options.model, 1920, 1080));
    scenes.push_back(benchScene(largest.stem().string(), "", largest, 1920, 1080));
    scenes.push_back(benchScene(options.smallModel.stem().string(), "", options.smallModel, 3840, 2160));
    const std::vector<std::size_t> triangleSweep =
        options.quick ? std::vector<std::size_t>{1000, 16000, 256000}
                      : std::vector<std::size_t>{1000, 4000, 16000, 64000, 256000, 1000000};
    for (const std::size_t triangles : triangleSweep) {
        const fs::path path = temp.path() / ("icosphere-" + std::to_string(triangles) + ".obj");
        writeIcosphereObj(path, triangles);
        scenes.push_back(benchScene("icosphere", "triangles", path, 1920, 1080));
    }
    const std::vector<std::pair<int, int>> resolutions =
        options.quick ? std::vector<std::pair<int, int>>{{640, 480}, {1920, 1080}, {3840, 2160}}
                      : std::vector<std::pair<int, int>>{
                            {640, 480}, {1280, 720}, {1920, 1080}, {2560, 1440}, {3840, 2160}};
    for (const auto& [width, height] : resolutions)
        scenes.push_back(benchScene(mainName, "resolution", options.model, width, height));

    // 2. Facet's memory, scene by scene, before Mesa is loaded into the process.
    std::ostringstream cpus;
    if (cpuLimit.limited())
        cpus << "limited to " << cpuLimit.cpus() << " of the " << cpuLimit.available()
             << " this process may use (sched_setaffinity): neither renderer can keep more than " << threads
             << " busy";
    else
        cpus << "all " << cpuLimit.available() << " this process may use";
    out << "facet bench --vs-mesa: Facet and Mesa llvmpipe render the same scenes, frames alternating\n"
        << "threads    " << threads << " each" << (options.threads > 0 ? "" : " (the hardware's count)")
        << ": Facet DrawContext(" << threads
        << "), llvmpipe LP_NUM_THREADS=" << MesaPeer::lpNumThreads(threads)
        << (threads == 1 ? " (bins and rasterizes on the calling thread; 1 would add a raster thread)" : "")
        << "\ncpus       " << cpus.str() << "\n"
        << "frames     " << options.frames << " timed per renderer after " << kWarmUpFrames
        << " warm-up frames each; median ms per frame; ratio = facet / mesa (< 1: Facet faster)\n"
        << "scenes     built-in per-pixel Lambert + Blinn-Phong, one white point light above left of the "
           "eye;\n"
        << "           back faces culled, depth test LESS, colour + depth cleared every frame\n"
        << "largest    " << largest.string() << " (" << largestTriangles << " triangles in "
        << options.sharedModels.string() << ")\n"
        << "peak       the process's resident-set peak during Facet's render, measured before Mesa is "
           "loaded;\n"
        << "           +N: over the resident set before the scene was loaded (" << std::fixed
        << std::setprecision(0) << startMiB << " MiB before any scene, mostly shared libraries)" << std::endl;
    for (BenchScene& bench : scenes)
        measureFacetMemory(bench, threads);

    // 3. Mesa.
    std::string whyNot;
    MesaOptions mesaOptions;
    mesaOptions.driver = MesaDriver::Llvmpipe;
    mesaOptions.threads = threads;
    std::unique_ptr<MesaPeer> mesa = MesaPeer::open(mesaOptions, whyNot);
    if (mesa) {
        out << "mesa       " << mesa->renderer() << ", OpenGL " << mesa->version() << "\n"
            << "target     both draw into "
            << (mesa->floatColor()
                    ? "float RGBA colour + float depth (Mesa: an RGBA32F framebuffer object)\n"
                    : "their own buffers; Mesa's colour is 8-bit RGBA (no float format here)\n");
    } else {
        out << "Mesa llvmpipe (OSMesa) not found: install libosmesa6 to compare; Facet alone:\n"
            << "           (" << whyNot << ")\n";
    }

    // 4. The frames.
    DrawContext context(threads);
    const fs::path imageFolder = options.csv.has_parent_path() ? options.csv.parent_path() : fs::path(".");
    std::string section = "-";
    int nameWidth = 0;
    for (const BenchScene& bench : scenes)
        nameWidth = std::max(nameWidth, static_cast<int>(bench.name.size()));
    for (BenchScene& bench : scenes) {
        if (bench.sweep != section) {
            section = bench.sweep;
            if (section.empty()) out << "scenes\n";
            if (section == "triangles") out << "triangle sweep: icospheres at 1920x1080\n";
            if (section == "resolution") out << "resolution sweep: " << mainName << "\n";
        }
        timeScene(bench, mesa.get(), context, options.frames, imageFolder, out);
        printScene(bench, nameWidth, out);
    }

    // 5. The sweeps as CSV and chart.
    writeCsv(options.csv, scenes);
    writeImage(options.chart, drawScalingChart(scenes, threads, mesa != nullptr, mainName));
    out << "wrote " << options.csv.string() << " and " << options.chart.string() << "\n";
}

// ---------------------------------------------------------------------------------------------------
// facet bench --sort

namespace {

constexpr std::size_t kSortMinTriangles = 50000;
constexpr double kSortStepsDegrees[] = {6.0, 1.0, 0.3, 0.1, 0.03, 0.01};
constexpr double kSortStepBudgetMs = 5000.0;  // timed sorting per step, after at least kSortMinFrames
constexpr int kSortMinFrames = 5;
constexpr double kSortKeyStepDegrees = 1.0;  // the step of the "sort key" comparison
constexpr int kSortKeyFrames = 20;

// The model on a turntable: each frame it turns about the vertical axis (the camera's up) through the
// centre of its bounding box, in world space, and the camera stays where prepareScene framed it.
class Turntable {
  public:
    explicit Turntable(const PreparedScene& prepared) : prepared_(prepared) {
        const mat4 worldFromView = inverse(prepared.camera.viewFromWorld);
        Bounds bounds{vec3(std::numeric_limits<float>::max()), vec3(-std::numeric_limits<float>::max())};
        for (const PreparedDraw& draw : prepared.draws) {
            worldFromObject_.push_back(worldFromView * draw.uniforms.viewFromObject);
            for (const MeshVertex& vertex : draw.vertices) {
                const vec3 p(worldFromObject_.back() * vec4(vertex.position, 1.0f));
                bounds.min = glm::min(bounds.min, p);
                bounds.max = glm::max(bounds.max, p);
            }
            triangles_ += draw.indices.size() / 3;
        }
        centre_ = bounds.centre();
        axis_ = normalize(prepared.camera.up);
    }

    std::size_t triangles() const { return triangles_; }

    // One key per triangle, draw after draw: −z_view of its centroid (the mean of its corners' depths,
    // as the view transform is affine) or of its farthest corner. Larger is farther.
    void keys(double angleDegrees, SortKey kind, std::vector<float>& keys) {
        const mat4 turn = prepared_.camera.viewFromWorld * glm::translate(mat4(1.0f), centre_) *
                          glm::rotate(mat4(1.0f), static_cast<float>(glm::radians(angleDegrees)), axis_) *
                          glm::translate(mat4(1.0f), -centre_);
        keys.resize(triangles_);
        std::size_t k = 0;
        for (std::size_t d = 0; d < prepared_.draws.size(); ++d) {
            const PreparedDraw& draw = prepared_.draws[d];
            const mat4 viewFromObject = turn * worldFromObject_[d];
            const vec4 depthRow(viewFromObject[0][2], viewFromObject[1][2], viewFromObject[2][2],
                                viewFromObject[3][2]);
            depth_.resize(draw.vertices.size());
            for (std::size_t v = 0; v < draw.vertices.size(); ++v) {
                const vec3& p = draw.vertices[v].position;
                depth_[v] = depthRow.x * p.x + depthRow.y * p.y + depthRow.z * p.z + depthRow.w;
            }
            const std::uint32_t* index = draw.indices.data();
            const std::size_t count = draw.indices.size() / 3;
            if (kind == SortKey::Centroid)
                for (std::size_t t = 0; t < count; ++t, index += 3)
                    keys[k++] = -(depth_[index[0]] + depth_[index[1]] + depth_[index[2]]) * (1.0f / 3.0f);
            else
                for (std::size_t t = 0; t < count; ++t, index += 3)
                    keys[k++] = -std::min({depth_[index[0]], depth_[index[1]], depth_[index[2]]});
        }
    }

  private:
    const PreparedScene& prepared_;
    std::vector<mat4> worldFromObject_;  // per draw
    vec3 centre_{0.0f}, axis_{0.0f, 1.0f, 0.0f};
    std::size_t triangles_ = 0;
    std::vector<float> depth_;  // view-space z per vertex of the current draw
};

// CPU time of the calling thread: on a machine shared with other work, wall-clock time would charge a
// long sort for the time slices other processes take in the middle of it, and a short one far less often.
double threadCpuMs() {
    timespec now{};
    ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) * 1e3 + static_cast<double>(now.tv_nsec) * 1e-6;
}

bool backToFront(std::span<const std::uint32_t> order, const std::vector<float>& keys) {
    for (std::size_t i = 1; i < order.size(); ++i)
        if (keys[order[i - 1]] < keys[order[i]]) return false;  // the model's keys are never NaN
    return true;
}

struct SortStep {
    double degrees = 0.0;
    int frames = 0;
    double keyMs = 0.0, insertionMs = 0.0, scratchMs = 0.0, radixMs = 0.0;
    double insertionComparisons = 0.0, insertionMoves = 0.0, scratchComparisons = 0.0;
    bool sorted = true;  // every order came out back to front
};

// Turns the model by `degrees` per frame from 0: one untimed warm-up frame (the insertion sorter's
// first, from scratch), then up to `frames` timed frames, the two sorts alternating which goes first.
SortStep timeSortStep(Turntable& turntable, double degrees, int frames) {
    SortStep step;
    step.degrees = degrees;
    TransparencySorter insertion, scratch, radix;
    SortStats stats;
    std::vector<float> keys;
    turntable.keys(0.0, SortKey::Centroid, keys);
    insertion.sort(keys, SortAlgorithm::InsertionWithMemory, stats);
    scratch.sort(keys, SortAlgorithm::FromScratch, stats);
    radix.sort(keys, SortAlgorithm::RadixFromScratch, stats);

    std::vector<double> keyMs, insertionMs, scratchMs, radixMs, insertionComparisons, insertionMoves,
        scratchComparisons;
    double spentMs = 0.0;
    for (int frame = 1; frame <= frames; ++frame) {
        const double keyStart = threadCpuMs();
        turntable.keys(frame * degrees, SortKey::Centroid, keys);
        keyMs.push_back(threadCpuMs() - keyStart);

        auto timeInsertion = [&] {
            const double start = threadCpuMs();
            const auto order = insertion.sort(keys, SortAlgorithm::InsertionWithMemory, stats);
            insertionMs.push_back(threadCpuMs() - start);
            insertionComparisons.push_back(static_cast<double>(stats.comparisons));
            insertionMoves.push_back(static_cast<double>(stats.moves));
            step.sorted = step.sorted && !stats.fromScratch && backToFront(order, keys);
        };
        auto timeScratch = [&] {
            const double start = threadCpuMs();
            const auto order = scratch.sort(keys, SortAlgorithm::FromScratch, stats);
            scratchMs.push_back(threadCpuMs() - start);
            scratchComparisons.push_back(static_cast<double>(stats.comparisons));
            step.sorted = step.sorted && backToFront(order, keys);
        };
        auto timeRadix = [&] {
            const double start = threadCpuMs();
            const auto order = radix.sort(keys, SortAlgorithm::RadixFromScratch, stats);
            radixMs.push_back(threadCpuMs() - start);
            step.sorted = step.sorted && backToFront(order, keys);
        };
        switch (frame % 3) {  // each goes first in turn
            case 0:
                timeInsertion();
                timeScratch();
                timeRadix();
                break;
            case 1:
                timeScratch();
                timeRadix();
                timeInsertion();
                break;
            default:
                timeRadix();
                timeInsertion();
                timeScratch();
                break;
        }
        step.frames = frame;
        spentMs += insertionMs.back() + scratchMs.back() + radixMs.back();
        if (spentMs > kSortStepBudgetMs && frame >= kSortMinFrames) break;
    }
    step.keyMs = median(keyMs);
    step.insertionMs = median(insertionMs);
    step.scratchMs = median(scratchMs);
    step.radixMs = median(radixMs);
    step.insertionComparisons = median(insertionComparisons);
    step.insertionMoves = median(insertionMoves);
    step.scratchComparisons = median(scratchComparisons);
    return step;
}

std::string degreesText(double degrees) {
    std::ostringstream text;
    text << degrees << " deg";
    return text.str();
}

// "12.3 M", "45.6 k", "789": a count per frame, short.
std::string countText(double count) {
    std::ostringstream text;
    text << std::fixed << std::setprecision(count >= 1e5 ? 1 : 0);
    if (count >= 1e6)
        text << count / 1e6 << " M";
    else if (count >= 1e5)
        text << count / 1e3 << " k";
    else
        text << count;
    return text.str();
}

}  // namespace

void runSortBench(const BenchOptions& options, std::ostream& out) {
    if (options.frames < 1) throw InputError("--frames must be at least 1");
    const PreparedScene prepared = prepareScene(loadSceneOrModel(options.model));
    Turntable turntable(prepared);
    const std::size_t n = turntable.triangles();
    if (n < kSortMinTriangles)
        throw InputError(options.model.string() + " has " + std::to_string(n) +
                         " triangles; bench --sort needs a model with at least " +
                         std::to_string(kSortMinTriangles) + " (the Stanford bunny has 69451)");

    out << "Per frame of a turntable, every triangle's back-to-front order (key: view-space depth of its "
           "centroid)\nby insertion sort from the previous frame's order, by std::sort from scratch and by a "
           "radix sort from scratch;\none thread, medians.\n";
    out << std::fixed << std::setprecision(2);
    out << "model      " << options.model.string() << "\n";
    out << "triangles  " << n << ", all treated as transparent (one key each)\n";
    out << "turntable  about the vertical axis through the bounding box's centre, camera as facet render "
           "frames it\n";
    out << "frames     " << options.frames << " timed per step after 1 warm-up (fewer where a step's "
        << kSortStepBudgetMs / 1000.0 << " s budget runs out); sorts alternate going first\n";
    out << "times      ms of CPU time of the thread (time slices taken by other processes do not count); "
           "each "
           "sort's ms\n           include turning the keys into (key, index) pairs and writing the order "
           "out; "
           "keys ms is\n           computing the keys (vertex depths, then centroids), paid once for both\n";
    out << "moves      insertion sort's shifts (= inversions of the previous order); std::sort's element "
           "moves are\n           swaps inside partitions, not comparable, not counted\n\n";

    out << "  step/frame  frames  keys ms   insertion ms   std::sort ms   faster               "
           "insertion compares    moves   std::sort compares   radix ms\n";
    std::vector<SortStep> steps;
    for (const double degrees : kSortStepsDegrees) {
        const SortStep step = timeSortStep(turntable, degrees, options.frames);
        steps.push_back(step);
        const bool insertionWins = step.insertionMs < step.scratchMs;
        std::ostringstream faster;
        faster << std::fixed << std::setprecision(1) << (insertionWins ? "insertion " : "std::sort ")
               << (insertionWins ? step.scratchMs / step.insertionMs : step.insertionMs / step.scratchMs)
               << "x";
        out << std::setprecision(2) << std::setw(12) << degreesText(degrees) << std::setw(8) << step.frames
            << std::setw(9) << step.keyMs << std::setw(15) << step.insertionMs << std::setw(15)
            << step.scratchMs << "   " << std::left << std::setw(18) << faster.str() << std::right
            << std::setw(20) << countText(step.insertionComparisons) << std::setw(9)
            << countText(step.insertionMoves) << std::setw(21) << countText(step.scratchComparisons)
            << std::setw(11) << step.radixMs << (step.sorted ? "" : "   ORDER NOT BACK TO FRONT")
            << std::endl;
    }

    // Where the two cross: the ratio of the times interpolated in log-log between the two steps around 1.
    for (std::size_t i = 1; i < steps.size(); ++i) {
        const double a = std::log(steps[i - 1].insertionMs / steps[i - 1].scratchMs);
        const double b = std::log(steps[i].insertionMs / steps[i].scratchMs);
        if (a >= 0.0 && b < 0.0) {
            const double t = a / (a - b);
            const double degrees =
                std::exp(std::log(steps[i - 1].degrees) +
                         t * (std::log(steps[i].degrees) - std::log(steps[i - 1].degrees)));
            out << "break-even insertion with memory is the faster below about " << std::setprecision(2)
                << degrees << " deg per frame (interpolated)\n";
            break;
        }
    }

    // The other usual key: the farthest corner. What it costs, and how much its order differs: the pairs
    // the two keys put the other way round are the moves of an insertion sort that starts from the
    // centroid order and is given the farthest-vertex keys.
    std::vector<float> centroidKeys, farthestKeys;
    TransparencySorter centroidSorter, farthestSorter, crossSorter;
    SortStats stats;
    turntable.keys(0.0, SortKey::Centroid, centroidKeys);
    turntable.keys(0.0, SortKey::FarthestVertex, farthestKeys);
    centroidSorter.sort(centroidKeys, SortAlgorithm::InsertionWithMemory, stats);
    farthestSorter.sort(farthestKeys, SortAlgorithm::InsertionWithMemory, stats);
    std::vector<double> centroidKeyMs, farthestKeyMs, centroidMoves, farthestMoves, disagreeing;
    for (int frame = 1; frame <= std::min(options.frames, kSortKeyFrames); ++frame) {
        const double angle = frame * kSortKeyStepDegrees;
        for (int k = 0; k < 2; ++k) {  // alternating which goes first
            const bool centroid = (k + frame) % 2 == 0;
            const double start = threadCpuMs();
            turntable.keys(angle, centroid ? SortKey::Centroid : SortKey::FarthestVertex,
                           centroid ? centroidKeys : farthestKeys);
            (centroid ? centroidKeyMs : farthestKeyMs).push_back(threadCpuMs() - start);
        }
        centroidSorter.sort(centroidKeys, SortAlgorithm::InsertionWithMemory, stats);
        centroidMoves.push_back(static_cast<double>(stats.moves));
        farthestSorter.sort(farthestKeys, SortAlgorithm::InsertionWithMemory, stats);
        farthestMoves.push_back(static_cast<double>(stats.moves));
        crossSorter.forget();
        crossSorter.sort(centroidKeys, SortAlgorithm::InsertionWithMemory, stats);
        crossSorter.sort(farthestKeys, SortAlgorithm::InsertionWithMemory, stats);
        disagreeing.push_back(static_cast<double>(stats.moves));
    }
    const double pairs = 0.5 * static_cast<double>(n) * static_cast<double>(n - 1);
    out << "sort key   at " << degreesText(kSortKeyStepDegrees) << " per frame: centroid keys "
        << median(centroidKeyMs) << " ms, " << countText(median(centroidMoves))
        << " moves; farthest vertex keys " << median(farthestKeyMs) << " ms, "
        << countText(median(farthestMoves)) << " moves; the two keys order " << countText(median(disagreeing))
        << " pairs differently (" << std::setprecision(3) << 100.0 * median(disagreeing) / pairs
        << "% of all pairs)\n";
}

}  // namespace facet
