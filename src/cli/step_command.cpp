#include "cli/step_command.h"

#include <iostream>
#include <sstream>

#include "base/errors.h"
#include "base/quote.h"
#include "io/text_file.h"
#include "render/renderer.h"
#include "scene/limits.h"
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

// The options of --versus applied over the command's own: the second setting of the comparison.
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
    return args;
}

}  // namespace

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
    command->add_option("--json", args.json, "Also write the whole trace as data (JSON) to this file");
    command->add_option(
        "--stages", args.stages,
        "Also write images of the whole frame after each stage to this folder (made if missing)");
    command->add_option(
        "--versus", args.versus,
        "Trace the pixel again with these options over the others (like \"--shading gouraud\") "
        "and print both side by side, marking where they first differ");
    command->footer(
        "On a terminal, the walk shows one stage at a time: Enter or n next, b back, a number jumps to a "
        "stage, "
        "p X,Y another pixel, t N another triangle, ? help, q quit. Without a terminal (or with --print) "
        "every "
        "screen is printed. docs/teaching.md has exercises.");
    return command;
}

int step(const StepArgs& args) {
    const std::optional<std::pair<int, int>> pixel =
        args.pixel ? std::optional(parsePixel(*args.pixel)) : std::nullopt;
    const std::optional<SceneArgs> other =
        args.versus ? std::optional(versusArgs(args, *args.versus)) : std::nullopt;
    const facet::Scene scene = sceneFromArgs(args);
    if (args.json) facet::checkTextDestination(*args.json);

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
    if (args.stages) {
        facet::step::StageImageOptions options;
        options.terms = request.terms;
        options.threads = args.threads;
        const auto images = facet::step::writeStageImages(prepared, *args.stages, options);
        std::cerr << "facet: wrote " << images.size() << " stage images to " << *args.stages << "\n";
    }

    if (other) {
        // The same pixel and triangle under the other setting.
        const facet::Scene otherScene = sceneFromArgs(*other);
        const facet::PreparedScene otherPrepared = facet::prepareScene(otherScene);
        facet::step::StepRequest otherRequest = request;
        otherRequest.pixel = std::pair(trace.walk.x, trace.walk.y);
        if (trace.walk.triangle) otherRequest.triangle = trace.walk.triangle->number;
        otherRequest.terms = other->only.value_or(facet::kAllTerms);
        const facet::step::StepTrace otherTrace =
            facet::step::traceStep(otherPrepared, context, otherRequest);
        std::cout << facet::step::sideBySide(trace.walk, "as given", otherTrace.walk, "with " + *args.versus);
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
