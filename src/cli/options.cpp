#include "cli/options.h"

#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "base/errors.h"
#include "base/quote.h"

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

void applyLightingOptions(const RenderArgs& args, facet::Scene& scene) {
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
    if (args.creaseAngle) {
        if (!(*args.creaseAngle >= 0.0f && *args.creaseAngle <= 180.0f))
            throw facet::InputError("--crease-angle must be from 0 to 180 degrees (got " +
                                    std::to_string(*args.creaseAngle) + ")");
        scene.lighting.creaseAngleDegrees = *args.creaseAngle;
    }
}

}  // namespace facet::cli
