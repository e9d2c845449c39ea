#include "cli/render_command.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "base/errors.h"
#include "base/quote.h"
#include "cli/batch.h"
#include "io/image_io.h"
#include "io/output_path.h"
#include "reference/reference.h"
#include "render/renderer.h"

namespace facet::cli {

namespace {

// Frame numbers stay within seven digits, so FIRST-LAST can never step past the largest int, and one
// run writes at most this many images (frames, times five with --components): a typo in --frames
// stops at once instead of filling the disk.
constexpr int kMaxFrameNumber = 9'999'999;
constexpr int kMaxImagesPerRun = 100'000;

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
         << stats.fragmentsDepthFailed << " fragments failed the depth test";
    // Nothing was written, so every fragment that failed the depth test failed against the value the
    // depth buffer is cleared to, the far plane's: its depth rounded to the far plane.
    if (stats.fragmentsDepthFailed > 0)
        text
            << ": their depths all rounded to the far plane, beyond what the depth buffer can tell apart "
               "at this near plane (a larger near plane, \"camera.near\" in a scene file, or a finer --depth "
               "draws them)";
    else
        text << "; the camera may look away from the model";
    return text.str();
}

void printFrameStats(std::ostream& out, int frame, const facet::PreparedScene& prepared,
                     const facet::FrameStats& stats) {
    out << "frame " << frame << ": " << stats.draw.fragmentsShaded << " fragments shaded";
    const std::size_t transparent = prepared.transparentTriangles.size();
    if (transparent > 0) {
        out << "; " << transparent << " transparent triangles";
        if (stats.sort.elements > 0) {
            out << " sorted "
                << (stats.sort.fromScratch ? "from scratch (radix sort)"
                                           : "by insertion from the last frame's order")
                << ": " << stats.sort.comparisons << " comparisons, " << stats.sort.moves << " moves, ";
            char ms[32];
            std::snprintf(ms, sizeof ms, "%.2f ms", stats.sortMilliseconds);
            out << ms;
        }
        out << "; " << stats.transparentRuns << (stats.transparentRuns == 1 ? " draw" : " draws")
            << " in the transparent pass";
        if (stats.runsReused) out << ", the last frame's (the order did not change)";
        if (stats.drawRuns > 0)
            out << " (small draws drawn together in " << stats.drawRuns
                << (stats.drawRuns == 1 ? " run)" : " runs)");
        if (stats.fragmentLists.fragments > 0) {
            char text[160];
            std::snprintf(
                text, sizeof text,
                "; exact: %llu fragments in per-pixel lists (longest %u), %.1f MiB held, resolved in %.2f ms",
                static_cast<unsigned long long>(stats.fragmentLists.fragments),
                stats.fragmentLists.longestList, double(stats.fragmentLists.bytesHeld) / (1024.0 * 1024.0),
                stats.resolveMilliseconds);
            out << text;
        }
    }
    out << "\n";
}

void printReferenceStats(std::ostream& out, int frame, const facet::ReferenceStats& stats) {
    char text[256];
    std::snprintf(
        text, sizeof text,
        "frame %d: reference: BVH built in %.1f ms (%zu non-finite triangles left out); %llu camera rays "
        "traced and shaded in %.1f ms (%.2f M rays/s), %llu see-through hits\n",
        frame, stats.buildMilliseconds, stats.nonFiniteSkipped,
        static_cast<unsigned long long>(stats.cameraRays), stats.renderMilliseconds,
        stats.renderMilliseconds > 0 ? double(stats.cameraRays) / stats.renderMilliseconds / 1000.0 : 0.0,
        static_cast<unsigned long long>(stats.transparentHits));
    out << text;
}

// The output name alone, before anything is loaded: "-o ''" (checkImageDestination checks the rest).
void checkOutputName(const std::string& output) {
    if (output.empty())
        throw facet::InputError("no output file given: name one with -o, like -o out/image.png");
}

}  // namespace

std::filesystem::path componentPath(const std::filesystem::path& output, std::string_view term) {
    std::filesystem::path path = output;
    path.replace_filename(output.stem().string() + "-" + std::string(term) + output.extension().string());
    return path;
}

