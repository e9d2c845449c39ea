// Every screen of `facet step --print` within 80 columns, walked in-process for the configurations a
// lecture meets: every bundled model and scene at several pixels, every shading frequency, reflection
// model and lighting convention, triangles numbered past 1000 in later draws, clipped pixels, each
// transparency mode and sort key, fog, shadows, textures, depth and colour buffer formats, encodings,
// shaders of one's own, and --versus. The command lines are parsed by the program's own parser
// (addStepCommand), so each configuration reads as a user types it.
//
// The walk's safety net (fitToColumns) wraps any line a screen makes too wide; these tests ask that it
// had nothing to do (Walk::linesWrappedToFit empty), so that a new long line fails here although a user
// would never see it. Each test names the one-line break it catches.
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli/step_command.h"
#include "render/renderer.h"
#include "step/versus.h"
#include "step/walk.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = FACET_SOURCE_DIR;

// Small, so that the whole walk of every configuration takes seconds.
const std::string kSize = " --width 160 --height 120";

// The pixels walked in each model: the default (the covered pixel nearest the centre), the corners,
// where triangles reaching out of the view are clipped, and the middles of two borders.
const std::vector<std::string> kPixels = {"", "2,2", "157,117", "80,118", "3,60"};

// `facet step ARGUMENTS` parsed as the program parses it, the input relative to the source folder.
cli::StepArgs parsed(const std::string& arguments) {
    CLI::App app;
    cli::StepArgs args;
    cli::addStepCommand(app, args);
    app.parse("step " + arguments, false);
    args.input = (kSource / args.input).string();
    if (args.shader) args.shader = (kSource / *args.shader).string();
    if (args.environment) args.environment = (kSource / *args.environment).string();
    return args;
}

step::StepRequest requestOf(const cli::StepArgs& args) {
    step::StepRequest request;
    if (args.pixel) {
        std::istringstream in(*args.pixel);
        int x = 0, y = 0;
        char comma = 0;
        in >> x >> comma >> y;
        request.pixel = std::pair(x, y);
    }
    if (args.triangle) request.triangle = static_cast<std::uint32_t>(*args.triangle);
    request.terms = args.only.value_or(kAllTerms);
    return request;
}

// The lines of `text` wider than 80 columns.
std::vector<std::string> wideLines(const std::string& text) {
    std::vector<std::string> wide;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);)
        if (step::columnsOf(line) > step::kScreenColumns) wide.push_back(line);
    return wide;
}

// Walks `arguments` and expects every screen within 80 columns before the safety net, and the printed
// walk within 80 after it. Returns the walk.
step::StepTrace walkFits(const std::string& arguments) {
    SCOPED_TRACE("facet step " + arguments);
    const cli::StepArgs args = parsed(arguments);
    const PreparedScene prepared = prepareScene(cli::sceneFromArgs(args));
    DrawContext context(1);
    const step::StepTrace trace = step::traceStep(prepared, context, requestOf(args));
    for (const std::string& line : trace.walk.linesWrappedToFit)
        ADD_FAILURE() << "facet step " << arguments << "\n  a line over 80 columns (" << step::columnsOf(line)
                      << " with its screen's name): " << line;
    for (const std::string& line : wideLines(step::printWalk(trace.walk)))
        ADD_FAILURE() << "facet step " << arguments << " --print\n  " << line;
    return trace;
}

// Whether the walk's clipping screen shows the triangle cut by a plane.
bool clipped(const step::Walk& walk) {
    for (const step::Screen& screen : walk.screens)
        if (screen.id == "clip" && screen.text.find("Plane ") != std::string::npos) return true;
    return false;
}

// Every bundled model and scene, at five pixels each. Catches: a screen of any stage of any bundled
// scene (multi-draw scenes' triangles past 1000, clipped triangles, computed normals, textures,
// shadows, fog, glass) printing a line over 80 columns.
TEST(StepWidth, EveryBundledModelAtSeveralPixels) {
    std::vector<fs::path> inputs;
    for (const auto& entry : fs::directory_iterator(kSource / "models"))
        if (entry.path().extension() == ".json") inputs.push_back(entry.path());
    for (const auto& folder : fs::directory_iterator(kSource / "models"))
        if (folder.is_directory())
            for (const auto& entry : fs::directory_iterator(folder.path()))
                if (entry.path().extension() == ".obj") inputs.push_back(entry.path());
    ASSERT_GE(inputs.size(), 20u);  // the models folder found
    int clippedWalks = 0;
    for (const fs::path& input : inputs)
        for (const std::string& pixel : kPixels) {
            const std::string model = fs::relative(input, kSource).string();
            const step::StepTrace trace =
                walkFits(model + kSize + (pixel.empty() ? "" : " --pixel " + pixel));
            clippedWalks += clipped(trace.walk);
        }
    EXPECT_GE(clippedWalks, 3) << "the pixels should meet clipped triangles";
}

