#include "cli/compare_command.h"

#include <filesystem>
#include <iostream>

#include "io/image_io.h"
#include "oracle/compare.h"

namespace facet::cli {

namespace {

// Exit status when the images differ beyond the bar (0: they agree; 1: bad input; 2: bad command line).
constexpr int kImagesDiffer = 3;

}  // namespace

CLI::App* addCompareCommand(CLI::App& app, CompareArgs& args) {
    CLI::App* command = app.add_subcommand(
        "compare", "Render a model or scene with Facet and with OpenGL (Mesa) and compare the pixels");
    command->add_option("input", args.scene.input, "Model (.obj) or scene (.json)")->required();
    command->add_option("--width", args.scene.width, "Image width in pixels")->check(kWholeNumber);
    command->add_option("--height", args.scene.height, "Image height in pixels")->check(kWholeNumber);
    addChoice(*command, "--driver", args.driver,
              "Mesa's rasterizer: softpipe (its reference implementation, the default) or llvmpipe");
    addChoice(*command, "--lighting", args.scene.lighting, "As for render");
    addChoice(*command, "--reflection", args.scene.reflection, "As for render");
    addChoice(*command, "--shading", args.scene.shading, "As for render");
    command->add_option("--crease-angle", args.scene.creaseAngle, "as for render")->check(kFiniteNumber);
    command->add_option("--facet", args.facetImage, "Also write Facet's image here");
    command->add_option("--mesa", args.mesaImage, "Also write OpenGL's image here");
    command->add_option("--diff", args.diffImage,
                        "Also write where they differ: grey equal, blue 1/255, yellow 2/255, red more");
    command
        ->add_option("--threads", args.scene.threads,
                     "Facet's worker threads (default: one per hardware thread)")
        ->check(wholeNumber(0, 1024));
    command->footer(
        "Exit status: 0 when at least 99.5% of the pixels are within 2/255 on every channel, 3 when not, "
        "1 for bad input, 2 for a bad command line.");
    return command;
}

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

    const facet::MesaDriver driver = args.driver.value_or(facet::MesaDriver::Softpipe);
    const facet::MesaComparison result = facet::compareWithMesa(scene, driver, args.scene.threads);
    std::cout << "facet compare: " << input.string() << "\n" << facet::describe(result);
    if (args.facetImage) facet::writeImage(*args.facetImage, result.facet, result.encoding);
    if (args.mesaImage) facet::writeImage(*args.mesaImage, result.mesa, result.encoding);
    if (args.diffImage) facet::writeImage(*args.diffImage, facet::differenceImage(result));
    return result.agrees() ? 0 : kImagesDiffer;
}

}  // namespace facet::cli
