#include "cli/compare_command.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string_view>

#include "base/errors.h"
#include "io/image_io.h"
#include "io/text_file.h"
#include "oracle/compare.h"
#include "oracle/reference_compare.h"
#include "oracle/shader_compare.h"
#include "render/user_shaders.h"
#include "shading/gamma.h"
#include "shading/shadow.h"
#include "step/versus.h"
#include "step/walk.h"
#include "trade/metrics.h"

namespace facet::cli {

namespace {

// Exit status when the images differ beyond the bar (0: they agree; 1: bad input; 2: bad command line).
constexpr int kImagesDiffer = 3;
// --against: the images differ (as diff(1) says so).
constexpr int kShaderDiffers = 1;

// The scene's loading warnings (a texture that cannot be read, a camera whose rotation had to be
// chosen, ...), as facet render prints them: the images compared are those of the scene they describe.
void printWarnings(const std::vector<std::string>& warnings) {
    for (const std::string& warning : warnings)
        std::cerr << "facet: warning: " << warning << "\n";
}

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
    command->add_option(
        "--diff", args.diffImage,
        "Also write where they differ: grey equal, blue 1/255, yellow 2/255, red more; with "
        "--reference: black equal, through red and yellow to white at 16/255 or more (as facet "
        "trade's error images), a legend below when 200 px wide or more");
    command
        ->add_option("--threads", args.scene.threads,
                     "Facet's worker threads (default: one per hardware thread)")
        ->check(wholeNumber(0, 1024));
    addMemoryLimitOption(*command);
    CLI::Option* reference = command->add_flag(
        "--reference", args.reference,
        "Compare with the exact reference renderer (ray casting in double) instead of OpenGL: the surface, "
        "colour and shadows of every pixel, and a table of shadow maps against ray-cast shadows");
    for (CLI::Option* mesaOnly : {command->get_option("--driver"), command->get_option("--mesa")})
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
    CLI::Option* against = addChoice(
        *command, "--against", args.against,
        "With --shader: render the scene with your shader and with this built-in reflection model (both "
        "per pixel; your shader sees the model in its uniforms), count the pixels whose 8-bit codes differ, "
        "and trace the first one in both one above the other (as facet step --versus does); no OpenGL");
    against->excludes(reference);
    for (const char* mesaOnly : {"--driver", "--mesa", "--diff"})
        against->excludes(command->get_option(mesaOnly));
    command
        ->add_flag("--no-trace", args.noTrace,
                   "With --against: give the first differing pixel's colours and the facet step command "
                   "that traces it, not the traces themselves")
        ->needs(against);
    command->footer(
        "With --against: exit status 0 when the two images are identical, 1 when they differ (as diff(1); "
        "bad input is 1 too, with a \"facet: error:\" line); --facet writes your shader's image. "
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
    for (const auto& path : {args.facetImage, args.referenceImage, args.diffImage})
        if (path) facet::checkImageDestination(*path, scene.width, scene.height);
    // Checked first, so that a bad path is reported before the long comparison (and an old file is only
    // replaced once the new one is whole).
    if (args.csv) facet::checkTextDestination(*args.csv);
    const facet::ReferenceComparison result = facet::compareWithReference(scene, options);
    printWarnings(result.warnings);
    std::cout << "facet compare --reference: " << args.scene.input << "\n" << facet::describe(result);
    if (args.facetImage) facet::writeImage(*args.facetImage, result.rasterized, result.encoding);
    if (args.referenceImage) facet::writeImage(*args.referenceImage, result.reference, result.encoding);
    if (args.diffImage)
        facet::writeImage(*args.diffImage,
                          facet::errorImage(result.rasterized, result.reference, result.encoding));
    if (args.csv) facet::writeTextFile(*args.csv, facet::shadowMapCsv(result));
    return result.agrees() ? 0 : kImagesDiffer;
}

// A word as a POSIX shell reads it back: as it is when it holds only safe characters, else in single
// quotes.
std::string shellWord(const std::string& word) {
    const bool safe = !word.empty() && std::all_of(word.begin(), word.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) ||
               std::string_view("_./,=:+-@%").find(c) != std::string_view::npos;
    });
    if (safe) return word;
    std::string quoted = "'";
    for (const char c : word)
        quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

// A colour as its 8-bit codes: "(201, 143, 96)".
std::string codes(const facet::vec4& color, facet::ColorEncoding encoding) {
    std::string text = "(";
    for (int k = 0; k < 3; ++k) {
        if (k) text += ", ";
        text += std::to_string(int(facet::encodeChannel(color[k], encoding)));
    }
    return text + ")";
}

// facet compare --shader FILE --against MODEL.
int compareAgainstBuiltIn(const CompareArgs& args, const facet::Scene& scene) {
    if (!scene.shader) {
        bool any = false;
        for (const facet::ObjectSpec& object : scene.objects)
            any = any || object.shader.has_value();
        if (!any)
            throw facet::InputError(
                "--against compares a shader of your own with a built-in one: give --shader FILE");
    }
    if (args.facetImage) facet::checkImageDestination(*args.facetImage, scene.width, scene.height);
    const facet::ReflectionModel model = *args.against;
    const std::string modelName(nameOf(model));
    const facet::ShaderAgainstScenes scenes = facet::shaderAgainstScenes(scene, model);
    // A differing pixel is traced (watched draws): the shader compiled for them too, at once.
    if (!args.noTrace) facet::compileForWatchedDraws();
    facet::PreparedScene mine, builtIn;
    const facet::ShaderComparison c =
        facet::compareShaderWithBuiltIn(scenes, args.scene.threads, &mine, &builtIn);
    printWarnings(c.warnings);
    const std::string shaderName =
        scene.shader ? scene.shader->source.filename().string() : std::string("the scene's shaders");
    const std::string builtInName = "built-in " + modelName;
    std::cout << "facet compare --against " << modelName << ": " << args.scene.input << ", " << shaderName
              << " against the built-in " << modelName << " shader (per pixel), " << c.width << "x"
              << c.height << "\n";
    if (args.facetImage) facet::writeImage(*args.facetImage, c.mine, c.encoding);
    if (c.identical()) {
        std::cout << "identical: every pixel has the same 8-bit codes\n";
        return 0;
    }
    const std::size_t pixels = static_cast<std::size_t>(c.width) * c.height;
    char share[32];
    std::snprintf(share, sizeof share, "%.3f%%", 100.0 * double(c.differing) / double(pixels));
    const auto [x, y] = *c.first;
    std::cout << "differ: " << c.differing << " of " << pixels << " pixels (" << share << "), by at most "
              << c.largest << " in 8-bit codes\n";
    std::cout << "first differing pixel (reading order): " << x << "," << y << ": " << shaderName << " "
              << codes(c.mine.at(x, y), c.encoding) << ", " << builtInName << " "
              << codes(c.builtIn.at(x, y), c.encoding) << "\n";
    // The facet step command that shows the same: the built-in side is the --versus.
    std::string command = "facet step " + shellWord(args.scene.input) + " --pixel " + std::to_string(x) +
                          "," + std::to_string(y) + " --width " + std::to_string(c.width) + " --height " +
                          std::to_string(c.height) + " --reflection " + modelName + " --shading phong";
    if (scene.shader) command += " --shader " + shellWord(scene.shader->source.string());
    for (const std::string& uniform : args.scene.uniforms)
        command += " --uniform " + shellWord(uniform);
    std::cout << "trace it: " << command << " --print\n";
    if (args.noTrace) return kShaderDiffers;
    // Both traces of that pixel, one above the other (facet step --versus's layout), the built-in following
    // the triangle that gave the pixel its colour in the shader's frame.
    facet::DrawContext context(args.scene.threads);
    facet::step::StepRequest request;
    request.pixel = *c.first;
    const facet::step::StepTrace traced = facet::step::traceStep(mine, context, request);
    facet::step::StepRequest other = request;
    if (traced.walk.triangle) other.triangle = traced.walk.triangle->number;
    const facet::step::StepTrace otherTraced = facet::step::traceStep(builtIn, context, other);
    std::cout << "\n" << facet::step::sideBySide(traced.walk, shaderName, otherTraced.walk, builtInName);
    return kShaderDiffers;
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
    if (args.against) return compareAgainstBuiltIn(args, scene);
    for (const auto& path : {args.facetImage, args.mesaImage, args.diffImage})
        if (path) facet::checkImageDestination(*path, scene.width, scene.height);

    const facet::MesaDriver driver = args.driver.value_or(facet::MesaDriver::Softpipe);
    const facet::MesaComparison result = facet::compareWithMesa(scene, driver, args.scene.threads);
    printWarnings(result.warnings);
    std::cout << "facet compare: " << input.string() << "\n" << facet::describe(result);
    if (args.facetImage) facet::writeImage(*args.facetImage, result.facet, result.encoding);
    if (args.mesaImage) facet::writeImage(*args.mesaImage, result.mesa, result.encoding);
    if (args.diffImage) facet::writeImage(*args.diffImage, facet::differenceImage(result));
    return result.agrees() ? 0 : kImagesDiffer;
}

}  // namespace facet::cli