// Cameras close to the model, whose corners lie outside several planes at once: the outcode lines,
// and clipping by many planes. Catches: a vertex's outcode line or the clipping title over 80 columns.
TEST(StepWidth, CamerasCloseToTheModel) {
    int clippedWalks = 0;
    for (const char* eye : {"0.3,0.2,0.6", "0.1,0.1,0.25", "-0.2,0.4,-0.3"})
        for (const std::string& pixel : kPixels)
            clippedWalks += clipped(walkFits("models/spot/spot_triangulated.obj" + kSize + " --eye " + eye +
                                             " --target 0,0,0" + (pixel.empty() ? "" : " --pixel " + pixel))
                                        .walk);
    EXPECT_GE(clippedWalks, 5);
}

// The model spot under every shading frequency, reflection model and lighting convention, and the
// other choices of the lighting (distributions, Fresnel, exponents, one term alone, affine
// interpolation, an environment map). Catches: a line of the lighting or shading screens over 80.
TEST(StepWidth, EveryShadingReflectionAndLighting) {
    const std::string spot = "models/spot/spot_triangulated.obj" + kSize;
    for (const char* shading : {"constant", "flat", "gouraud", "phong"})
        for (const char* reflection : {"phong", "blinn-phong", "cook-torrance"})
            for (const char* lighting : {"facet", "gl", "lecture"})
                walkFits(spot + " --shading " + shading + " --reflection " + reflection + " --lighting " +
                         lighting);
    for (const char* distribution : {"ggx", "beckmann", "gaussian"})
        walkFits(spot + " --reflection cook-torrance --fresnel exact --distribution " + distribution);
    walkFits(spot + " --blinn-exponent matched --powers exact --normalize fast");
    for (const char* term : {"emission", "ambient", "diffuse", "specular"})
        walkFits(spot + " --only " + term);
    walkFits(spot + " --interpolation affine --textures off");
    walkFits(spot + " --texture-filter nearest --cull none");
    walkFits(spot + " --environment models/environment/sky.png");
    walkFits("models/red-sphere.json" + kSize + " --reflection cook-torrance --ior 2.4");
    walkFits("models/anisotropic.json" + kSize + " --shading gouraud");
}

// Triangles numbered past 1000, in the second and third draws of scenes of several objects, at the
// default pixel (where most make no fragment: the "no fragment" screens) and where they are drawn.
// Catches: the input screen's "Triangle N of the scene (draw D, its triangle T)" or the no-fragment
// line over 80 columns.
TEST(StepWidth, TrianglesPastAThousandInLaterDraws) {
    for (const char* scene : {"models/environment.json", "models/lighting-scene.json", "models/shadows.json"})
        for (const char* triangle : {"1000", "1500", "3000", "5800"})
            walkFits(std::string(scene) + kSize + " --triangle " + triangle);
    // The default pixel's own triangle, past 1000 in draw 2 of environment.json.
    const step::StepTrace trace = walkFits("models/environment.json" + kSize);
    ASSERT_TRUE(trace.walk.triangle.has_value());
    EXPECT_GE(trace.walk.triangle->number, 1000u);
    EXPECT_GE(trace.walk.triangle->draw, 1u);
}