CLI::App* addRenderCommand(CLI::App& app, RenderArgs& args) {
    CLI::App* command = app.add_subcommand("render", "Render an OBJ model or a JSON scene to an image");
    addSceneOptions(*command, args);
    // Render takes any number of inputs (a batch, cli/batch.h), so the scene options' one input is
    // replaced by a list; one of them, or --list, is required.
    command->remove_option(command->get_option("input"));
    command->add_option("input", args.inputs,
                        "Models (.obj) or scenes (.json); with several, -o names each image with {name} or "
                        "{index} (docs/batch.md)");
    command->parse_complete_callback([&args] {
        if (args.inputs.empty() && !args.list) throw CLI::RequiredError("input");
        if (!args.inputs.empty()) args.input = args.inputs.front();  // what a one-input caller reads
    });
    command
        ->add_option("-o,--output", args.output,
                     "Image to write; the extension picks the format (.png .exr .ppm .jpg .tif); {name} is "
                     "replaced by the input's file name without extension, {index} by its place in the list")
        ->required();
    command->add_flag("-q,--quiet", args.quiet, "Print nothing on success");
    command->add_option("--frames", args.frames,
                        "Render frames FIRST-LAST (like 0-59) of a turntable, writing NAME-0000.png ...");
    command
        ->add_option("--turntable", args.turntable,
                     "Degrees the objects turn about the vertical axis over the frames (default 360)")
        ->check(kFiniteNumber);
    command
        ->add_option(
            "--png-compression", args.pngCompression,
            "PNG files: zlib's level, 0 (none: the largest file, written fastest) to 9 (the smallest, "
            "slowest); default " +
                std::to_string(facet::kFastPngCompression) +
                ": four times faster to write than 6, files about 40% larger")
        ->check(kWholeNumber);
    command->add_flag("--stats", args.stats,
                      "Print per frame the fragments and the sorting of transparent triangles (comparisons, "
                      "moves, time)");
    addChoice(*command, "--renderer", args.renderer,
              "The rasterizer, or the exact reference: rays through Embree, shading in double "
              "(docs/reference.md)" +
                  byDefault(facet::RendererKind::Rasterizer));
    command
        ->add_option(
            "--samples", args.samples,
            "--renderer reference: N×N rays per pixel on a stratified grid, box-filtered (default 4; "
            "1 is the pixel centre)")
        ->check(kWholeNumber);
    command->add_flag("--components", args.components,
                      "Also write each term alone next to the output: NAME-emission, NAME-ambient, "
                      "NAME-diffuse, NAME-specular (the output is their sum)");
    // Many inputs in one process, and a share of them per process of a cluster job (docs/batch.md).
    CLI::Option_group* batch = command->add_option_group("Batch", "Many inputs in one process");
    batch
        ->add_option("--list", args.list,
                     "Render every input named in FILE, one path a line (# comments, blank lines skipped; "
                     "relative paths from FILE's folder), after those of the command line")
        ->type_name("FILE");
    batch
        ->add_option("--shard", args.shard,
                     "Render only the inputs whose index in the list, counted from 0, is I modulo N (like "
                     "--shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT)")
        ->type_name("I/N");
    return command;
}

RenderSettings renderSettings(const RenderArgs& args) {
    checkOutputName(args.output);
    if (args.only && args.components) throw facet::InputError("--only and --components do not go together");
    if (args.turntable && !args.frames)
        throw facet::InputError("--turntable needs --frames (like --frames 0-59)");
    RenderSettings settings;
    if (args.pngCompression) {
        if (*args.pngCompression < 0 || *args.pngCompression > 9)
            throw facet::InputError("--png-compression must be from 0 (none) to 9 (smallest file); got " +
                                    std::to_string(*args.pngCompression));
        settings.pngCompression = *args.pngCompression;
    }
    std::tie(settings.firstFrame, settings.lastFrame) =
        args.frames ? parseFrames(*args.frames) : std::pair{0, 0};
    const int frameCount = settings.lastFrame - settings.firstFrame + 1;
    const int imagesPerFrame =
        args.components ? 1 + static_cast<int>(std::size(facet::kLightingTermNames)) : 1;
    if (static_cast<long long>(frameCount) * imagesPerFrame > kMaxImagesPerRun)
        throw facet::InputError("--frames " + *args.frames + " would write " +
                                std::to_string(static_cast<long long>(frameCount) * imagesPerFrame) +
                                " images; one run writes at most " + std::to_string(kMaxImagesPerRun) +
                                (args.components ? " (--components writes five per frame)" : ""));
    settings.turntable = args.turntable.value_or(args.frames ? 360.0f : 0.0f);  // finite: kFiniteNumber
    settings.reference = args.renderer == facet::RendererKind::Reference;
    if (args.samples) {
        if (!settings.reference) throw facet::InputError("--samples is for --renderer reference");
        if (*args.samples < 1 || *args.samples > facet::kMaxReferenceSamples)
            throw facet::InputError("--samples must be from 1 to " +
                                    std::to_string(facet::kMaxReferenceSamples) +
                                    " (N×N rays per pixel; got " + std::to_string(*args.samples) + ")");
        settings.referenceOptions.samples = *args.samples;
    }
    // The rasterizer's approximations, given on the command line for the exact renderer, which has none
    // of them: refused rather than silently ignored (a scene file's keys are the scene, which the
    // reference draws exactly whatever they ask of the rasterizer).
    if (settings.reference)
        for (const auto& [name, value] : args.knobs)
            if (const facet::SceneKnob* knob = facet::sceneKnobNamed(name);
                knob && !knob->referenceInstead.empty())
                throw facet::InputError(knob->flag + " " + value +
                                        " does not go with --renderer reference, which " +
                                        knob->referenceInstead + ": leave " + knob->flag +
                                        " out, or render without --renderer reference");
    settings.terms = args.only.value_or(facet::kAllTerms);
    return settings;
}

