// How far an image is from the reference: PSNR, SSIM, mean and largest absolute error, and the share of
// pixels off by more than one and two 8-bit steps, in linear light and in the 8-bit output.
#pragma once

#include "io/image_io.h"

namespace facet {

struct ErrorMetrics {
    double psnr = 0;     // dB, 10·log10(1 / MSE) over R, G and B, peak 1; at most kMaxPsnr
    double ssim = 0;     // Wang et al. 2004, 11×11 Gaussian window, mean over R, G and B; 1: identical
    double meanAbs = 0;  // mean |a − b| over every R, G and B value
    double maxAbs = 0;   // largest |a − b| of any channel of any pixel
    double over1 = 0;    // share of pixels with some channel off by more than 1/255
    double over2 = 0;    // ... by more than 2/255
};

// PSNR is capped here: identical images (MSE 0, an infinite PSNR) and differences below float rounding
// read as this, so that the table and the CSV hold only finite numbers.
inline constexpr double kMaxPsnr = 100.0;

// How the linear columns see light. Their metrics assume values from 0 to 1: PSNR's peak of 1, SSIM's
// constants (for 0..255 after scaling), the 1/255 thresholds. A reference far brighter than 1 (an
// emission or a light well above 1) breaks that: its PSNR goes negative once the differences' RMS
// passes 1. Such images are then compared after the tone map x / (1 + x) (Reinhard et al. 2002's
// simplest operator) of each channel, which brings every value into 0..1, keeps their order and
// compresses the bright ones most.
enum class LinearLight { AsIs, ToneMapped };

// The brightest value (of any R, G or B of the reference) up to which the plain metrics are kept: a
// highlight adding its specular to a lit diffuse surface overshoots 1 a little (spot's reaches 1.03),
// which the plain metrics bear (a negative PSNR would need the RMS difference above 1 where no value
// exceeds 2), and tone mapping would change every column of such common scenes for a few pixels.
inline constexpr float kPlainLinearPeak = 2.0f;

// ToneMapped when some R, G or B of `reference` is above kPlainLinearPeak; AsIs otherwise.
LinearLight linearLightFor(const LinearImage& reference);

// x / (1 + x), with x below 0 taken as 0.
inline float toneMapped(float x) {
    x = x > 0 ? x : 0.0f;
    return x / (1.0f + x);
}

struct ImageError {
    // Linear light, the colour buffer's values (SSIM on values × 255, the range its constants assume);
    // tone mapped first when linearToneMapped.
    ErrorMetrics linear;
    bool linearToneMapped = false;
    // The 8-bit output as written (`encoding`), codes / 255: what the PNG shows. over1 is then the share
    // of pixels off by 2 or more codes, over2 by 3 or more.
    ErrorMetrics encoded;
};

// `image` against `reference` (the same size; alpha is not compared), the linear metrics as `linear`
// says. Throws std::invalid_argument when the sizes differ.
ImageError measureError(const LinearImage& image, const LinearImage& reference, ColorEncoding encoding,
                        LinearLight linear = LinearLight::AsIs);

// The same over RGB planes given as floats (3 per pixel, row by row), peak value 1.
ErrorMetrics measurePlanes(const std::vector<float>& a, const std::vector<float>& b, int width, int height);

// The 8-bit output, codes / 255, 3 floats per pixel.
std::vector<float> encodedPlanes(const LinearImage& image, ColorEncoding encoding);

// Whether two images would be written as the same 8-bit file.
bool sameEncoded(const LinearImage& a, const LinearImage& b, ColorEncoding encoding);

// |image − reference| in 8-bit codes, made visible: black where equal, through red and yellow to white
// at kErrorImageFullScale codes or more, with a legend strip below when the image is wide enough.
inline constexpr int kErrorImageFullScale = 16;
LinearImage errorImage(const LinearImage& image, const LinearImage& reference, ColorEncoding encoding);

}  // namespace facet
