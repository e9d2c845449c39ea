#include "cli/compare_command.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "base/errors.h"
#include "io/image_io.h"
#include "oracle/compare.h"
#include "oracle/reference_compare.h"
#include "shading/shadow.h"

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
    // The knobs that decide what both renderers draw: OpenGL draws in the same depth and colour formats
    // and filters textures the same way (gl_scene.h).
    for (const char* knob : {"lighting", "reflection", "shading", "crease-angle", "depth", "color-buffer",
                             "texture-filter", "normals", "powers", "normalize", "fresnel"})
        addKnobOption(*command, knob, args.scene);
    addInfiniteFarOption(*command, args.scene);
    addShaderOptions(*command, args.scene);
    command->add_option("--facet", args.facetImage, "Also write Facet's image here");
    command->add_option("--mesa", args.mesaImage, "Also write OpenGL's image here");
    command->add_option("--diff", args.diffImage,
                        "Also write where they differ: grey equal, blue 1/255, yellow 2/255, red more");
    command
        ->add_option("--threads", args.scene.threads,
                     "Facet's worker threads (default: one per hardware thread)")
        ->check(wholeNumber(0, 1024));
    CLI::Option* reference = command->add_flag(
        "--reference", args.reference,
        "Compare with the exact reference renderer (ray casting in double) instead of OpenGL: the surface, "
        "colour and shadows of every pixel, and a table of shadow maps against ray-cast shadows");
    for (CLI::Option* mesaOnly :
         {command->get_option("--driver"), command->get_option("--mesa"), command->get_option("--diff")})
        reference->excludes(mesaOnly);
    // --aa: Facet's image only (OpenGL's is not anti-aliased), and not with --reference, whose per-pixel
    // surface check follows the pixel centre of one drawing. --shadows: with --reference only, a map
    // compared as a ray.
    addKnobOption(*command, "aa", args.scene)->excludes(reference);
    addKnobOption(*command, "shadows", args.scene)->needs(reference);
    command
        ->add_option("--shadow-map-sizes", args.shadowMapSizes,
                     "With --reference: the shadow-map table's sizes, e.g. 256,1024 (default "
                     "256,512,1024,2048,4096; 0 for no table)")
        ->needs(reference);
    command->add_option("--csv", args.csv, "With --reference: write the shadow-map table here as CSV")
        ->needs(reference);
    command->add_option("--reference-image", args.referenceImage, "With --reference: write its image here")
        ->needs(reference);
    command->footer(
        "Exit status: 0 when at least 99.5% of the pixels are within 2/255 on every channel, 3 when not, "
        "1 for bad input, 2 for a bad command line. With --reference: 0 when no pixel shows another "
        "surface than the reference's except at an edge, those edge pixels are under 1% of the covered "
        "ones, 99% of the rest are within 1/255, and ray-cast shadows differ only at shadow boundaries. "
        "--aa anti-aliases Facet's image only; with --reference, --shadows map is compared as ray.");
    return command;
}

std::vector<int> parseShadowMapSizes(const std::string& text) {
    std::vector<int> sizes;
    if (text == "0") return sizes;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t comma = std::min(text.find(',', start), text.size());
        const std::string item = text.substr(start, comma - start);
        std::size_t used = 0;
        int size = 0;
        try {
            size = std::stoi(item, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (item.empty() || used != item.size() || size < 16 || size > facet::kMaxShadowMapSize) {
            std::string message = "--shadow-map-sizes: \"";
            message += item;
            message += "\" is not a size; give whole numbers from 16 to ";
            message += std::to_string(facet::kMaxShadowMapSize);
            message += " separated by commas (e.g. 256,1024), or 0 for no table";
            throw facet::InputError(message);
        }
        sizes.push_back(size);
        start = comma + 1;
    }
    return sizes;
}

namespace {

int compareAgainstReference(const CompareArgs& args, const facet::Scene& scene) {
    facet::ReferenceCompareOptions options;
    options.threads = args.scene.threads;
    if (args.shadowMapSizes) {
        options.shadowMapSizes = parseShadowMapSizes(*args.shadowMapSizes);
        options.shadowMapTable = !options.shadowMapSizes.empty();
    }
    for (const auto& path : {args.facetImage, args.referenceImage})
        if (path) facet::checkImageDestination(*path, scene.width, scene.height);
    std::ofstream csv;  // opened first, so that a bad path is reported before the long comparison
    if (args.csv) {
        csv.open(*args.csv);
        if (!csv) throw facet::InputError(*args.csv + ": cannot write the CSV file there");
    }
    const facet::ReferenceComparison result = facet::compareWithReference(scene, options);
    std::cout << "facet compare --reference: " << args.scene.input << "\n" << facet::describe(result);
    if (args.facetImage) facet::writeImage(*args.facetImage, result.rasterized, result.encoding);
    if (args.referenceImage) facet::writeImage(*args.referenceImage, result.reference, result.encoding);
    if (args.csv) {
        csv << facet::shadowMapCsv(result);
        if (!csv.flush()) throw facet::InputError(*args.csv + ": cannot write the CSV file there");
    }
    return result.agrees() ? 0 : kImagesDiffer;
}

}  // namespace

int compare(const CompareArgs& args) {
    const std::filesystem::path input = args.scene.input;
    facet::Scene scene = facet::loadSceneOrModel(input);
    if (args.scene.width) scene.width = *args.scene.width;
    if (args.scene.height) scene.height = *args.scene.height;
    checkSize(scene.width, scene.height,
              sizeFromScene(input, args.scene.width.has_value(), args.scene.height.has_value()));
    applyLightingOptions(args.scene, scene);
    if (args.reference && scene.pipeline.antialiasing != facet::Antialiasing::None) {
        std::string message =
            "facet compare --reference checks every pixel's centre against the reference, "
            "but the scene's \"pipeline\": {\"antialiasing\": \"";
        message += nameOf(scene.pipeline.antialiasing);
        message += "\"} averages several samples: compare without it, or render both images";
        throw facet::InputError(message);
    }
    if (args.reference) return compareAgainstReference(args, scene);
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
