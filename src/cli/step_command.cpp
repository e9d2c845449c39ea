#include "cli/step_command.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "base/errors.h"
#include "base/memory_limit.h"
#include "base/quote.h"
#include "io/output_path.h"
#include "io/text_file.h"
#include "render/renderer.h"
#include "render/user_shaders.h"
#include "scene/limits.h"
#include "step/html_page.h"
#include "step/notation.h"
#include "step/screen_export.h"
#include "step/stage_images.h"
#include "step/terminal_walk.h"
#include "step/versus.h"
#include "step/walk.h"

namespace facet::cli {

namespace {

// "X,Y": two whole numbers.
std::pair<int, int> parsePixel(const std::string& text) {
    std::istringstream in(text);
    long long x = -1, y = -1;
    char comma = 0;
    if (!(in >> x >> comma >> y) || comma != ',' || !(in >> std::ws).eof() || x < 0 || y < 0 ||
        x > facet::kMaxImageSide || y > facet::kMaxImageSide)
        throw facet::InputError(
            "--pixel expects X,Y, two whole numbers from 0 (like 400,300; y grows down) (got " +
            facet::inQuotes(text) + ")");
    return {static_cast<int>(x), static_cast<int>(y)};
}

// The pixels the web page traces: every gridStep-th pixel of every gridStep-th row, from gridStep/2, and
// every pixel of the region.
struct HtmlPlan {
    int gridStep = 1;
    std::optional<facet::step::PixelRect> region;
};

// The most pixels a page traces: every pixel of a 400x250 image. A traced pixel adds about 0.6 kB (a
// model alone) to 2 kB (several objects and shadows) to the page's folder, in tiles of a few megabytes
// of which a click loads one; facet step holds the walks' text compactly while it writes.
constexpr long long kMostTracedPixels = 100000;

// "X,Y,W,H": the region, inside the image. Throws InputError naming the option.
facet::step::PixelRect parseRegion(const std::string& text, int width, int height) {
    std::istringstream in(text);
    long long x = -1, y = -1, w = 0, h = 0;
    char c1 = 0, c2 = 0, c3 = 0;
    if (!(in >> x >> c1 >> y >> c2 >> w >> c3 >> h) || c1 != ',' || c2 != ',' || c3 != ',' ||
        !(in >> std::ws).eof() || x < 0 || y < 0 || w < 1 || h < 1)
        throw facet::InputError(
            "--html-region expects X,Y,W,H: the top-left pixel and the width and height in pixels, like "
            "100,80,120,90 (got " +
            facet::inQuotes(text) + ")");
    if (x + w > width || y + h > height)
        throw facet::InputError("--html-region " + text + " reaches outside the image, which is " +
                                std::to_string(width) + "x" + std::to_string(height));
    return {int(x), int(y), int(w), int(h)};
}

// How many of `from`..`to` - 1 lie on the grid: start + k·step.
long long onGrid(int from, int to, int start, int step) {
    const auto firstAtOrAfter = [&](long long v) { return v <= start ? 0 : (v - start + step - 1) / step; };
    return std::max(0LL, firstAtOrAfter(to) - firstAtOrAfter(from));
}

// The page's pixels. By default every pixel of an image of at most kMostTracedPixels, else (or with a
// region) a grid of about 2000. Throws InputError for more than kMostTracedPixels, naming the ways out.
HtmlPlan planHtml(const StepArgs& args, int width, int height) {
    HtmlPlan plan;
    if (args.htmlRegion) plan.region = parseRegion(*args.htmlRegion, width, height);
    const long long pixels = (long long)width * height;
    const int sparse = std::max(4, int(std::ceil(std::sqrt(pixels / 2000.0))));
    plan.gridStep = args.htmlStep.value_or(pixels <= kMostTracedPixels && !plan.region ? 1 : sparse);
    const int start = plan.gridStep / 2;
    long long traced = onGrid(0, width, start, plan.gridStep) * onGrid(0, height, start, plan.gridStep);
    if (plan.region) {
        const facet::step::PixelRect& r = *plan.region;
        traced += (long long)r.width * r.height - onGrid(r.x, r.x + r.width, start, plan.gridStep) *
                                                      onGrid(r.y, r.y + r.height, start, plan.gridStep);
    }
    if (traced > kMostTracedPixels) {
        const int fewest = int(std::ceil(std::sqrt(pixels / double(kMostTracedPixels))));
        throw facet::InputError(
            "--html-step " + std::to_string(plan.gridStep) +
            (plan.region ? " and --html-region " + *args.htmlRegion : std::string()) + " would trace " +
            std::to_string(traced) + " pixels of this " + std::to_string(width) + "x" +
            std::to_string(height) + " image; the page takes at most " + std::to_string(kMostTracedPixels) +
            ": trace a part in full with --html-region X,Y,W,H, or every N-th pixel with --html-step " +
            std::to_string(std::max(fewest, 2)) + " or more");
    }
    return plan;
}

// The web page: the stage images, and the walks of the planned pixels (and of the traced one, shown
// first), traced a batch at a time so that only the compact page holds them all.
void writeHtml(const StepArgs& args, const facet::PreparedScene& prepared, facet::DrawContext& context,
               const facet::step::StepRequest& request, const facet::step::StepTrace& trace) {
    const std::filesystem::path dir = *args.html;
    facet::step::StageImageOptions options;
    options.terms = request.terms;
    options.threads = args.threads;
    facet::step::HtmlPage page;
    page.stages = facet::step::writeStageImages(prepared, dir, options);
    page.width = prepared.scene.width;
    page.height = prepared.scene.height;
    page.title = std::filesystem::path(args.input).filename().string();
    page.commandLine = args.commandLine;
    const HtmlPlan plan = planHtml(args, page.width, page.height);
    page.gridStep = plan.gridStep;
    page.region = plan.region;
    // The grid in row order, then the region's other pixels in row order (the page's order on a tie).
    std::vector<std::pair<int, int>> pixels;
    const int start = page.gridStep / 2;
    const auto isOnGrid = [&](int x, int y) {
        return x >= start && y >= start && (x - start) % page.gridStep == 0 &&
               (y - start) % page.gridStep == 0;
    };
    for (int y = start; y < page.height; y += page.gridStep)
        for (int x = start; x < page.width; x += page.gridStep)
            pixels.emplace_back(x, y);
    if (const auto& r = page.region)
        for (int y = r->y; y < r->y + r->height; ++y)
            for (int x = r->x; x < r->x + r->width; ++x)
                if (!isOnGrid(x, y)) pixels.emplace_back(x, y);

    facet::step::PageWalks walks(page.width);
    constexpr std::size_t kBatch = 4096;  // pixels traced at once: two frames per batch, their text in memory
    for (std::size_t first = 0; first < pixels.size(); first += kBatch) {
        const std::vector<std::pair<int, int>> batch(
            pixels.begin() + first, pixels.begin() + std::min(pixels.size(), first + kBatch));
        for (const facet::step::Walk& walk : facet::step::traceWalks(prepared, context, batch, request.terms))
            walks.add(walk);
    }
    const auto same = std::find(pixels.begin(), pixels.end(), std::pair(trace.walk.x, trace.walk.y));
    if (same != pixels.end() && !request.triangle) {
        page.firstWalk = static_cast<std::size_t>(same - pixels.begin());
    } else {
        page.firstWalk = walks.size();
        walks.add(trace.walk);
    }
    facet::step::writeHtmlPage(dir, page, walks);
    std::cerr << "facet: wrote " << (dir / facet::step::kHtmlPageFile).string() << " (" << walks.size()
              << " pixels traced: "
              << (page.gridStep == 1 ? std::string("every pixel")
                                     : "every " + std::to_string(page.gridStep) + "th of every " +
                                           std::to_string(page.gridStep) + "th row")
              << (page.region ? ", and the region " + *args.htmlRegion : std::string()) << "; "
              << page.stages.size() << " stage images)\n";
}

// The step mode follows one pixel's centre through one drawing of the frame. Supersampling draws the
// frame once per sample, shifted, and averages the passes, so no single pass is the image; multisampling
// draws it once but tests coverage and depth at each sample, away from the centre, and averages the
// samples after the frame's draws. Either way the trace would not match the image.
void refuseAntialiasing(const facet::Scene& scene) {
    const facet::Antialiasing aa = scene.pipeline.antialiasing;
    if (aa == facet::Antialiasing::None) return;
    const std::string samples = std::to_string(facet::samplesPerPixel(aa));
    std::string message =
        "facet step follows the centre of a pixel through one drawing of the frame, but --aa ";
    message += nameOf(aa);
    message += " (or the scene's \"pipeline\": {\"antialiasing\"}) ";
    message += facet::isMultisampled(aa) ? "tests coverage and depth at " + samples +
                                               " sample positions of each pixel and averages them"
                                         : "draws the frame " + samples + " times and averages them";
    message += ": step with --aa none";
    throw facet::InputError(message);
}

// The stage images at --stage-scale stay within the largest image facet writes. Throws InputError.
void checkStageScale(const StepArgs& args, int width, int height) {
    const long long scale = args.stageScale.value_or(1);
    if (std::max(width, height) * scale <= facet::kMaxImageSide) return;
    throw facet::InputError("--stage-scale " + std::to_string(scale) + " would make the " +
                            std::to_string(width) + "x" + std::to_string(height) + " stage images " +
                            std::to_string(width * scale) + "x" + std::to_string(height * scale) +
                            "; at most " + std::to_string(facet::kMaxImageSide) +
                            " pixels a side (--stage-scale " +
                            std::to_string(facet::kMaxImageSide / std::max(width, height)) + " or less)");
}

// What --screen and --format print: one screen or the whole walk. Throws InputError for a screen the
// walk does not have, naming those it has.
std::string formatted(const StepArgs& args, const facet::step::Walk& walk) {
    const facet::step::ScreenFormat format = facet::step::screenFormatNamed(args.format.value_or("text"))
                                                 .value_or(facet::step::ScreenFormat::Text);
    if (!args.screen) return facet::step::formatWalk(walk, format);
    return facet::step::formatScreen(walk, facet::step::screenIndex(walk, *args.screen), format);
}

}  // namespace

SceneArgs versusArgs(const SceneArgs& base, const std::string& options) {
    SceneArgs args = base;
    CLI::App app{"--versus"};
    addSceneOptions(app, args);
    app.get_option("input")->required(false);  // the same input: only options may differ
    try {
        app.parse(options, false);
    } catch (const CLI::ParseError& e) {
        throw facet::InputError("--versus " + facet::inQuotes(options) + ": " + e.what());
    }
    if (args.input != base.input)
        throw facet::InputError("--versus " + facet::inQuotes(options) +
                                ": give only options; the input is the command's own");
    if (base.shader && options.find_first_not_of(" \t") == std::string::npos) args.shader = kBuiltInShaders;
    if (wantsBuiltInShaders(args)) args.uniforms.clear();
    return args;
}

bool wantsBuiltInShaders(const SceneArgs& args) {
    return args.shader && *args.shader == kBuiltInShaders;
}

CLI::App* addStepCommand(CLI::App& app, StepArgs& args) {
    CLI::App* command = app.add_subcommand(
        "step", "Follow one pixel and one triangle through every stage of the pipeline, with every number");
    addSceneOptions(*command, args);
    command->add_option("--pixel", args.pixel,
                        "The pixel X,Y to follow (x from the left, y from the top; default: the covered "
                        "pixel nearest the centre)");
    command
        ->add_option("--triangle", args.triangle,
                     "The triangle N to follow (counted over the scene's objects in order, from 0; "
                     "default: the one that gave the pixel its colour)")
        ->check(wholeNumber(0, 4'000'000'000));
    command->add_flag("--print", args.print,
                      "Write every screen to standard output instead of the interactive walk");
    command->add_flag("--notation", args.notation,
                      "Print the notation instead: every symbol the screens print, what it means and which "
                      "screens print it (no input needed)");
    // The notation is the same for every scene: the input is required only without --notation.
    command->get_option("input")->required(false);
    command->parse_complete_callback([&args] {
        if (args.input.empty() && !args.notation) throw CLI::RequiredError("input");
    });
    command->add_option("--json", args.json, "Also write the whole trace as data (JSON) to this file");
    CLI::Option* stagesOption = command->add_option(
        "--stages", args.stages,
        "Also write images of the whole frame after each stage to this folder (made if missing)");
    command
        ->add_option("--stage-scale", args.stageScale,
                     "Write the --stages images N times larger, each pixel an NxN block (nearest "
                     "neighbour), for slides (default 1)")
        ->check(wholeNumber(1, facet::kMaxImageSide))
        ->needs(stagesOption);
    command->add_option("--html", args.html,
                        "Also write a web page to this folder: the stage images, and the history of any "
                        "pixel clicked (offline: open DIR/index.html)");
    command
        ->add_option("--html-step", args.htmlStep,
                     "The page traces every N-th pixel of every N-th row; a click shows the nearest traced "
                     "one (default: 1, every pixel, up to 100000 pixels; beyond, or with --html-region, N "
                     "for about 2000 pixels, at least 4)")
        ->check(wholeNumber(1, 1024));
    command->add_option("--html-region", args.htmlRegion,
                        "The page also traces every pixel of this part of the image, X,Y,W,H (top-left "
                        "pixel, width, height; for images over 100000 pixels)");
    command->add_option(
        "--versus", args.versus,
        "Trace the pixel again with these options over the others (like \"--shading gouraud\", or "
        "\"--shader mine.cpp\"; \"--shader builtin\", or \"\" after --shader, for the built-in shaders) "
        "and print both side by side, marking where they first differ");
    command->add_option("--screen", args.screen,
                        "Print only this screen, by the short name the walk gives it (like clip or "
                        "lighting); an unknown name lists the walk's screens");
    command
        ->add_option("--format", args.format,
                     "Print the screens (or the --screen) as text (as --print shows them), markdown (a "
                     "heading, prose and fenced formula blocks) or latex (a Beamer frame's body, the "
                     "formulas in math mode); default text")
        ->check(CLI::IsMember(std::vector<std::string>(facet::step::kScreenFormatNames.begin(),
                                                       facet::step::kScreenFormatNames.end())));
    command->add_flag("--stats", args.stats,
                      "Print a few numbers on the trace to standard error (with a shader of your own: its "
                      "recorded values, and how many were NaN or infinite)");
    command->footer(
        "On a terminal, the walk shows one stage at a time: Enter or n next, b back, a number jumps to a "
        "stage, "
        "p X,Y another pixel, t N another triangle, ? help, ?? notation, q quit. Without a terminal (or with "
        "--print) "
        "every "
        "screen is printed. docs/teaching.md has exercises.");
    return command;
}

int step(const StepArgs& args) {
    if (args.notation) {  // the same for every scene: nothing is loaded or traced
        std::cout << facet::step::notationText();
        return 0;
    }
    const std::optional<std::pair<int, int>> pixel =
        args.pixel ? std::optional(parsePixel(*args.pixel)) : std::nullopt;
    const std::optional<SceneArgs> other =
        args.versus ? std::optional(versusArgs(args, *args.versus)) : std::nullopt;
    const facet::Scene scene = sceneFromArgs(args);
    refuseAntialiasing(scene);
    // Every output checked before any work: a file, a device or "-" for --json, folders for the others.
    if (args.json) facet::checkTextDestination(*args.json);
    if (args.html) facet::checkOutputFolder(*args.html, "--html");
    if (args.stages) facet::checkOutputFolder(*args.stages, "--stages");
    if (args.html) planHtml(args, scene.width, scene.height);  // too many pixels refused before any work
    if (args.htmlRegion && !args.html) throw facet::InputError("--html-region needs --html DIR");
    checkStageScale(args, scene.width, scene.height);
    if (args.html || args.stages)  // the stage images' planes, before the scene is loaded
        facet::requireMemory(std::string("drawing the stage images of ") +
                                 (args.html ? "--html" : "--stages") + " for a " +
                                 std::to_string(scene.width) + "x" + std::to_string(scene.height) + " image",
                             facet::step::stageImagesBytes(scene.width, scene.height,
                                                           args.html ? 1 : args.stageScale.value_or(1)));
    if (args.versus && (args.screen || args.format))
        throw facet::InputError(std::string(args.screen ? "--screen" : "--format") +
                                " prints one walk; --versus prints two side by side: give one of them");

    // The walk watches the scene's draws: a shader of one's own is compiled with its watched draw at once.
    facet::compileForWatchedDraws();
    const facet::PreparedScene prepared = facet::prepareScene(scene);
    for (const std::string& warning : prepared.warnings)
        std::cerr << "facet: warning: " << warning << "\n";
    facet::DrawContext context(args.threads);
    facet::step::StepRequest request;
    request.pixel = pixel;
    if (args.triangle)
        request.triangle = static_cast<std::uint32_t>(std::min<long long>(*args.triangle, 0xffffffffLL));
    request.terms = args.only.value_or(facet::kAllTerms);
    const facet::step::StepTrace trace = facet::step::traceStep(prepared, context, request);

    if (args.json) facet::writeTextFile(*args.json, facet::step::toJson(trace).dump(1) + "\n");
    if (args.stats) std::cerr << facet::step::stepStats(trace);
    if (args.stages) {
        facet::step::StageImageOptions options;
        options.terms = request.terms;
        options.threads = args.threads;
        options.scale = args.stageScale.value_or(1);
        const auto images = facet::step::writeStageImages(prepared, *args.stages, options);
        std::cerr << "facet: wrote " << images.size() << " stage images to " << *args.stages << "\n";
    }

    if (args.html) writeHtml(args, prepared, context, request, trace);

    if (other) {
        // The same pixel and triangle under the other setting.
        facet::Scene otherScene = sceneFromArgs(*other);
        if (wantsBuiltInShaders(*other)) {  // no shader of one's own anywhere in the scene
            otherScene.shader.reset();
            otherScene.uniforms.clear();
            for (facet::ObjectSpec& object : otherScene.objects)
                object.shader.reset();
        }
        refuseAntialiasing(otherScene);
        const facet::PreparedScene otherPrepared = facet::prepareScene(otherScene, prepared.assets);
        facet::step::StepRequest otherRequest = request;
        otherRequest.pixel = std::pair(trace.walk.x, trace.walk.y);
        if (trace.walk.triangle) otherRequest.triangle = trace.walk.triangle->number;
        otherRequest.terms = other->only.value_or(facet::kAllTerms);
        const facet::step::StepTrace otherTrace =
            facet::step::traceStep(otherPrepared, context, otherRequest);
        const std::string otherName =
            args.versus->find_first_not_of(" \t") == std::string::npos && wantsBuiltInShaders(*other)
                ? "with the built-in shaders"
                : "with " + *args.versus;
        std::cout << facet::step::sideBySide(trace.walk, "as given", otherTrace.walk, otherName);
        return 0;
    }
    if (args.screen || args.format) {
        std::cout << formatted(args, trace.walk);
        return 0;
    }
    if (!args.print && facet::step::isInteractive()) {
        // Another pixel or triangle: the frame traced again (p X,Y keeps no triangle; t N keeps the pixel).
        const facet::step::Retrace retrace = [&](const facet::step::WalkRequest& next) {
            facet::step::StepRequest again = request;
            again.pixel = next.pixel;
            again.triangle = next.triangle;
            return facet::step::traceStep(prepared, context, again).walk;
        };
        return facet::step::runTerminalWalk(trace.walk, retrace, std::cin, std::cout,
                                            facet::step::terminalSize());
    }
    std::cout << facet::step::printWalk(trace.walk);
    return 0;
}

}  // namespace facet::cli