facet::Scene inputScene(const RenderArgs& args) {
    facet::Scene scene = sceneFromArgs(args);
    facet::checkImageDestination(args.output, scene.width, scene.height);
    return scene;
}

RenderedInput renderInput(const RenderArgs& args, const RenderSettings& settings, facet::DrawContext& context,
                          std::ostream& out, std::ostream& warnings) {
    return renderScene(args, settings, inputScene(args), context, out, warnings);
}

RenderedInput renderScene(const RenderArgs& args, const RenderSettings& settings, const facet::Scene& scene,
                          facet::DrawContext& context, std::ostream& out, std::ostream& warnings) {
    const auto start = std::chrono::steady_clock::now();
    const facet::PreparedScene asWritten = facet::prepareScene(scene);
    for (const std::string& warning : asWritten.warnings)
        warnings << "facet: warning: " << warning << "\n";
    facet::Framebuffer framebuffer(scene.width, scene.height);
    facet::FrameMemory memory;  // the transparent triangles' order, carried from frame to frame
    facet::ReferenceOptions referenceOptions = settings.referenceOptions;
    const int frameCount = settings.lastFrame - settings.firstFrame + 1;
    RenderedInput result;
    std::vector<std::filesystem::path>& written = result.written;
    facet::DrawStats total;
    int emptyFrames = 0;
    facet::DrawStats firstEmptyStats;  // and its name, written.front() of those frames
    std::filesystem::path firstEmpty;
    for (int k = 0; k < frameCount; ++k) {
        const int frame = settings.firstFrame + k;
        // A turntable: frame k of n is a copy of the scene's frame with the objects turned by
        // turntable·k/n degrees (sharing its models, textures and triangles).
        std::optional<facet::PreparedScene> turnedFrame;
        if (args.frames)
            turnedFrame = facet::turned(asWritten, settings.turntable * float(k) / float(frameCount));
        const facet::PreparedScene& prepared = turnedFrame ? *turnedFrame : asWritten;
        const std::filesystem::path output =
            args.frames ? framePath(args.output, frame) : std::filesystem::path(args.output);
        if (settings.reference) {
            // The exact image: ray cast and shaded in double (and, with --components, each term alone).
            facet::ReferenceStats stats;
            referenceOptions.terms = settings.terms;
            facet::writeImage(output,
                              facet::renderReference(prepared, referenceOptions, context.pool, &stats),
                              prepared.encoding, settings.pngCompression);
            written.push_back(output);
            if (stats.surfaceHits == 0 && emptyFrames++ == 0) firstEmpty = output;
            if (args.stats) printReferenceStats(out, frame, stats);
            if (args.components) {
                for (const facet::EnumName<facet::LightingTerm>& term : facet::kLightingTermNames) {
                    referenceOptions.terms = term.value;
                    written.push_back(componentPath(output, term.name));
                    facet::writeImage(written.back(),
                                      facet::renderReference(prepared, referenceOptions, context.pool),
                                      prepared.encoding, settings.pngCompression);
                }
            }
            continue;
        }
        const facet::FrameStats stats =
            facet::renderFrame(prepared, framebuffer, context, memory, settings.terms);
        total += stats.draw;
        if (stats.draw.fragmentsWritten + stats.draw.fragmentsStored == 0 && emptyFrames++ == 0) {
            firstEmptyStats = stats.draw;
            firstEmpty = output;
        }
        if (args.stats) printFrameStats(out, frame, prepared, stats);
        facet::writeImage(output, facet::viewOf(framebuffer), prepared.encoding, settings.pngCompression,
                          &context.pool);
        written.push_back(output);
        // The component images: each term alone, over the same background; the main image is their sum.
        if (args.components) {
            for (const facet::EnumName<facet::LightingTerm>& term : facet::kLightingTermNames) {
                facet::FrameMemory scratch;  // not the animation's: keeps its insertion sort honest
                facet::renderFrame(prepared, framebuffer, context, scratch, term.value);
                written.push_back(componentPath(output, term.name));
                facet::writeImage(written.back(), facet::viewOf(framebuffer), prepared.encoding,
                                  settings.pngCompression, &context.pool);
            }
        }
    }
    const auto rendered = std::chrono::steady_clock::now();
    if (emptyFrames > 0 && settings.reference)
        warnings << "facet: warning: " << firstEmpty.string()
                 << ": no ray met a surface, only the background is seen; the camera may look away from the "
                    "model\n";
    else if (emptyFrames > 0)
        warnings << "facet: warning: "
                 << emptyFrameWarning(
                        emptyFrames == 1 ? firstEmpty.string() + ":"
                                         : std::to_string(emptyFrames) + " of " + std::to_string(frameCount) +
                                               " frames (the first " + firstEmpty.string() + "):",
                        firstEmptyStats)
                 << "\n";

    result.width = scene.width;
    result.height = scene.height;
    result.triangles = asWritten.triangleCount;
    result.degenerateSkipped = asWritten.degenerateSkipped;
    result.fragmentsShaded = total.fragmentsShaded;
    result.milliseconds = std::chrono::duration<double, std::milli>(rendered - start).count();
    return result;
}

