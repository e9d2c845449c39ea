// Comparing two renderings of one scene: whether they cover the same pixels with the same colours
// (compareImages, in linear values), and how far apart their 8-bit images are (comparePixels), as
// `facet compare`, `facet bench --vs-mesa` and the conformance tests report it.
#pragma once

#include <cstddef>
#include <optional>

#include "io/image_io.h"

namespace facet {

using glm::vec4;

// How closely two renderings of one scene agree: proof that two renderers did the same work.
struct ImageAgreement {
    double coverageAgreement = 0.0;     // fraction of all pixels that both call foreground or both background
    double colorWithinTolerance = 0.0;  // of the pixels both cover: fraction within kColorTolerance
    double meanColorDifference = 0.0;   // of the pixels both cover: mean of the largest |Δ| over R, G, B
    std::size_t foregroundA = 0, foregroundB = 0;  // pixels each image covers

    static constexpr double kMinCoverageAgreement = 0.98;  // silhouettes differ only along edges
    static constexpr double kMinColorWithin = 0.95;        // shading differs only by rounding and edges
    static constexpr float kColorTolerance = 0.02f;        // linear units, on one channel

    bool agrees() const {
        return foregroundA > 0 && foregroundB > 0 && coverageAgreement > kMinCoverageAgreement &&
               colorWithinTolerance > kMinColorWithin;
    }
};

// Compares two images of the same size, pixel by pixel. A pixel is foreground when some channel of
// RGB differs from `background` by more than `backgroundTolerance` (a little above the rounding of the
// buffer: 0 for float buffers, half a code step for 8-bit ones). Throws std::invalid_argument when the
// sizes differ.
ImageAgreement compareImages(const LinearImage& a, const LinearImage& b, vec4 background,
                             float backgroundTolerance = 1e-5f);

// ---- 8-bit comparison, for the conformance tests ------------------------------------------------------

// Two images compared after both are quantised to 8 bits the same way; differences in code steps,
// over R, G and B (alpha is not compared).
struct PixelDifference {
    std::size_t pixels = 0;     // width × height
    std::size_t differing = 0;  // pixels with some channel's codes unequal
    int maxDifference = 0;      // the largest |Δcode| of any channel of any pixel
    double within1 = 0.0;       // fraction of pixels whose every channel is within 1 code
    double within2 = 0.0;       // ... within 2 codes
    // With a background colour only (else 0): silhouette pixels are those that are background, or have
    // a 4-neighbour that is background, in either image; interior ones are the rest.
    std::size_t coveredA = 0, coveredB = 0;  // pixels each image drew (not background)
    std::size_t differingAtEdges = 0;        // differing pixels on the silhouette
    int maxInteriorDifference = 0;           // maxDifference over interior pixels
};

// Throws std::invalid_argument when the sizes differ. A pixel is background when each of its four
// channels (alpha included) is within `backgroundTolerance` of `background`'s: clearing to an alpha no
// drawn pixel has (0, say) tells coverage apart even where a lit pixel is as dark as the background.
PixelDifference comparePixels(const LinearImage& a, const LinearImage& b, ColorEncoding encoding,
                              std::optional<vec4> background = std::nullopt,
                              float backgroundTolerance = 1e-6f);

}  // namespace facet
