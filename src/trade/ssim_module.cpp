// The module holding OpenCV (libfacet_opencv.so, loaded by metrics.cpp when facet trade first scores an
// image): OpenCV and the ~15 libraries it brings (LAPACK, BLAS, X11, …) cost every run of the program
// ~14 ms before main when linked, for one function only facet trade calls.
#include <cmath>
#include <cstddef>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/quality/qualityssim.hpp>

// SSIM of two RGB images (3 floats per pixel, row by row, peak value 1), the mean over R, G and B of
// OpenCV's QualitySSIM (Wang et al. 2004: 11×11 Gaussian window, C1 = (0.01·255)², C2 = (0.03·255)², so
// the values are scaled to 0..255 first). NaN if OpenCV fails (the caller reports it); C linkage, so
// that no C++ type crosses the module's boundary.
extern "C" [[gnu::visibility("default")]] double facetStructuralSimilarity(const float* a, const float* b,
                                                                           int width, int height) {
    try {
        const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3;
        std::vector<float> copyA(a, a + count), copyB(b, b + count);  // cv::Mat wraps them, non-const
        const cv::Mat matA(height, width, CV_32FC3, copyA.data()),
            matB(height, width, CV_32FC3, copyB.data());
        cv::Mat scaledA, scaledB;
        matA.convertTo(scaledA, CV_32FC3, 255.0);
        matB.convertTo(scaledB, CV_32FC3, 255.0);
        cv::Mat qualityMap;
        const cv::Scalar ssim = cv::quality::QualitySSIM::compute(scaledA, scaledB, qualityMap);
        return (ssim[0] + ssim[1] + ssim[2]) / 3.0;
    } catch (...) {
        return NAN;
    }
}
