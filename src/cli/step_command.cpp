#include "cli/step_command.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "base/errors.h"
#include "base/quote.h"
#include "io/text_file.h"
#include "render/renderer.h"
#include "scene/limits.h"
#include "step/html_page.h"
#include "step/notation.h"
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

// The web page's grid: every gridStep-th pixel of every gridStep-th row is traced. By default about 2000
// pixels, so that the data file stays a few megabytes for any image size; each traced pixel adds a few
// kilobytes, and a bound keeps the page loadable. Throws InputError for a step beyond the bound.
int htmlGridStep(const StepArgs& args, int width, int height) {
    const double pixels = double(width) * height;
    const int step = args.htmlStep.value_or(std::max(4, int(std::ceil(std::sqrt(pixels / 2000.0)))));
    constexpr double kMostTracedPixels = 20000;
    const double traced = std::ceil(double(width) / step) * std::ceil(double(height) / step);
    if (traced > kMostTracedPixels)
        throw facet::InputError(
            "--html-step " + std::to_string(step) + " would trace " +
            std::to_string(static_cast<long long>(traced)) + " pixels of this " + std::to_string(width) +
            "x" + std::to_string(height) + " image; the page takes at most 20000 (--html-step " +
            std::to_string(int(std::ceil(std::sqrt(pixels / kMostTracedPixels)))) + " or more)");
    return step;
}

// The web page: the stage images, and the walks of a grid of pixels (and of the traced one, shown first).
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
    page.gridStep = htmlGridStep(args, page.width, page.height);
    std::vector<std::pair<int, int>> grid;
    for (int y = page.gridStep / 2; y < page.height; y += page.gridStep)
        for (int x = page.gridStep / 2; x < page.width; x += page.gridStep)
            grid.emplace_back(x, y);
    page.walks = facet::step::traceWalks(prepared, context, grid, request.terms);
    const auto same = std::find_if(page.walks.begin(), page.walks.end(), [&](const facet::step::Walk& w) {
        return w.x == trace.walk.x && w.y == trace.walk.y;
    });
    if (same != page.walks.end() && !request.triangle) {
        page.firstWalk = static_cast<std::size_t>(same - page.walks.begin());
    } else {
        page.firstWalk = page.walks.size();
        page.walks.push_back(trace.walk);
    }
    facet::step::writeHtmlPage(dir, page);
    std::cerr << "facet: wrote " << (dir / facet::step::kHtmlPageFile).string() << " (" << page.walks.size()
              << " pixels traced, every " << page.gridStep << "th of every " << page.gridStep
              << "th row, and " << page.stages.size() << " stage images)\n";
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
    command->add_option(
        "--stages", args.stages,
        "Also write images of the whole frame after each stage to this folder (made if missing)");
    command->add_option("--html", args.html,
                        "Also write a web page to this folder: the stage images, and the history of any "
                        "pixel clicked (offline: open DIR/index.html)");
    command
        ->add_option("--html-step", args.htmlStep,
                     "The page traces every N-th pixel of every N-th row; a click shows the nearest traced "
                     "one (default: N for about 2000 pixels, at least 4)")
        ->check(wholeNumber(1, 1024));
    command->add_option(
        "--versus", args.versus,
        "Trace the pixel again with these options over the others (like \"--shading gouraud\", or "
        "\"--shader mine.cpp\"; \"--shader builtin\", or \"\" after --shader, for the built-in shaders) "
        "and print both side by side, marking where they first differ");
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
    if (args.json) facet::checkTextDestination(*args.json);
    if (args.html) htmlGridStep(args, scene.width, scene.height);  // a step too fine refused before any work

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
