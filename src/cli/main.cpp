// facet: renders OBJ models and scene files to images with the Facet software rasterizer.
#include <cfloat>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "base/errors.h"
#include "base/quote.h"
#include "bench/bench.h"
#include "oracle/compare.h"
#include "render/renderer.h"

namespace {

// Frame numbers stay within seven digits, so FIRST-LAST can never step past the largest int, and one
// run writes at most this many images (frames, times five with --components): a typo in --frames
// stops at once instead of filling the disk.
constexpr int kMaxFrameNumber = 9'999'999;
constexpr int kMaxImagesPerRun = 100'000;
constexpr int kMaxBenchFrames = 100'000;  // timed frames per measurement

// Command-line numbers, checked on the text before CLI11 converts it, so a bad value is named with
// what is expected rather than CLI11's "Could not convert" or "not in range".
CLI::Validator wholeNumber(long long lowest, long long highest) {
    const std::string range = "from " + std::to_string(lowest) + " to " + std::to_string(highest);
    return CLI::Validator(
        [lowest, highest, range](std::string& text) -> std::string {
            long long value = 0;
            const char* end = text.data() + text.size();
            const auto [stop, error] = std::from_chars(text.data(), end, value);
            if (error != std::errc() || stop != end || value < lowest || value > highest)
                return "expects a whole number " + range + " (got " + facet::inQuotes(text) + ")";
            return "";
        },
        "INT " + range);
}

// A whole number whose range the program checks afterwards with its own message (--width, --height).
const CLI::Validator kWholeNumber(
    [](std::string& text) -> std::string {
        int value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        if (error != std::errc() || stop != end)
            return "expects a whole number (got " + facet::inQuotes(text) + ")";
        return "";
    },
    "INT");

// Any finite number: "nan", "inf" and values beyond a float (1e39) are refused; each option checks
// its own range afterwards.
const CLI::Validator kFiniteNumber(
    [](std::string& text) -> std::string {
        char* stop = nullptr;
        const double value = std::strtod(text.c_str(), &stop);
        if (text.empty() || *stop != '\0' || !std::isfinite(value) || std::abs(value) > FLT_MAX)
            return "expects a finite number (got " + facet::inQuotes(text) + ")";
        return "";
    },
    "NUMBER");

// Parses "x,y,z" into a vec3; CLI11 hands us the raw text so the error can quote it.
glm::vec3 parseVec3(const std::string& option, const std::string& text) {
    std::stringstream in(text);
    glm::vec3 v;
    char comma1 = 0, comma2 = 0;
    if (!(in >> v.x >> comma1 >> v.y >> comma2 >> v.z) || comma1 != ',' || comma2 != ',' ||
        !(in >> std::ws).eof() || !std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        throw facet::InputError(option + " expects three numbers separated by commas, like 0,1.5,4 (got " +
                                facet::inQuotes(text) + ")");
    return v;
}

// `fromScene` names the scene file and key a side came from when the command line did not give it
// (the file itself never holds more than the limit, but its height with a --width can).
void checkSize(int width, int height, const std::string& fromScene = "") {
    for (auto [name, value] : {std::pair{"--width", width}, std::pair{"--height", height}})
        if (value < 1 || value > facet::kMaxImageSide)
            throw facet::InputError(std::string(name) + " must be between 1 and " +
                                    std::to_string(facet::kMaxImageSide) + " (got " + std::to_string(value) +
                                    ")");
    if (static_cast<long long>(width) * height > facet::kMaxPixels)
        throw facet::InputError("an image of " + std::to_string(width) + "x" + std::to_string(height) +
                                " pixels is larger than the limit of " + std::to_string(facet::kMaxPixels) +
                                " pixels" + fromScene);
}

// For checkSize: " (\"height\" from scenes/a.json)" when a side of the image comes from the scene file.
std::string sizeFromScene(const std::filesystem::path& input, bool widthGiven, bool heightGiven) {
    if (input.extension() != ".json" || (widthGiven && heightGiven)) return "";
    const std::string keys = widthGiven    ? "\"height\""
                             : heightGiven ? "\"width\""
                                           : "\"width\" and \"height\"";
    return " (" + keys + " from " + input.string() + ")";
}

struct RenderArgs {
    std::string input;
    std::string output;
    std::optional<int> width, height;
    std::optional<std::string> eye, target;
    std::optional<float> fovy;
    int threads = 0;
    bool quiet = false;
    std::optional<std::string> lighting, reflection, shading, only;
    std::optional<float> creaseAngle;
    bool components = false;
    std::optional<std::string> frames;  // "0-59"
    std::optional<float> turntable;     // degrees over the frames
    bool stats = false;
    std::optional<std::string> transparency, sortKey, encode;
    std::optional<float> gamma;
};

// The lighting terms by the names the command line uses, in the order component images are written.
struct TermName {
    const char* name;
    std::uint8_t bits;
};
constexpr TermName kTermNames[] = {{"emission", facet::kEmissionTerm},
                                   {"ambient", facet::kAmbientTerm},
                                   {"diffuse", facet::kDiffuseTerm},
                                   {"specular", facet::kSpecularTerm}};

// "out/spot.png" + "diffuse" -> "out/spot-diffuse.png"
std::filesystem::path componentPath(const std::filesystem::path& output, const char* term) {
    std::filesystem::path path = output;
    path.replace_filename(output.stem().string() + "-" + term + output.extension().string());
    return path;
}

// Applies the command line's lighting choices to every object (they win over the scene file's).
void applyLightingOptions(const RenderArgs& args, facet::Scene& scene) {
    if (args.lighting)
        scene.lighting.preset =
            *args.lighting == "gl" ? facet::LightingPreset::GL : facet::LightingPreset::Facet;
    if (args.reflection) {
        const facet::ReflectionModel model = *args.reflection == "phong" ? facet::ReflectionModel::Phong
                                             : *args.reflection == "blinn-phong"
                                                 ? facet::ReflectionModel::BlinnPhong
                                                 : facet::ReflectionModel::CookTorrance;
        scene.lighting.model = model;
        for (facet::ObjectSpec& object : scene.objects)
            object.reflection = model;
    }
    if (args.shading) {
        const facet::ShadingFrequency frequency = *args.shading == "flat" ? facet::ShadingFrequency::Flat
                                                  : *args.shading == "gouraud"
                                                      ? facet::ShadingFrequency::Gouraud
                                                      : facet::ShadingFrequency::Phong;
        scene.lighting.shading = frequency;
        for (facet::ObjectSpec& object : scene.objects)
            object.shading = frequency;
    }
    if (args.transparency)
        scene.transparency.mode = *args.transparency == "sorted"     ? facet::TransparencyMode::Sorted
                                  : *args.transparency == "unsorted" ? facet::TransparencyMode::Unsorted
                                                                     : facet::TransparencyMode::Exact;
    if (args.sortKey)
        scene.transparency.key =
            *args.sortKey == "farthest" ? facet::SortKey::FarthestVertex : facet::SortKey::Centroid;
    if ((args.encode || args.gamma) && scene.lighting.preset == facet::LightingPreset::GL)
        throw facet::InputError(
            "the gl preset writes colours as OpenGL 1.x does, unencoded: --encode and --gamma do not apply");
    if (args.encode)
        scene.gamma.encode = *args.encode == "srgb"    ? facet::TransferCurve::Srgb
                             : *args.encode == "power" ? facet::TransferCurve::Power
                                                       : facet::TransferCurve::Linear;
    if (args.gamma) {
        if (!(*args.gamma > 0.0f && *args.gamma <= 10.0f))
            throw facet::InputError("--gamma must be above 0 and at most 10 (got " +
                                    std::to_string(*args.gamma) + ")");
        if (args.encode && *args.encode != "power")
            throw facet::InputError("--gamma goes with --encode power");
        scene.gamma.encode = facet::TransferCurve::Power;
        scene.gamma.exponent = *args.gamma;
    }
    if (args.creaseAngle) {
        if (!(*args.creaseAngle >= 0.0f && *args.creaseAngle <= 180.0f))
            throw facet::InputError("--crease-angle must be from 0 to 180 degrees (got " +
                                    std::to_string(*args.creaseAngle) + ")");
        scene.lighting.creaseAngleDegrees = *args.creaseAngle;
    }
}

// "0-59" or "12": the first and last frame numbers, each from 0 to kMaxFrameNumber.
std::pair<int, int> parseFrames(const std::string& text) {
    std::stringstream in(text);
    long long first = 0, last = 0;
    char dash = 0;
    bool ok = static_cast<bool>(in >> first);
    if (ok && !(in >> std::ws).eof())
        ok = (in >> dash) && dash == '-' && (in >> last) && (in >> std::ws).eof();
    else
        last = first;
    if (!ok || first < 0 || last < first || last > kMaxFrameNumber)
        throw facet::InputError("--frames expects FIRST-LAST (like 0-59) or one frame number, from 0 to " +
                                std::to_string(kMaxFrameNumber) + ", FIRST <= LAST (got " +
                                facet::inQuotes(text) + ")");
    return {static_cast<int>(first), static_cast<int>(last)};
}

// "out/spin.png", frame 7 -> "out/spin-0007.png".
std::filesystem::path framePath(const std::filesystem::path& output, int frame) {
    char number[16];
    std::snprintf(number, sizeof number, "-%04d", frame);
    std::filesystem::path path = output;
    path.replace_filename(output.stem().string() + number + output.extension().string());
    return path;
}

// The last line of defence against a blank image reported as success: what became of the triangles
// of a frame that drew nothing, and the likely reasons.
std::string emptyFrameWarning(const std::string& where, const facet::DrawStats& stats) {
    std::ostringstream text;
    text << where << " nothing was drawn, only the background: of " << stats.triangles << " triangles, "
         << stats.trianglesRejected << " lay outside the view (or were cut off by the near and far planes), "
         << stats.trianglesCulled << " were culled as back faces, "
         << stats.trianglesZeroArea + stats.trianglesMissingSamples << " covered no pixel centre, and "
         << stats.fragmentsDepthFailed << " fragments failed the depth test; the camera may look away from "
         << "the model";
    return text.str();
}

void printFrameStats(int frame, const facet::PreparedScene& prepared, const facet::FrameStats& stats) {
    std::cout << "frame " << frame << ": " << stats.draw.fragmentsShaded << " fragments shaded";
    const std::size_t transparent = prepared.transparentTriangles.size();
    if (transparent > 0) {
        std::cout << "; " << transparent << " transparent triangles";
        if (stats.sort.elements > 0) {
            std::cout << " sorted "
                      << (stats.sort.fromScratch ? "from scratch"
                                                 : "by insertion from the last frame's order")
                      << ": " << stats.sort.comparisons << " comparisons, " << stats.sort.moves << " moves, ";
            char ms[32];
            std::snprintf(ms, sizeof ms, "%.2f ms", stats.sortMilliseconds);
            std::cout << ms;
        }
        std::cout << "; " << stats.transparentRuns << (stats.transparentRuns == 1 ? " draw" : " draws")
                  << " in the transparent pass";
        if (stats.fragmentLists.fragments > 0) {
            char text[160];
            std::snprintf(
                text, sizeof text,
                "; exact: %llu fragments in per-pixel lists (longest %u), %.1f MiB held, resolved in %.2f ms",
                static_cast<unsigned long long>(stats.fragmentLists.fragments),
                stats.fragmentLists.longestList, double(stats.fragmentLists.bytesHeld) / (1024.0 * 1024.0),
                stats.resolveMilliseconds);
            std::cout << text;
        }
    }
    std::cout << "\n";
}

// The output name alone, before anything is loaded: "-o ''" (checkImageDestination checks the rest).
void checkOutputName(const std::string& output) {
    if (output.empty())
        throw facet::InputError("no output file given: name one with -o, like -o out/image.png");
}

int render(const RenderArgs& args) {
    // Everything the command line alone decides is checked before a model is loaded: a typo in
    // --frames must not wait for a large model, nor start writing images.
    checkOutputName(args.output);
    if (args.only && args.components) throw facet::InputError("--only and --components do not go together");
    if (args.turntable && !args.frames)
        throw facet::InputError("--turntable needs --frames (like --frames 0-59)");
    const auto [firstFrame, lastFrame] = args.frames ? parseFrames(*args.frames) : std::pair{0, 0};
    const int frameCount = lastFrame - firstFrame + 1;
    const int imagesPerFrame = args.components ? 1 + static_cast<int>(std::size(kTermNames)) : 1;
    if (static_cast<long long>(frameCount) * imagesPerFrame > kMaxImagesPerRun)
        throw facet::InputError("--frames " + *args.frames + " would write " +
                                std::to_string(static_cast<long long>(frameCount) * imagesPerFrame) +
                                " images; one run writes at most " + std::to_string(kMaxImagesPerRun) +
                                (args.components ? " (--components writes five per frame)" : ""));
    const float turntable = args.turntable.value_or(args.frames ? 360.0f : 0.0f);  // finite: kFiniteNumber

    const std::filesystem::path input = args.input;
    facet::Scene scene = facet::loadSceneOrModel(input);
    if (args.width) scene.width = *args.width;
    if (args.height) scene.height = *args.height;
    checkSize(scene.width, scene.height,
              sizeFromScene(input, args.width.has_value(), args.height.has_value()));
    if (args.eye) scene.camera.eye = parseVec3("--eye", *args.eye);
    if (args.target) scene.camera.target = parseVec3("--target", *args.target);
    if (args.fovy) {
        if (!(*args.fovy >= facet::kMinFovyDegrees && *args.fovy <= facet::kMaxFovyDegrees)) {
            std::ostringstream message;
            message << "--fovy must be from " << facet::kMinFovyDegrees << " to " << facet::kMaxFovyDegrees
                    << " degrees (got " << *args.fovy << ")";
            throw facet::InputError(message.str());
        }
        scene.camera.fovyDegrees = *args.fovy;
    }
    if (scene.camera.eye && scene.camera.target &&
        glm::length(*scene.camera.eye - *scene.camera.target) == 0.0f)
        throw facet::InputError("the camera's eye and target are the same point");

    applyLightingOptions(args, scene);
    std::uint8_t terms = facet::kAllTerms;
    if (args.only)
        for (const TermName& term : kTermNames)
            if (*args.only == term.name) terms = term.bits;
    facet::checkImageDestination(args.output, scene.width, scene.height);

    const auto start = std::chrono::steady_clock::now();
    facet::PreparedScene prepared = facet::prepareScene(scene);
    for (const std::string& warning : prepared.warnings)
        std::cerr << "facet: warning: " << warning << "\n";
    facet::Framebuffer framebuffer(scene.width, scene.height);
    facet::DrawContext context(args.threads);
    facet::FrameMemory memory;  // the transparent triangles' order, carried from frame to frame
    std::vector<std::filesystem::path> written;
    facet::DrawStats total;
    int emptyFrames = 0;
    facet::DrawStats firstEmptyStats;  // and its name, written.front() of those frames
    std::filesystem::path firstEmpty;
    for (int k = 0; k < frameCount; ++k) {
        const int frame = firstFrame + k;
        // A turntable: frame k of n turns the objects by turntable·k/n degrees.
        if (args.frames) facet::setTurntable(prepared, turntable * float(k) / float(frameCount));
        const std::filesystem::path output =
            args.frames ? framePath(args.output, frame) : std::filesystem::path(args.output);
        const facet::FrameStats stats = facet::renderFrame(prepared, framebuffer, context, memory, terms);
        total += stats.draw;
        if (stats.draw.fragmentsWritten + stats.draw.fragmentsStored == 0 && emptyFrames++ == 0) {
            firstEmptyStats = stats.draw;
            firstEmpty = output;
        }
        if (args.stats) printFrameStats(frame, prepared, stats);
        facet::writeImage(output, facet::toImage(framebuffer), prepared.encoding);
        written.push_back(output);
        // The component images: each term alone, over the same background; the main image is their sum.
        if (args.components) {
            for (const TermName& term : kTermNames) {
                facet::FrameMemory scratch;  // not the animation's: keeps its insertion sort honest
                facet::renderFrame(prepared, framebuffer, context, scratch, term.bits);
                written.push_back(componentPath(output, term.name));
                facet::writeImage(written.back(), facet::toImage(framebuffer), prepared.encoding);
            }
        }
    }
    const auto rendered = std::chrono::steady_clock::now();
    if (emptyFrames > 0)
        std::cerr << "facet: warning: "
                  << emptyFrameWarning(emptyFrames == 1
                                           ? firstEmpty.string() + ":"
                                           : std::to_string(emptyFrames) + " of " +
                                                 std::to_string(frameCount) + " frames (the first " +
                                                 firstEmpty.string() + "):",
                                       firstEmptyStats)
                  << "\n";

    if (!args.quiet) {
        const double ms = std::chrono::duration<double, std::milli>(rendered - start).count();
        std::cout << "facet: wrote "
                  << (args.frames ? std::to_string(frameCount) + " frames, " + written.front().string() +
                                        " to " + framePath(args.output, lastFrame).string()
                                  : args.output)
                  << " (" << scene.width << "x" << scene.height << ", " << prepared.triangleCount
                  << " triangles";
        if (prepared.degenerateSkipped)
            std::cout << ", " << prepared.degenerateSkipped << " degenerate skipped";
        std::cout << ", " << total.fragmentsShaded << " fragments shaded, " << static_cast<long>(ms + 0.5)
                  << " ms including loading)\n";
        if (!args.frames)
            for (std::size_t k = 1; k < written.size(); ++k)
                std::cout << "facet: wrote " << written[k].string() << " (" << kTermNames[k - 1].name
                          << " term alone)\n";
    }
    return 0;
}

// The repository this program was built in, found from the executable (REPO/build/src/facet): the
// nearest folder above it holding the bundled models/ and, beside it, the shared ../shared/models.
// Empty when the program has been moved out of its build tree.
std::filesystem::path repositoryOfExecutable() {
    std::error_code error;
    const std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", error);
    if (error) return {};
    for (std::filesystem::path folder = executable.parent_path();
         !folder.empty() && folder != folder.root_path(); folder = folder.parent_path())
        if (std::filesystem::is_directory(folder / "models", error) &&
            std::filesystem::is_directory(folder / "../shared/models", error))
            return folder;
    return {};
}

// The benchmark's models when the command line names none: beside the repository the program was
// built in, so that `facet bench` works from any folder; else relative to the working folder.
void chooseDefaultBenchModels(facet::BenchOptions& options, bool modelGiven) {
    const std::filesystem::path bunny = "stanford-bunny/stanford-bunny.obj";
    const std::filesystem::path repository = repositoryOfExecutable();
    if (!repository.empty()) {
        options.sharedModels = (repository / "../shared/models").lexically_normal();
        options.smallModel = repository / "models/spot/spot_triangulated.obj";
    }
    if (modelGiven) return;
    options.model = options.sharedModels / bunny;
    std::error_code error;
    if (!std::filesystem::is_regular_file(options.model, error))
        throw facet::InputError("the default benchmark model " + options.model.string() +
                                " is not there; name a model to time: facet bench MODEL.obj");
}

struct CompareArgs {
    RenderArgs scene;  // input, size and lighting choices as for render
    std::string driver = "softpipe";
    std::optional<std::string> facetImage, mesaImage, diffImage;
};

// Exit status when the images differ beyond the bar (0: they agree; 1: bad input; 2: bad command line).
constexpr int kImagesDiffer = 3;

int compare(const CompareArgs& args) {
    const std::filesystem::path input = args.scene.input;
    facet::Scene scene = facet::loadSceneOrModel(input);
    if (args.scene.width) scene.width = *args.scene.width;
    if (args.scene.height) scene.height = *args.scene.height;
    checkSize(scene.width, scene.height,
              sizeFromScene(input, args.scene.width.has_value(), args.scene.height.has_value()));
    applyLightingOptions(args.scene, scene);
    for (const auto& path : {args.facetImage, args.mesaImage, args.diffImage})
        if (path) facet::checkImageDestination(*path, scene.width, scene.height);

    const facet::MesaDriver driver =
        args.driver == "llvmpipe" ? facet::MesaDriver::Llvmpipe : facet::MesaDriver::Softpipe;
    const facet::MesaComparison result = facet::compareWithMesa(scene, driver, args.scene.threads);
    std::cout << "facet compare: " << input.string() << "\n" << facet::describe(result);
    if (args.facetImage) facet::writeImage(*args.facetImage, result.facet, result.encoding);
    if (args.mesaImage) facet::writeImage(*args.mesaImage, result.mesa, result.encoding);
    if (args.diffImage) facet::writeImage(*args.diffImage, facet::differenceImage(result));
    return result.agrees() ? 0 : kImagesDiffer;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Facet: a software rasterizer. Renders OBJ models and scene files to images on the CPU."};
    app.require_subcommand(1);
    app.set_version_flag("--version", "facet 0.1");

    RenderArgs renderArgs;
    CLI::App* renderCommand = app.add_subcommand("render", "Render an OBJ model or a JSON scene to an image");
    renderCommand->add_option("input", renderArgs.input, "Model (.obj) or scene (.json) to render")
        ->required();
    renderCommand
        ->add_option("-o,--output", renderArgs.output,
                     "Image to write; the extension picks the format (.png .exr .ppm .jpg .tif)")
        ->required();
    renderCommand->add_option("--width", renderArgs.width, "Image width in pixels (default 1280)")
        ->check(kWholeNumber);
    renderCommand->add_option("--height", renderArgs.height, "Image height in pixels (default 960)")
        ->check(kWholeNumber);
    renderCommand->add_option("--eye", renderArgs.eye,
                              "Camera position x,y,z (default: framed from the front)");
    renderCommand->add_option("--target", renderArgs.target,
                              "Point the camera looks at, x,y,z (default: the model's centre)");
    renderCommand->add_option("--fovy", renderArgs.fovy, "Vertical field of view in degrees (default 40)")
        ->check(kFiniteNumber);
    renderCommand
        ->add_option("--threads", renderArgs.threads, "Worker threads (default: one per hardware thread)")
        ->check(wholeNumber(0, 1024));
    renderCommand->add_flag("-q,--quiet", renderArgs.quiet, "Print nothing on success");
    renderCommand
        ->add_option("--lighting", renderArgs.lighting,
                     "facet: linear light, sRGB output (default); gl: OpenGL 1.x fixed-function conventions "
                     "(docs/lighting.md)")
        ->check(CLI::IsMember({"facet", "gl"}));
    renderCommand
        ->add_option("--reflection", renderArgs.reflection,
                     "Reflection model for every object: phong, blinn-phong (default) or cook-torrance")
        ->check(CLI::IsMember({"phong", "blinn-phong", "cook-torrance"}));
    renderCommand
        ->add_option(
            "--shading", renderArgs.shading,
            "Shading frequency for every object: flat (per face), gouraud (per vertex) or phong (per "
            "pixel, the default)")
        ->check(CLI::IsMember({"flat", "gouraud", "phong"}));
    renderCommand
        ->add_option("--crease-angle", renderArgs.creaseAngle,
                     "Computed normals: faces meeting at a sharper angle (degrees) keep a hard edge "
                     "(default 60)")
        ->check(kFiniteNumber);
    renderCommand
        ->add_option("--only", renderArgs.only,
                     "Render one term of the lighting equation alone: emission, ambient, diffuse or specular")
        ->check(CLI::IsMember({"emission", "ambient", "diffuse", "specular"}));
    renderCommand->add_option(
        "--frames", renderArgs.frames,
        "Render frames FIRST-LAST (like 0-59) of a turntable, writing NAME-0000.png ...");
    renderCommand
        ->add_option("--turntable", renderArgs.turntable,
                     "Degrees the objects turn about the vertical axis over the frames (default 360)")
        ->check(kFiniteNumber);
    renderCommand->add_flag(
        "--stats", renderArgs.stats,
        "Print per frame the fragments and the sorting of transparent triangles (comparisons, "
        "moves, time)");
    renderCommand
        ->add_option("--transparency", renderArgs.transparency,
                     "sorted (back to front, the default), unsorted (file order) or exact (per-pixel lists)")
        ->check(CLI::IsMember({"sorted", "unsorted", "exact"}));
    renderCommand
        ->add_option("--sort-key", renderArgs.sortKey,
                     "Depth that orders transparent triangles: centroid (default) or farthest (vertex)")
        ->check(CLI::IsMember({"centroid", "farthest"}));
    renderCommand
        ->add_option(
            "--encode", renderArgs.encode,
            "8-bit output encoding: srgb (the exact curve, default), power (1/gamma) or linear (none)")
        ->check(CLI::IsMember({"srgb", "power", "linear"}));
    renderCommand->add_option("--gamma", renderArgs.gamma, "Encode 8-bit output as c^(1/GAMMA) (e.g. 2.2)")
        ->check(kFiniteNumber);
    renderCommand->add_flag("--components", renderArgs.components,
                            "Also write each term alone next to the output: NAME-emission, NAME-ambient, "
                            "NAME-diffuse, NAME-specular (the output is their sum)");

    CompareArgs compareArgs;
    CLI::App* compareCommand = app.add_subcommand(
        "compare", "Render a model or scene with Facet and with OpenGL (Mesa) and compare the pixels");
    compareCommand->add_option("input", compareArgs.scene.input, "Model (.obj) or scene (.json)")->required();
    compareCommand->add_option("--width", compareArgs.scene.width, "Image width in pixels")
        ->check(kWholeNumber);
    compareCommand->add_option("--height", compareArgs.scene.height, "Image height in pixels")
        ->check(kWholeNumber);
    compareCommand
        ->add_option("--driver", compareArgs.driver,
                     "Mesa's rasterizer: softpipe (its reference implementation, the default) or llvmpipe")
        ->check(CLI::IsMember({"softpipe", "llvmpipe"}));
    compareCommand->add_option("--lighting", compareArgs.scene.lighting, "facet or gl (as for render)")
        ->check(CLI::IsMember({"facet", "gl"}));
    compareCommand
        ->add_option("--reflection", compareArgs.scene.reflection, "phong, blinn-phong or cook-torrance")
        ->check(CLI::IsMember({"phong", "blinn-phong", "cook-torrance"}));
    compareCommand->add_option("--shading", compareArgs.scene.shading, "flat, gouraud or phong")
        ->check(CLI::IsMember({"flat", "gouraud", "phong"}));
    compareCommand->add_option("--crease-angle", compareArgs.scene.creaseAngle, "as for render")
        ->check(kFiniteNumber);
    compareCommand->add_option("--facet", compareArgs.facetImage, "Also write Facet's image here");
    compareCommand->add_option("--mesa", compareArgs.mesaImage, "Also write OpenGL's image here");
    compareCommand->add_option(
        "--diff", compareArgs.diffImage,
        "Also write where they differ: grey equal, blue 1/255, yellow 2/255, red more");
    compareCommand
        ->add_option("--threads", compareArgs.scene.threads,
                     "Facet's worker threads (default: one per hardware thread)")
        ->check(wholeNumber(0, 1024));
    compareCommand->footer(
        "Exit status: 0 when at least 99.5% of the pixels are within 2/255 on every channel, 3 when not, "
        "1 for bad input, 2 for a bad command line.");

    facet::BenchOptions benchOptions;
    CLI::App* benchCommand = app.add_subcommand("bench", "Time frames of a model (median ms per frame)");
    benchCommand->add_option("model", benchOptions.model,
                             "Model or scene (default: the Stanford bunny in ../shared/models)");
    benchCommand->add_option("--width", benchOptions.width, "Image width (default 1920)")
        ->check(kWholeNumber);
    benchCommand->add_option("--height", benchOptions.height, "Image height (default 1080)")
        ->check(kWholeNumber);
    benchCommand->add_option("--frames", benchOptions.frames, "Timed frames (default 30)")
        ->check(wholeNumber(1, kMaxBenchFrames));
    benchCommand
        ->add_option("--threads", benchOptions.threads, "Worker threads (default: one per hardware thread)")
        ->check(wholeNumber(0, 1024));
    benchCommand->add_flag("--vs-mesa", benchOptions.vsMesa,
                           "Compare with Mesa llvmpipe (OSMesa, if installed) on fixed scenes and sweeps, "
                           "same thread count");
    benchCommand->add_flag("--quick", benchOptions.quick,
                           "With --vs-mesa: a shorter sweep and 5 frames (unless --frames), for a smoke run");
    benchCommand->add_option("--csv", benchOptions.csv,
                             "With --vs-mesa: where the sweeps' CSV goes (default out/bench-scaling.csv)");
    benchCommand->add_option("--chart", benchOptions.chart,
                             "With --vs-mesa: where the sweeps' chart goes (default out/bench-scaling.png)");
    benchCommand->add_flag(
        "--sort", benchOptions.sort,
        "Time the transparency sorter on a turntable of MODEL (at least 50,000 triangles): "
        "insertion sort with memory against std::sort, 60 frames per step (unless --frames)");

    benchCommand->add_flag(
        "--transparency", benchOptions.transparency,
        "Time the transparency modes (sorted, unsorted, exact) on a turntable of MODEL made "
        "half transparent");
    benchCommand
        ->add_option("--degrees-per-frame", benchOptions.degreesPerFrame,
                     "With --transparency: the turntable's step (default 1)")
        ->check(kFiniteNumber);

    if (argc == 1) {  // no command at all: show what there is to do
        std::cerr << app.help();
        return 2;
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        // One line, like every other error (CLI11's own report adds a second line).
        std::cerr << "facet: error: " << e.what() << " (facet --help lists the commands and options)\n";
        return 2;
    }

    try {
        if (*renderCommand) return render(renderArgs);
        if (*compareCommand) return compare(compareArgs);
        if (*benchCommand) {
            chooseDefaultBenchModels(benchOptions, benchCommand->count("model") > 0);
            if (benchOptions.transparency) {
                for (const char* option : {"--vs-mesa", "--quick", "--csv", "--chart", "--sort"})
                    if (benchCommand->count(option))
                        throw facet::InputError(std::string(option) + " does not go with --transparency");
                checkSize(benchOptions.width, benchOptions.height);
                facet::runTransparencyBench(benchOptions, std::cout);
                return 0;
            }
            if (benchCommand->count("--degrees-per-frame"))
                throw facet::InputError("--degrees-per-frame goes with --transparency");
            if (benchOptions.sort) {
                // The camera frames MODEL as facet render does; the sort runs on one thread.
                for (const char* option :
                     {"--vs-mesa", "--quick", "--csv", "--chart", "--width", "--height", "--threads"})
                    if (benchCommand->count(option))
                        throw facet::InputError(std::string(option) + " does not go with --sort");
                if (benchCommand->count("--frames") == 0) benchOptions.frames = 60;
                facet::runSortBench(benchOptions, std::cout);
                return 0;
            }
            if (benchOptions.vsMesa) {
                // The scenes and their sizes are fixed; MODEL replaces the bunny.
                if (benchCommand->count("--width") || benchCommand->count("--height"))
                    throw facet::InputError(
                        "--vs-mesa renders fixed sizes; --width and --height do not apply");
                if (benchOptions.quick && benchCommand->count("--frames") == 0) benchOptions.frames = 5;
                facet::runMesaComparison(benchOptions, std::cout);
                return 0;
            }
            if (benchOptions.quick || benchCommand->count("--csv") || benchCommand->count("--chart"))
                throw facet::InputError("--quick, --csv and --chart go with --vs-mesa");
            checkSize(benchOptions.width, benchOptions.height);
            facet::runBench(benchOptions, std::cout);
            return 0;
        }
    } catch (const facet::InputError& e) {
        std::cerr << "facet: error: " << e.what() << "\n";
        return 1;
    } catch (const std::bad_alloc&) {
        std::cerr << "facet: error: out of memory (try a smaller image)\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "facet: internal error: " << e.what() << "\n";
        return 2;
    }
    return 0;
}
