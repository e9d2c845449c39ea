// `facet compare`: one scene rendered by Facet and by OpenGL (Mesa through OSMesa), compared pixel by
// pixel after both are encoded to 8 bits as `facet render` writes them. The conformance tests run the
// same function on their scenes.
#pragma once

#include <string>
#include <vector>

#include "oracle/image_compare.h"
#include "oracle/mesa_peer.h"
#include "scene/scene.h"

namespace facet {

struct MesaComparison {
    std::string mesaRenderer;  // GL_RENDERER and GL_VERSION
    std::string programs;      // how OpenGL drew the scene, e.g. "2 draws: fixed function (Gouraud)"
    ColorEncoding encoding = kSrgbEncoding;
    LinearImage facet, mesa;  // the colour buffers, rows top to bottom
    PixelDifference difference;
    std::vector<std::string> warnings;  // the scene's loading warnings (PreparedScene::warnings)

    // The bar the conformance tests hold Facet to: at least 99.5% of pixels within 2/255 on every channel,
    // of images that both drew something (two empty frames prove nothing).
    static constexpr double kMinWithin2 = 0.995;
    bool drewSomething() const { return difference.coveredA > 0 && difference.coveredB > 0; }
    bool agrees() const { return drewSomething() && difference.within2 >= kMinWithin2; }
};

// Renders `scene` with Facet (on `threads` threads, 0: all) and with Mesa's `driver`, compares them.
// Throws InputError when the scene is unusable or Mesa cannot be opened or cannot draw it as asked.
MesaComparison compareWithMesa(const Scene& scene, MesaDriver driver, int threads = 0);

// The comparison as lines of text for a person: sizes, the statistics, where the differences are.
std::string describe(const MesaComparison& comparison);

// A picture of where the two images differ: equal pixels as a dim grey copy of Facet's image,
// pixels within 1/255 blue, within 2/255 yellow, further apart red.
LinearImage differenceImage(const MesaComparison& comparison);

}  // namespace facet