// Each transparency mode and sort key on the scenes with glass, fog and shadows of every kind, the
// depth and colour buffer formats and the encodings. Catches: the sort key's z_key line, the exact
// transparency lines, the reversed-Z note, the outcode line, the colour buffer line or an encoding
// line over 80 columns.
TEST(StepWidth, TransparencyFogShadowsBuffersAndEncodings) {
    for (const char* scene :
         {"models/fog-and-glass.json", "models/glass-fresnel.json", "models/intersecting-quads.json"})
        for (const char* mode : {"sorted", "unsorted", "exact"})
            for (const char* key : {"centroid", "farthest"})
                for (const std::string& pixel : kPixels)
                    walkFits(std::string(scene) + kSize + " --transparency " + mode + " --sort-key " + key +
                             (pixel.empty() ? "" : " --pixel " + pixel));
    for (const char* fog : {"linear", "exp", "exp2", "height"})
        walkFits("models/fog-and-glass.json" + kSize + " --fog " + fog);
    for (const char* shadows : {"ray", "map"}) {
        walkFits("models/shadows.json" + kSize + " --shadows " + shadows);
        walkFits("models/area-light.json" + kSize + " --shadows " + shadows);
    }
    const std::string spot = "models/spot/spot_triangulated.obj" + kSize;
    for (const char* depth : {"float", "unorm16", "unorm24", "reversed-float"}) {
        walkFits(spot + " --depth " + depth);
        walkFits("models/near-plane.json" + kSize + " --depth " + depth + " --pixel 3,60");
        walkFits("models/glass-fresnel.json" + kSize + " --depth " + depth + " --infinite-far");
    }
    for (const char* buffer : {"float", "half", "unorm8"})
        walkFits("models/fog-and-glass.json" + kSize + " --color-buffer " + buffer);
    for (const char* encoding : {"--encode srgb", "--encode power", "--encode linear", "--gamma 2.2"}) {
        walkFits(spot + " " + encoding);
        walkFits("models/anisotropic.json" + kSize + " --pixel 5,5 " + encoding);
    }
}

// The example shaders of one's own (examples/shaders, built as modules by the build), each walked at
// the default pixel and beside the built-in shaders. Catches: a line of the shader's vertex or
// fragment screens (its uniforms, recorded values, varyings) over 80 columns.
TEST(StepWidth, EveryExampleShader) {
    int shaders = 0;
    for (const auto& entry : fs::directory_iterator(FACET_EXAMPLE_SHADER_DIR)) {
        if (entry.path().extension() != ".so") continue;
        ++shaders;
        const step::StepTrace trace = walkFits("models/spot/spot_triangulated.obj" + kSize + " --shader '" +
                                               entry.path().string() + "'");
        EXPECT_TRUE(trace.userShader.has_value()) << entry.path();
    }
    EXPECT_GE(shaders, 5);
}

// --versus, stacked: every line of the comparison within 80 columns, and its sentence on the first
// difference whole. Catches: --versus printing two screens side by side (160 columns and more), or
// cutting a long line of either trace.
TEST(StepWidth, VersusStacksWithin80Columns) {
    struct Pair {
        std::string arguments, versus;
    };
    const std::vector<Pair> pairs = {
        {"models/spot/spot_triangulated.obj --pixel 80,60", "--shading gouraud"},
        {"models/spot/spot_triangulated.obj", "--reflection cook-torrance --lighting gl"},
        {"models/intersecting-quads.json", "--transparency exact"},
        {"models/glass-fresnel.json --pixel 3,60", "--depth reversed-float --infinite-far"},
        {"models/environment.json", "--shading flat --fog exp2"},
    };
    for (const Pair& pair : pairs) {
        SCOPED_TRACE("facet step " + pair.arguments + " --versus '" + pair.versus + "'");
        const cli::StepArgs args = parsed(pair.arguments + kSize);
        cli::SceneArgs otherArgs = cli::versusArgs(args, pair.versus);
        const PreparedScene prepared = prepareScene(cli::sceneFromArgs(args));
        const PreparedScene other = prepareScene(cli::sceneFromArgs(otherArgs), prepared.assets);
        DrawContext context(1);
        const step::StepTrace a = step::traceStep(prepared, context, requestOf(args));
        step::StepRequest same = requestOf(args);
        same.pixel = std::pair(a.walk.x, a.walk.y);
        if (a.walk.triangle) same.triangle = a.walk.triangle->number;
        const step::StepTrace b = step::traceStep(other, context, same);
        EXPECT_TRUE(b.walk.linesWrappedToFit.empty()) << b.walk.linesWrappedToFit.front();
        const std::string text = step::sideBySide(a.walk, "as given", b.walk, "with " + pair.versus);
        EXPECT_TRUE(wideLines(text).empty()) << wideLines(text).front();
        // The sentence naming the first difference, whole: its title, then both lines.
        const std::size_t first = text.find("They first differ in \"");
        ASSERT_NE(first, std::string::npos) << text;
        EXPECT_NE(text.find("\":\n", first), std::string::npos) << text.substr(first, 400);
    }
}

}  // namespace
}  // namespace facet
