#include "oracle/compare.h"

#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>

#include "base/errors.h"
#include "render/renderer.h"

namespace facet {

namespace {

std::string percent(double fraction) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3f%%", 100.0 * fraction);
    return text;
}

}  // namespace

MesaComparison compareWithMesa(const Scene& scene, MesaDriver driver, int threads) {
    const PreparedScene prepared = prepareScene(scene);
    MesaComparison result;
    result.encoding = prepared.encoding;
    result.warnings = prepared.warnings;

    // Facet.
    Framebuffer framebuffer(scene.width, scene.height);
    DrawContext context(threads);
    renderFrame(prepared, framebuffer, context);
    result.facet = toImage(framebuffer);

    // OpenGL.
    std::string whyNot;
    const std::unique_ptr<MesaPeer> mesa = MesaPeer::open(MesaOptions{driver, 1}, whyNot);
    if (!mesa) throw InputError("cannot compare with OpenGL: " + whyNot);
    result.mesaRenderer = mesa->renderer() + ", OpenGL " + mesa->version();
    const GlScene glScene = toGlScene(prepared);
    std::map<std::string, int> programs;
    for (const GlDraw& draw : glScene.draws)
        ++programs[std::string(programName(draw.program)) + " (" + std::string(nameOf(draw.frequency)) + ")"];
    for (const auto& [name, count] : programs) {
        if (!result.programs.empty()) result.programs += ", ";
        result.programs += std::to_string(count) + (count == 1 ? " draw: " : " draws: ") + name;
    }
    try {
        mesa->load(glScene);
    } catch (const std::invalid_argument& e) {
        throw InputError(scene.source.string() +
                         ": OpenGL cannot draw this scene as Facet does: " + e.what());
    }
    mesa->renderFrame();
    result.mesa = mesa->readImage();
    result.difference = comparePixels(result.facet, result.mesa, result.encoding, prepared.clearColor);
    return result;
}

std::string describe(const MesaComparison& c) {
    const PixelDifference& d = c.difference;
    std::ostringstream out;
    out << "image      " << c.facet.width << "x" << c.facet.height << ", 8-bit "
        << (c.encoding.curve == TransferCurve::Srgb ? "sRGB-encoded" : "unencoded (gl preset)") << "\n";
    out << "opengl     " << c.mesaRenderer << "; " << c.programs << "\n";
    out << "drawn      Facet " << d.coveredA << " pixels (" << percent(double(d.coveredA) / double(d.pixels))
        << "), OpenGL " << d.coveredB << " (" << percent(double(d.coveredB) / double(d.pixels))
        << "); the rest is the background\n";
    out << "differing  " << d.differing << " of " << d.pixels << " pixels ("
        << percent(double(d.differing) / double(d.pixels)) << "), the largest difference " << d.maxDifference
        << "/255\n";
    out << "within     1/255: " << percent(d.within1) << "   2/255: " << percent(d.within2) << "\n";
    out << "where      " << d.differingAtEdges
        << " of the differing pixels are on silhouettes (coverage decided "
        << "differently by the two rasterizers); inside, the largest difference is "
        << d.maxInteriorDifference << "/255\n";
    out << "verdict    "
        << (c.agrees()          ? "agrees"
            : c.drewSomething() ? "DIFFERS"
                                : "NOTHING DRAWN")
        << " (the bar: both draw something, and at least " << percent(MesaComparison::kMinWithin2)
        << " of pixels within 2/255)\n";
    return out.str();
}

LinearImage differenceImage(const MesaComparison& c) {
    LinearImage image = c.facet;
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        int difference = 0;
        for (int channel = 0; channel < 3; ++channel)
            difference =
                std::max(difference, std::abs(int(encodeChannel(c.facet.pixels[i][channel], c.encoding)) -
                                              int(encodeChannel(c.mesa.pixels[i][channel], c.encoding))));
        vec4& p = image.pixels[i];
        if (difference == 0) {
            const float grey = 0.25f * (p.r + p.g + p.b) / 3.0f;
            p = vec4(grey, grey, grey, 1.0f);
        } else if (difference == 1) {
            p = vec4(0.0f, 0.3f, 1.0f, 1.0f);
        } else if (difference == 2) {
            p = vec4(1.0f, 0.9f, 0.0f, 1.0f);
        } else {
            p = vec4(1.0f, 0.0f, 0.0f, 1.0f);
        }
    }
    return image;
}

}  // namespace facet
