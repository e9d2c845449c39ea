#include "cli/options.h"

#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <tuple>

#include "base/errors.h"
#include "base/quote.h"
#include "scene/limits.h"

namespace facet::cli {

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

const CLI::Validator kFiniteNumber(
    [](std::string& text) -> std::string {
        char* stop = nullptr;
        const double value = std::strtod(text.c_str(), &stop);
        if (text.empty() || *stop != '\0' || !std::isfinite(value) || std::abs(value) > FLT_MAX)
            return "expects a finite number (got " + facet::inQuotes(text) + ")";
        return "";
    },
    "NUMBER");

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

void checkSize(int width, int height, const std::string& fromScene) {
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

std::string sizeFromScene(const std::filesystem::path& input, bool widthGiven, bool heightGiven) {
    if (input.extension() != ".json" || (widthGiven && heightGiven)) return "";
    const std::string keys = widthGiven    ? "\"height\""
                             : heightGiven ? "\"width\""
                                           : "\"width\" and \"height\"";
    return " (" + keys + " from " + input.string() + ")";
}

void addFormulaOptions(CLI::App& command, SceneArgs& args) {
    addChoice(command, "--normals", args.normals,
              "Computed normals: each face weighted by its triangles' areas, its polygon's area, or its "
              "angle at the vertex (docs/trade.md)" +
                  byDefault(VertexNormals::PolygonArea));
    addChoice(command, "--powers", args.powers,
              "pow and exp in lighting and fog: the C library's, or polynomials on the float's bits" +
                  byDefault(MathPrecision::Fast));
    addChoice(command, "--normalize", args.normalize,
              "Unit vectors N, L, V, H: 1/sqrt, or the reciprocal square root estimate and one Newton step" +
                  byDefault(Normalization::Exact));
    addChoice(command, "--fresnel", args.fresnel,
              "Cook-Torrance's Fresnel term: Schlick's approximation or the exact dielectric one" +
                  byDefault(FresnelModel::Schlick));
}

void addSceneOptions(CLI::App& command, SceneArgs& args) {
    command.add_option("input", args.input, "Model (.obj) or scene (.json)")->required();
    command.add_option("--width", args.width, "Image width in pixels (default 1280)")->check(kWholeNumber);
    command.add_option("--height", args.height, "Image height in pixels (default 960)")->check(kWholeNumber);
    command.add_option("--eye", args.eye, "Camera position x,y,z (default: framed from the front)");
    command.add_option("--target", args.target,
                       "Point the camera looks at, x,y,z (default: the model's centre)");
    command.add_option("--fovy", args.fovy, "Vertical field of view in degrees (default 40)")
        ->check(kFiniteNumber);
    command.add_option("--threads", args.threads, "Worker threads (default: one per hardware thread)")
        ->check(wholeNumber(0, 1024));
    addChoice(command, "--lighting", args.lighting,
              "Conventions: linear light and sRGB output, or OpenGL 1.x fixed function (docs/lighting.md)" +
                  byDefault(LightingPreset::Facet));
    addChoice(command, "--reflection", args.reflection,
              "Reflection model for every object" + byDefault(ReflectionModel::BlinnPhong));
    addChoice(command, "--shading", args.shading,
              "Shading frequency for every object: per face, per vertex or per pixel" +
                  byDefault(ShadingFrequency::Phong));
    command
        .add_option(
            "--crease-angle", args.creaseAngle,
            "Computed normals: faces meeting at a sharper angle (degrees) keep a hard edge (default 60)")
        ->check(kFiniteNumber);
    addFormulaOptions(command, args);
    addChoice(command, "--only", args.only, "Render one term of the lighting equation alone");
    addChoice(command, "--transparency", args.transparency,
              "Transparent triangles back to front, in file order, or in exact per-pixel lists" +
                  byDefault(TransparencyMode::Sorted));
    addChoice(command, "--sort-key", args.sortKey,
              "Depth that orders transparent triangles: the centroid's or the farthest vertex's" +
                  byDefault(SortKey::Centroid));
    addChoice(command, "--encode", args.encode,
              "8-bit output encoding: the exact sRGB curve, a power 1/gamma, or none" +
                  byDefault(TransferCurve::Srgb));
    command.add_option("--gamma", args.gamma, "Encode 8-bit output as c^(1/GAMMA) (e.g. 2.2)")
        ->check(kFiniteNumber);
    addChoice(
        command, "--interpolation", args.interpolation,
        "Varyings across a triangle: perspective-correct, or affine in screen space (wrong, for teaching)" +
            byDefault(Interpolation::PerspectiveCorrect));
    addChoice(command, "--cull", args.cull, "Which faces are not drawn" + byDefault(CullMode::Back));
    command
        .add_option(
            "--subpixel-bits", args.subpixelBits,
            "Rasterizer precision: vertices snapped to 1/2^N of a pixel, N from 0 to 8 (default 8, as "
            "GPUs and Mesa)")
        ->check(wholeNumber(0, facet::kMaxSubpixelBits));
    addChoice(command, "--aa", args.antialiasing,
              "Anti-aliasing: supersampling (ssaaN) draws the frame once per sample (2, 4, 8 or 16, at the "
              "standard sample positions) and averages them; multisampling (msaaN) draws it once, testing "
              "coverage and depth per sample and shading once per pixel" +
                  byDefault(Antialiasing::None));
    addChoice(command, "--shadows", args.shadows,
              "Shadows of every light: none, a ray to the light (exact), or a shadow map (default: each "
              "light's \"shadows\" in the scene file, else none)");
    command
        .add_option("--shadow-map-size", args.shadowMapSize,
                    "Shadow maps: texels per side (default 2048; a point light draws six)")
        ->check(kWholeNumber);
    command
        .add_option("--shadow-bias", args.shadowBias,
                    "Shadow maps: constant depth offset, in units of the map's depth resolution (default 1)")
        ->check(kFiniteNumber);
    command
        .add_option(
            "--shadow-slope-bias", args.shadowSlopeBias,
            "Shadow maps: depth offset per unit of the surface's depth slope across a texel (default 1.5)")
        ->check(kFiniteNumber);
    command
        .add_option("--shadow-filter", args.shadowFilter,
                    "Shadow maps: depth comparisons averaged per point, 1, 4 or 16 (default 4)")
        ->check(kWholeNumber);
    addChoice(command, "--textures", args.textures,
              "The MTL's texture maps: used, or ignored so surfaces take their materials' colours" +
                  byDefault(TextureMaps::On));
    addChoice(command, "--texture-filter", args.textureFilter,
              "Texture filtering: the nearest texel, bilinear, or trilinear over mipmaps (docs/trade.md)" +
                  byDefault(TextureFilter::Bilinear));
    addBufferFormatOptions(command, args);
}

void addBufferFormatOptions(CLI::App& command, SceneArgs& args) {
    addChoice(
        command, "--depth", args.depth,
        "Depth buffer format: 16- or 24-bit unorm, 32-bit float, or float with reversed Z (docs/trade.md)" +
            byDefault(DepthBufferFormat::Float));
    addChoice(
        command, "--color-buffer", args.colorBuffer,
        "Colour buffer precision, rounded after every write: 8-bit linear, half or float (docs/trade.md)" +
            byDefault(ColorBufferFormat::Float));
    command.add_flag("--infinite-far", args.infiniteFar,
                     "Camera: no far plane (the projection's limit as far goes to infinity; best with "
                     "--depth reversed-float)");
}

facet::Scene sceneFromArgs(const SceneArgs& args) {
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
    return scene;
}

void applyLightingOptions(const SceneArgs& args, facet::Scene& scene) {
    if (args.lighting) scene.lighting.preset = *args.lighting;
    if (args.reflection) {
        scene.lighting.model = *args.reflection;
        for (facet::ObjectSpec& object : scene.objects)
            object.reflection = *args.reflection;
    }
    if (args.shading) {
        scene.lighting.shading = *args.shading;
        for (facet::ObjectSpec& object : scene.objects)
            object.shading = *args.shading;
    }
    if (args.transparency) scene.transparency.mode = *args.transparency;
    if (args.interpolation) scene.pipeline.interpolation = *args.interpolation;
    if (args.cull) scene.pipeline.cull = *args.cull;
    if (args.subpixelBits) scene.pipeline.subpixelBits = *args.subpixelBits;
    if (args.depth) scene.pipeline.depth = *args.depth;
    if (args.colorBuffer) scene.pipeline.colorBuffer = *args.colorBuffer;
    if (args.infiniteFar) {
        scene.camera.infiniteFar = true;
        scene.camera.far.reset();
    }
    if (args.antialiasing) scene.pipeline.antialiasing = *args.antialiasing;
    if (args.sortKey) scene.transparency.key = *args.sortKey;
    if ((args.encode || args.gamma) && scene.lighting.preset == facet::LightingPreset::GL)
        throw facet::InputError(
            "the " + std::string(nameOf(LightingPreset::GL)) +
            " preset writes colours as OpenGL 1.x does, unencoded: --encode and --gamma do not apply");
    if (args.encode) scene.gamma.encode = *args.encode;
    if (args.gamma) {
        if (!(*args.gamma > 0.0f && *args.gamma <= 10.0f))
            throw facet::InputError("--gamma must be above 0 and at most 10 (got " +
                                    std::to_string(*args.gamma) + ")");
        if (args.encode && *args.encode != TransferCurve::Power)
            throw facet::InputError("--gamma goes with --encode " +
                                    std::string(nameOf(TransferCurve::Power)));
        scene.gamma.encode = facet::TransferCurve::Power;
        scene.gamma.exponent = *args.gamma;
    }
    if (args.shadows) scene.shadows = *args.shadows;
    if (args.textures) scene.textures.maps = *args.textures;
    if (args.textureFilter) scene.textures.filter = *args.textureFilter;
    if (args.shadowMapSize) {
        if (*args.shadowMapSize < 16 || *args.shadowMapSize > facet::kMaxShadowMapSize)
            throw facet::InputError("--shadow-map-size must be from 16 to " +
                                    std::to_string(facet::kMaxShadowMapSize) + " texels (got " +
                                    std::to_string(*args.shadowMapSize) + ")");
        scene.shadowMap.size = *args.shadowMapSize;
    }
    for (auto [name, value, field] :
         {std::tuple{"--shadow-bias", args.shadowBias, &scene.shadowMap.constantBias},
          std::tuple{"--shadow-slope-bias", args.shadowSlopeBias, &scene.shadowMap.slopeBias}}) {
        if (!value) continue;
        if (!(*value >= 0.0f && *value <= 1e6f)) {
            // The value as typed (-1, not std::to_string's -1.000000).
            std::ostringstream message;
            message << name << " must be from 0 to 1e6 (got " << *value << ")";
            throw facet::InputError(message.str());
        }
        *field = *value;
    }
    if (args.shadowFilter) {
        if (*args.shadowFilter != 1 && *args.shadowFilter != 4 && *args.shadowFilter != 16)
            throw facet::InputError("--shadow-filter must be 1, 4 or 16 depth comparisons per point (got " +
                                    std::to_string(*args.shadowFilter) + ")");
        scene.shadowMap.filterTaps = *args.shadowFilter;
    }
    if (args.normals) scene.lighting.normals = *args.normals;
    if (args.powers) scene.lighting.powers = *args.powers;
    if (args.normalize) scene.lighting.normalize = *args.normalize;
    if (args.fresnel) scene.lighting.brdf.fresnel = *args.fresnel;
    if (args.creaseAngle) {
        if (!(*args.creaseAngle >= 0.0f && *args.creaseAngle <= 180.0f))
            throw facet::InputError("--crease-angle must be from 0 to 180 degrees (got " +
                                    std::to_string(*args.creaseAngle) + ")");
        scene.lighting.creaseAngleDegrees = *args.creaseAngle;
    }
}

}  // namespace facet::cli
