#include "trade/blank.h"

#include <algorithm>

#include "base/errors.h"
#include "shading/gamma.h"

namespace facet {

LinearImage emptyFrame(const PreparedScene& prepared, DrawContext& context) {
    PreparedScene empty = prepared;  // a cheap copy: the assets and geometry are shared
    empty.draws.clear();
    empty.transparentTriangles = {};
    Framebuffer framebuffer(empty.scene.width, empty.scene.height);
    FrameMemory memory;
    renderFrame(empty, framebuffer, context, memory);
    return toImage(framebuffer);
}

LinearImage emptyReference(const PreparedScene& prepared, const ReferenceOptions& options, ThreadPool& pool) {
    PreparedScene empty = prepared;
    empty.draws.clear();
    empty.transparentTriangles = {};
    return renderReference(empty, options, pool);
}

std::vector<bool> surfacePixels(const LinearImage& image, const LinearImage& background,
                                ColorEncoding encoding) {
    std::vector<bool> surface(image.pixels.size(), false);
    if (background.pixels.size() != image.pixels.size()) return surface;
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int channel = 0; channel < 3 && !surface[i]; ++channel)
            surface[i] = encodeChannel(image.pixels[i][channel], encoding) !=
                         encodeChannel(background.pixels[i][channel], encoding);
    return surface;
}

Coverage coverageOf(const std::vector<bool>& imageSurface, const std::vector<bool>& referenceSurface) {
    Coverage coverage;
    for (std::size_t i = 0; i < referenceSurface.size(); ++i) {
        if (!referenceSurface[i]) continue;
        ++coverage.reference;
        if (i < imageSurface.size() && imageSurface[i]) ++coverage.shown;
    }
    return coverage;
}

void requireReferenceShowsScene(const std::vector<bool>& referenceSurface, const std::string& source) {
    if (std::find(referenceSurface.begin(), referenceSurface.end(), true) != referenceSurface.end()) return;
    throw InputError(source +
                     ": the exact reference image shows only the background, so there is nothing to trade "
                     "(is the scene in front of the camera, between its near and far planes?)");
}

std::string blankWarning(const TradeSetting& setting, const Coverage& coverage) {
    const bool baseline = setting.knob == "baseline";
    std::string text = baseline                   ? "the baseline (the scene as given)"
                       : setting.knob == "preset" ? "preset " + setting.value
                                                  : setting.label();
    text += coverage.shown == 0 ? " draws nothing" : " draws almost nothing";
    text += " where the reference shows the scene (" + std::to_string(coverage.shown) + " of its " +
            std::to_string(coverage.reference) + " pixels)";
    text += baseline ? ": its times and errors are those of an empty image, not of the scene"
                     : ": a blank image, left off the Pareto front";
    return text;
}

bool scoresMeaningful(const TradeResult& result, const TradeRow& row) {
    return !row.blank && !(!result.rows.empty() && result.rows.front().blank);
}

void markBlankBaseline(TradeResult& result) {
    if (result.rows.empty() || !result.rows.front().blank) return;
    for (TradeRow& row : result.rows) {
        row.noEffect = false;
        row.withinReferenceFloor = false;
        row.timeVerdict = TimeVerdict::WithinNoise;
    }
    result.rows.front().pareto = false;
    result.warnings.insert(result.warnings.begin(),
                           "the scores are meaningless: the baseline (the scene as given) draws nothing of "
                           "what the reference shows, so no setting is judged faster, slower, more "
                           "accurate or without effect against it (trade.csv: scores_meaningful 0)");
    result.recommendations = {
        "none: the scene as given draws nothing of what the reference shows; make it draw the scene "
        "(another camera, near plane, depth format or culling) and run the trade again"};
}

}  // namespace facet
