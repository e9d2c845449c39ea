// Image comparison: coverage and colour agreement in linear values, and 8-bit pixel statistics.
#include "oracle/image_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace facet {

ImageAgreement compareImages(const LinearImage& a, const LinearImage& b, vec4 background,
                             float backgroundTolerance) {
    if (a.width != b.width || a.height != b.height || a.pixels.size() != b.pixels.size())
        throw std::invalid_argument("compareImages: the images differ in size");
    auto isForeground = [&](const vec4& c) {
        for (int channel = 0; channel < 3; ++channel)
            if (std::abs(c[channel] - background[channel]) > backgroundTolerance) return true;
        return false;
    };
    ImageAgreement result;
    std::size_t coverageSame = 0, bothCovered = 0, colorWithin = 0;
    double differenceSum = 0.0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        const bool inA = isForeground(a.pixels[i]);
        const bool inB = isForeground(b.pixels[i]);
        result.foregroundA += inA;
        result.foregroundB += inB;
        coverageSame += inA == inB;
        if (!(inA && inB)) continue;
        ++bothCovered;
        float difference = 0.0f;
        for (int channel = 0; channel < 3; ++channel) {
            const float d = std::abs(a.pixels[i][channel] - b.pixels[i][channel]);
            difference = std::max(difference, std::isnan(d) ? 1.0f : d);  // NaN counts as fully wrong
        }
        differenceSum += difference;
        colorWithin += difference <= ImageAgreement::kColorTolerance;
    }
    if (!a.pixels.empty()) result.coverageAgreement = static_cast<double>(coverageSame) / a.pixels.size();
    if (bothCovered) {
        result.colorWithinTolerance = static_cast<double>(colorWithin) / bothCovered;
        result.meanColorDifference = differenceSum / bothCovered;
    }
    return result;
}

PixelDifference comparePixels(const LinearImage& a, const LinearImage& b, ColorEncoding encoding,
                              std::optional<vec4> background, float backgroundTolerance) {
    if (a.width != b.width || a.height != b.height || a.pixels.size() != b.pixels.size())
        throw std::invalid_argument("comparePixels: the images differ in size");
    const std::size_t count = a.pixels.size();

    // Background pixels of either image, when there is a background to tell.
    std::vector<bool> backgroundEither;
    std::size_t coveredA = 0, coveredB = 0;
    if (background) {
        auto isBackground = [&](const vec4& c) {
            for (int channel = 0; channel < 4; ++channel)
                if (!(std::abs(c[channel] - (*background)[channel]) <= backgroundTolerance)) return false;
            return true;
        };
        backgroundEither.resize(count);
        for (std::size_t i = 0; i < count; ++i) {
            const bool backgroundA = isBackground(a.pixels[i]), backgroundB = isBackground(b.pixels[i]);
            backgroundEither[i] = backgroundA || backgroundB;
            coveredA += !backgroundA;
            coveredB += !backgroundB;
        }
    }
    auto atEdge = [&](int x, int y) {
        auto background = [&](int px, int py) {
            return px >= 0 && py >= 0 && px < a.width && py < a.height &&
                   backgroundEither[static_cast<std::size_t>(py) * a.width + px];
        };
        return background(x, y) || background(x - 1, y) || background(x + 1, y) || background(x, y - 1) ||
               background(x, y + 1);
    };

    PixelDifference result;
    result.pixels = count;
    result.coveredA = coveredA;
    result.coveredB = coveredB;
    std::size_t within1 = 0, within2 = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const vec4& pa = a.at(x, y);
            const vec4& pb = b.at(x, y);
            int difference = 0;
            for (int channel = 0; channel < 3; ++channel)
                difference = std::max(difference, std::abs(int(encodeChannel(pa[channel], encoding)) -
                                                           int(encodeChannel(pb[channel], encoding))));
            result.maxDifference = std::max(result.maxDifference, difference);
            result.differing += difference > 0;
            within1 += difference <= 1;
            within2 += difference <= 2;
            if (!background) continue;
            if (atEdge(x, y))
                result.differingAtEdges += difference > 0;
            else
                result.maxInteriorDifference = std::max(result.maxInteriorDifference, difference);
        }
    if (count) {
        result.within1 = static_cast<double>(within1) / count;
        result.within2 = static_cast<double>(within2) / count;
    }
    return result;
}

}  // namespace facet