int render(const RenderArgs& args) {
    if (isBatch(args)) return renderBatch(args);
    // Everything the command line alone decides is checked before the model is loaded.
    const RenderSettings settings = renderSettings(args);
    RenderArgs one = args;
    if (!args.inputs.empty()) one.input = args.inputs.front();  // else a caller set `input` itself
    one.output = expandOutput(args.output, one.input, 0);
    // "-o -": the image is standard output, so the reports go to standard error.
    const bool imageToStandardOutput = facet::isStandardOutput(one.output);
    if (imageToStandardOutput && (args.frames || args.components))
        throw facet::InputError(std::string("-o - writes one image to standard output; ") +
                                (args.frames ? "--frames" : "--components") +
                                " writes several: name a file, like -o out/image.png");
    std::ostream& report = imageToStandardOutput ? std::cerr : std::cout;
    facet::DrawContext context(args.threads);
    const RenderedInput result = renderInput(one, settings, context, report, std::cerr);

    if (!args.quiet) {
        const std::vector<std::filesystem::path>& written = result.written;
        report << "facet: wrote "
               << (args.frames ? std::to_string(settings.lastFrame - settings.firstFrame + 1) + " frames, " +
                                     written.front().string() + " to " +
                                     framePath(one.output, settings.lastFrame).string()
                               : one.output)
               << " (" << result.width << "x" << result.height << ", " << result.triangles << " triangles";
        if (result.degenerateSkipped) report << ", " << result.degenerateSkipped << " degenerate skipped";
        const long ms = static_cast<long>(result.milliseconds + 0.5);
        if (settings.reference)
            report << ", reference renderer, " << settings.referenceOptions.samples << "x"
                   << settings.referenceOptions.samples << " rays per pixel, " << ms
                   << " ms including loading)\n";
        else
            report << ", " << result.fragmentsShaded << " fragments shaded, " << ms
                   << " ms including loading)\n";
        if (!args.frames)
            for (std::size_t k = 1; k < written.size(); ++k)
                report << "facet: wrote " << written[k].string() << " ("
                       << facet::kLightingTermNames[k - 1].name << " term alone)\n";
    }
    return 0;
}

}  // namespace facet::cli
