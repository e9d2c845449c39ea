#include "trade/metrics.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>

#include "base/module.h"
#include "bench/chart.h"
#include "io/image_file.h"
#include "oracle/image_compare.h"

#if defined(FACET_OPENCV_LINKED)
// Sanitized builds (src/trade/CMakeLists.txt says why): the module's function linked in.
extern "C" double facetStructuralSimilarity(const float* a, const float* b, int width, int height);
#elif !defined(FACET_OPENCV_MODULE)
#error "FACET_OPENCV_MODULE: the module's path in the build, set by src/trade/CMakeLists.txt"
#endif

namespace facet {

namespace {

std::vector<float> linearPlanes(const LinearImage& image, LinearLight linear) {
    std::vector<float> planes;
    planes.reserve(image.pixels.size() * 3);
    for (const glm::vec4& p : image.pixels)
        if (linear == LinearLight::ToneMapped)
            planes.insert(planes.end(), {toneMapped(p.r), toneMapped(p.g), toneMapped(p.b)});
        else
            planes.insert(planes.end(), {p.r, p.g, p.b});
    return planes;
}

// Pixels with some channel off by more than `threshold`: OpenImageIO's failure count (a pixel fails
// when any of its channels is off by more than the threshold).
double shareAbove(const std::vector<float>& a, const std::vector<float>& b, int width, int height,
                  float threshold) {
    const std::size_t pixels = static_cast<std::size_t>(width) * height;
    const PixelComparison result = openImageIO().compare(a.data(), b.data(), width, height, 3, threshold);
    return pixels ? static_cast<double>(result.pixelsOver) / static_cast<double>(pixels) : 0.0;
}

// SSIM through the OpenCV module (ssim_module.cpp), loaded at the first call.
double structuralSimilarity(const std::vector<float>& a, const std::vector<float>& b, int width, int height) {
    using Entry = double (*)(const float*, const float*, int, int);
    static std::once_flag loaded;
    static Entry entry = nullptr;
    std::call_once(loaded, [] {
#if defined(FACET_OPENCV_LINKED)
        entry = facetStructuralSimilarity;
#else
        entry = reinterpret_cast<Entry>(loadModuleEntry("libfacet_opencv.so", FACET_OPENCV_MODULE,
                                                        "facetStructuralSimilarity",
                                                        "scoring images by SSIM needs OpenCV"));
#endif
    });
    const double ssim = entry(a.data(), b.data(), width, height);
    if (std::isnan(ssim)) throw std::runtime_error("OpenCV could not compute the SSIM of two images");
    return ssim;
}

}  // namespace

ErrorMetrics measurePlanes(const std::vector<float>& a, const std::vector<float>& b, int width, int height) {
    if (a.size() != b.size() || a.size() != static_cast<std::size_t>(width) * height * 3)
        throw std::invalid_argument("measurePlanes: the images differ in size");

    ErrorMetrics metrics;
    const PixelComparison result = openImageIO().compare(a.data(), b.data(), width, height, 3, 1.0f);
    metrics.meanAbs = result.meanError;
    metrics.maxAbs = result.maxError;
    // PSNR = 10·log10(peak² / MSE) with peak 1; rmsError is √MSE over every channel value.
    metrics.psnr = result.rmsError > 0 ? std::min(kMaxPsnr, -20.0 * std::log10(result.rmsError)) : kMaxPsnr;
    // A hair above the thresholds: a difference of exactly one code, (k+1)/255 − k/255, may round above
    // 1/255 in float.
    metrics.over1 = shareAbove(a, b, width, height, 1.0f / 255.0f * 1.0001f);
    metrics.over2 = shareAbove(a, b, width, height, 2.0f / 255.0f * 1.0001f);

    // SSIM with OpenCV's constants C1 = (0.01·255)², C2 = (0.03·255)²: values scaled to 0..255.
    metrics.ssim = structuralSimilarity(a, b, width, height);
    return metrics;
}

std::vector<float> encodedPlanes(const LinearImage& image, ColorEncoding encoding) {
    std::vector<float> planes;
    planes.reserve(image.pixels.size() * 3);
    for (const glm::vec4& p : image.pixels)
        for (int channel = 0; channel < 3; ++channel)
            planes.push_back(static_cast<float>(encodeChannel(p[channel], encoding)) / 255.0f);
    return planes;
}

LinearLight linearLightFor(const LinearImage& reference) {
    for (const glm::vec4& p : reference.pixels)
        if (p.r > kPlainLinearPeak || p.g > kPlainLinearPeak || p.b > kPlainLinearPeak)
            return LinearLight::ToneMapped;
    return LinearLight::AsIs;
}

ImageError measureError(const LinearImage& image, const LinearImage& reference, ColorEncoding encoding,
                        LinearLight linear) {
    if (image.width != reference.width || image.height != reference.height)
        throw std::invalid_argument("measureError: the images differ in size");
    ImageError error;
    error.linear = measurePlanes(linearPlanes(image, linear), linearPlanes(reference, linear), image.width,
                                 image.height);
    error.linearToneMapped = linear == LinearLight::ToneMapped;
    error.encoded = measurePlanes(encodedPlanes(image, encoding), encodedPlanes(reference, encoding),
                                  image.width, image.height);
    // The 8-bit shares counted in whole codes (the oracle's comparison), not by float thresholds.
    const PixelDifference codes = comparePixels(image, reference, encoding);
    // within1 and within2 are counts over the pixel count: back to whole counts, so that one pixel of
    // 384 reads as exactly 1/384.
    const double pixels = static_cast<double>(codes.pixels);
    error.encoded.over1 = std::round((1.0 - codes.within1) * pixels) / pixels;
    error.encoded.over2 = std::round((1.0 - codes.within2) * pixels) / pixels;
    return error;
}

bool sameEncoded(const LinearImage& a, const LinearImage& b, ColorEncoding encoding) {
    return a.width == b.width && a.height == b.height &&
           encodedPlanes(a, encoding) == encodedPlanes(b, encoding);
}

namespace {

// 0 → black, ⅓ → red, ⅔ → yellow, 1 → white, in 8-bit sRGB steps.
vec4 heat(float t) {
    t = std::clamp(t, 0.0f, 1.0f);
    const float r = std::min(1.0f, 3.0f * t), g = std::clamp(3.0f * t - 1.0f, 0.0f, 1.0f),
                b = std::clamp(3.0f * t - 2.0f, 0.0f, 1.0f);
    return srgb8(static_cast<int>(std::lround(255 * r)), static_cast<int>(std::lround(255 * g)),
                 static_cast<int>(std::lround(255 * b)));
}

}  // namespace

LinearImage errorImage(const LinearImage& image, const LinearImage& reference, ColorEncoding encoding) {
    const std::vector<float> a = encodedPlanes(image, encoding), b = encodedPlanes(reference, encoding);
    constexpr int kLegendHeight = 24, kLegendMinWidth = 200;
    const bool legend = image.width >= kLegendMinWidth;
    Canvas canvas(image.width, image.height + (legend ? kLegendHeight : 0), vec4(0, 0, 0, 1));
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const std::size_t i = (static_cast<std::size_t>(y) * image.width + x) * 3;
            float codes = 0;
            for (int channel = 0; channel < 3; ++channel)
                codes = std::max(codes, std::abs(a[i + channel] - b[i + channel]) * 255.0f);
            canvas.fillRect(x, y, x + 1, y + 1, heat(std::round(codes) / kErrorImageFullScale));
        }
    if (legend) {  // a ramp 0..16 codes, then its label
        const int top = image.height + 4, rampWidth = 96;
        for (int x = 0; x < rampWidth; ++x)
            canvas.fillRect(4 + x, top, 5 + x, top + 16, heat(static_cast<float>(x) / (rampWidth - 1)));
        std::string label = "0 TO ";
        label += std::to_string(kErrorImageFullScale);
        label += "+ 8-BIT STEPS OFF";
        canvas.text(4 + rampWidth + 8, top + 4, label, 1, vec4(1));
    }
    return canvas.image();
}

}  // namespace facet
