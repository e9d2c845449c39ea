// A blank image: one that shows nothing, or nearly nothing, where the reference shows the scene (a near
// plane so small that every depth of a 16-bit buffer rounds to the far plane; back faces culled with
// the camera inside a closed model). Such an image is fast because it draws nothing: the trade flags
// it and keeps it off the Pareto front, and refuses a scene whose reference itself shows nothing.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "io/image_io.h"
#include "reference/reference.h"
#include "render/renderer.h"
#include "trade/knobs.h"
#include "trade/trade.h"

namespace facet {

// The image of `prepared` with its objects left out: the background as each renderer draws it (the
// clear colour rounded to the colour buffer, or the environment map along each pixel's or sample's
// rays).
LinearImage emptyFrame(const PreparedScene& prepared, DrawContext& context);
LinearImage emptyReference(const PreparedScene& prepared, const ReferenceOptions& options, ThreadPool& pool);

// Per pixel, whether it shows a surface: its 8-bit colour differs from that of `background`, the same
// renderer's empty image, in some channel. Alpha cannot tell: a surface's alpha and the background's
// are both 1 unless the scene says otherwise.
std::vector<bool> surfacePixels(const LinearImage& image, const LinearImage& background,
                                ColorEncoding encoding);

// An image is blank when, of the pixels where the reference shows a surface, it shows one at fewer
// than this share: a tenth, far below what any approximation of the scene loses (a near plane that
// cuts the model, culling an open model's back faces), far above the few pixels stray fragments
// would cover.
inline constexpr double kBlankShare = 0.1;

struct Coverage {
    std::size_t reference = 0;  // pixels where the reference shows a surface
    std::size_t shown = 0;      // of those, the pixels where the image shows one too
    bool blank() const { return static_cast<double>(shown) < kBlankShare * static_cast<double>(reference); }
};
Coverage coverageOf(const std::vector<bool>& imageSurface, const std::vector<bool>& referenceSurface);

// Throws InputError when the reference shows no surface at all (`source`: the scene, for the message):
// every setting would then score perfectly against an empty image.
void requireReferenceShowsScene(const std::vector<bool>& referenceSurface, const std::string& source);

// The warning for a blank image of `setting`.
std::string blankWarning(const TradeSetting& setting, const Coverage& coverage);

// When the baseline (the scene as given) is blank, every comparison with it says nothing about the
// scene: another setting's time is against an empty image's, its image the same as the baseline's
// means both draw nothing, its error beside the baseline's within the reference's floor is beside an
// empty image's. Then no row gets a time verdict, "no effect" or "within floor", the baseline is off
// the Pareto front, the scores are marked meaningless (scoresMeaningful), the warning says why and
// the knob-by-knob advice is one line on what to change. Nothing when the baseline drew the scene.
void markBlankBaseline(TradeResult& result);

// Whether a row's scores describe the scene: false for a blank row (its error is an empty image's)
// and for every row when the baseline is blank (its time and verdicts are against an empty image).
bool scoresMeaningful(const TradeResult& result, const TradeRow& row);

}  // namespace facet
