// facet bench --vs-mesa: Facet and Mesa's llvmpipe on the same scenes and sweeps, frames alternating.
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <memory>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include "base/errors.h"
#include "bench/bench.h"
#include "bench/chart.h"
#include "bench/process_stats.h"
#include "io/image_io.h"
#include "io/output_path.h"
#include "io/text_file.h"
#include "oracle/mesa_peer.h"
#include "render/frame_kernels.h"
#include "render/renderer.h"

namespace facet {

namespace {

namespace fs = std::filesystem;
using glm::dvec2;

constexpr int kChartWidth = 1400;
constexpr int kChartHeight = 640;

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
    // Facet's CPU time per frame on one thread, from frames taking turns with the others (NaN when the
    // bench runs on one thread): what the N-thread frame's CPU time is set against.
    double facetOneThreadCpuMs = std::numeric_limits<double>::quiet_NaN();
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
    light.type = LightKind::Point;
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
    std::size_t meshBytes = 0;
    for (const PreparedDraw& draw : prepared.draws)
        meshBytes += draw.vertices.size() * sizeof(MeshVertex) + draw.indices.size() * sizeof(std::uint32_t);
    const std::size_t textureBytes = prepared.assets->textureBytes;
    bench.meshMiB = static_cast<double>(meshBytes) / kMiB;
    bench.textureMiB = static_cast<double>(textureBytes) / kMiB;
    bench.framebufferMiB =
        static_cast<double>(bench.width) * bench.height * (sizeof(vec4) + sizeof(float)) / kMiB;

    const bool reset = resetPeakResidentSet();
    {
        DrawContext context(threads);
        Framebuffer framebuffer(bench.width, bench.height);
        FrameMemory memory;
        renderFrame(prepared, framebuffer, context, memory);
        renderFrame(prepared, framebuffer, context, memory);
        if (reset) bench.peakMiB = statusMiB("VmHWM");
    }
}

// The folder of the images of scenes where Facet and Mesa differ: the CSV's, or the chart's when the CSV
// goes to a device or standard output (never into /dev); empty when both do (no images then).
fs::path disagreementFolder(const BenchOptions& options) {
    for (const fs::path& output : {options.csv, options.chart}) {
        const OutputTarget target = classifyOutput(output);
        if (target.kind == OutputKind::AtomicFile)
            return target.path.has_parent_path() ? target.path.parent_path() : fs::path(".");
    }
    return {};
}

// Where the two images differ, both are written beside the CSV for a look.
void writeDisagreement(const BenchScene& bench, const LinearImage& facet, const LinearImage& mesa,
                       const fs::path& folder, std::ostream& out) {
    if (folder.empty()) return;
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
// With `oneThread`, Facet's frames on one thread take turns with them too (CPU time only).
void timeScene(BenchScene& bench, MesaPeer* mesa, DrawContext& context, DrawContext* oneThread, int frames,
               const fs::path& imageFolder, std::ostream& out) {
    const PreparedScene prepared = prepareBenchScene(bench);
    Framebuffer framebuffer(bench.width, bench.height);
    std::optional<Framebuffer> oneThreadFramebuffer;
    FrameMemory oneThreadMemory;
    if (oneThread) {
        oneThreadFramebuffer.emplace(bench.width, bench.height);
        for (int i = 0; i < kWarmUpFrames; ++i)
            renderFrame(prepared, *oneThreadFramebuffer, *oneThread, oneThreadMemory);
    }
    if (mesa) mesa->load(toGlScene(prepared));
    // Facet's frames as a loop of frames draws them (facet render --frames): the transparent triangles'
    // order and the plan's buffers kept from frame to frame (Mesa is given that order once, at load).
    FrameMemory memory;
    for (int i = 0; i < kWarmUpFrames; ++i) {
        renderFrame(prepared, framebuffer, context, memory);
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
    std::vector<double> facetMs, facetCpuMs, mesaMs, mesaCpuMs, oneThreadCpuMs;
    auto timeFacet = [&] {
        const double cpu = processCpuMs();
        const auto start = Clock::now();
        renderFrame(prepared, framebuffer, context, memory);
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
    auto timeFacetOneThread = [&] {
        const double cpu = processCpuMs();
        renderFrame(prepared, *oneThreadFramebuffer, *oneThread, oneThreadMemory);
        oneThreadCpuMs.push_back(processCpuMs() - cpu);
    };
    for (int i = 0; i < frames; ++i) {
        const bool mesaFirst = mesa && i % 2 == 1;
        if (mesaFirst) timeMesa();
        timeFacet();
        if (mesa && !mesaFirst) timeMesa();
        if (oneThread) timeFacetOneThread();
    }
    bench.facetMs = median(facetMs);
    bench.facetCpuMs = median(facetCpuMs);
    if (oneThread) bench.facetOneThreadCpuMs = median(oneThreadCpuMs);
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
    if (!std::isnan(bench.facetOneThreadCpuMs))
        out << " (" << bench.facetCpuMs / bench.facetOneThreadCpuMs << "x one thread's "
            << bench.facetOneThreadCpuMs << " ms)";
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
    // Written as the images are (io/output_path.h): a file beside the destination, renamed into place.
    const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::error_code error;
    if (classifyOutput(path).kind == OutputKind::AtomicFile) fs::create_directories(folder, error);
    writeTextFile(path, text.str());
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

void runMesaComparison(const BenchOptions& options, std::ostream& out) {
    if (options.frames < 1) throw InputError("--frames must be at least 1");
    if (options.model.extension() != ".obj")
        throw InputError(options.model.string() +
                         ": --vs-mesa takes an OBJ model (it builds the scenes itself)");
    // Every output checked before the benchmark's minute of work: the CSV (a file, a device, "-") and
    // the chart.
    checkOutput(options.csv, true);
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
        << coreHandoffLine(threads) << "code       Facet's frame compiled for " << describeFrameKernels()
        << "\n"
        << "frames     " << options.frames << " timed per renderer after " << kWarmUpFrames
        << " warm-up frames each; median ms per frame; ratio = facet / mesa (< 1: Facet faster)\n"
        << (threads > 1
                ? "cpu        every thread's CPU time per frame; (Rx one thread's): Facet's over its CPU "
                  "time on one thread,\n           from one-thread frames taking turns with the others "
                  "(1.00: no CPU spent waiting)\n"
                : "")
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
    std::optional<DrawContext> oneThread;
    if (context.pool.threads() > 1) oneThread.emplace(1);
    const fs::path imageFolder = disagreementFolder(options);
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
        timeScene(bench, mesa.get(), context, oneThread ? &*oneThread : nullptr, options.frames, imageFolder,
                  out);
        printScene(bench, nameWidth, out);
    }

    // 5. The sweeps as CSV and chart.
    writeCsv(options.csv, scenes);
    writeImage(options.chart, drawScalingChart(scenes, threads, mesa != nullptr, mainName));
    out << "wrote " << options.csv.string() << " and " << options.chart.string() << "\n";
}

}  // namespace facet
