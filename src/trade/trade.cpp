#include "trade/trade.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "base/errors.h"
#include "bench/chart.h"
#include "bench/process_stats.h"
#include "reference/reference.h"
#include "render/renderer.h"
#include "trade/pareto.h"
#include "trade/recommend.h"

namespace facet {

namespace {

// The settings of the trade, in order: the baseline, each selected knob at each of its values, the
// presets; those the baseline already has are left out (their labels in `skipped`).
std::vector<TradeSetting> tradeSettings(const Scene& baseline, const std::vector<const Knob*>& knobs,
                                        std::vector<std::string>& skipped) {
    std::vector<TradeSetting> settings = {TradeSetting{"baseline", "", {}}};
    auto add = [&](TradeSetting setting) {
        if (sceneHasSetting(baseline, setting))
            skipped.push_back((setting.knob == "preset" ? "preset " + setting.value : setting.label()) +
                              " (the baseline's own)");
        else
            settings.push_back(std::move(setting));
    };
    auto selected = [&](const std::string& name) {
        return std::any_of(knobs.begin(), knobs.end(), [&](const Knob* knob) { return knob->name == name; });
    };
    for (const Knob* knob : knobs)
        for (const std::string& value : knob->values) {
            TradeSetting setting = knobSetting(*knob, value);
            // "--shadows map --shadow-map-size 2048" is "--shadows map", which the shadows knob runs.
            if (!knob->needsKnob.empty() && value == knob->defaultValue && selected(knob->needsKnob) &&
                !sceneHasSetting(baseline, knobSetting(knobNamed(knob->needsKnob), knob->needsValue))) {
                skipped.push_back(setting.label() + " (the same as " +
                                  knobSetting(knobNamed(knob->needsKnob), knob->needsValue).label() + ")");
                continue;
            }
            add(std::move(setting));
        }
    for (const std::string& preset : kPresetNames)
        add(presetSetting(preset));
    return settings;
}

// The chart's label of a row: the knob's own words (its prerequisite's are in the CSV), "preset fast".
std::string chartLabel(const TradeSetting& setting) {
    if (setting.knob == "baseline") return "baseline";
    if (setting.knob == "preset") return "preset " + setting.value;
    return setting.words[setting.words.size() - 2] + " " + setting.words.back();
}

void writeChart(const TradeResult& result, const std::string& title, const std::filesystem::path& path) {
    std::vector<LabelledPoint> points;
    std::vector<glm::dvec2> xy;
    for (const TradeRow& row : result.rows) {
        // A setting without effect sits on the baseline's error: pale and unlabelled, so that the cluster
        // around the baseline does not bury the labels of the settings that matter.
        const vec4 color = row.pareto                     ? srgb8(30, 100, 200)
                           : row.setting.knob == "preset" ? srgb8(230, 120, 20)
                           : row.noEffect                 ? srgb8(205, 205, 205)
                                                          : srgb8(150, 150, 150);
        points.push_back({row.noEffect && !row.pareto ? std::string() : chartLabel(row.setting),
                          {row.msMedian, tradeError(row)},
                          row.setting.knob == "baseline" ? srgb8(20, 20, 20) : color});
        xy.push_back(points.back().point);
    }
    Canvas canvas(1200, 800, vec4(1.0f));
    drawScatter(canvas, 0, 0, 1200, 800, title, "MS PER FRAME (MEDIAN)",
                "1 - SSIM OF THE 8-BIT IMAGE (LOG); BLUE: PARETO FRONT; PALE: NO EFFECT", true, points,
                paretoFront(xy));
    writeImage(path, canvas.image());
}

std::string number(double value, int decimals) {
    char text[32];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

// Enough digits for a CSV: a metric of 0.9999987 keeps its distance from 1.
std::string csvNumber(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", value);
    return text;
}

std::string csvField(const std::string& text) {  // quoted when it holds a comma or a quote
    if (text.find_first_of(",\"") == std::string::npos) return text;
    std::string quoted = "\"";
    for (const char c : text) {
        if (c == '"') quoted += '"';
        quoted += c;
    }
    quoted += '"';
    return quoted;
}

}  // namespace

std::string settingFileStem(int number, const TradeSetting& setting) {
    char prefix[8];
    std::snprintf(prefix, sizeof prefix, "%02d", number);
    std::string stem = prefix;
    if (setting.knob == "baseline") return stem + "-baseline";
    if (setting.knob == "preset") return stem + "-preset-" + setting.value;
    for (const std::string& word : setting.words) {  // "--shading flat" → "-shading-flat"
        stem += "-";
        for (const char c : word.substr(word.rfind("--", 0) == 0 ? 2 : 0))
            stem += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.' ? c : '_';
    }
    return stem;
}

TradeResult runTrade(const SceneWithWords& sceneWithWords, const TradeOptions& options, std::ostream& log) {
    if (options.frames < 1 || options.frames > kMaxTradeFrames)
        throw InputError("--frames must be from 1 to " + std::to_string(kMaxTradeFrames) + " (got " +
                         std::to_string(options.frames) + ")");
    if (options.rounds < 1 || options.rounds > kMaxTradeRounds)
        throw InputError("--rounds must be from 1 to " + std::to_string(kMaxTradeRounds) + " (got " +
                         std::to_string(options.rounds) + ")");
    if (options.referenceSamples < 1 || options.referenceSamples > kMaxReferenceSamples)
        throw InputError("--reference-samples must be from 1 to " + std::to_string(kMaxReferenceSamples) +
                         " (N×N rays per pixel; got " + std::to_string(options.referenceSamples) + ")");
    const std::vector<const Knob*> knobs = selectKnobs(options.knobs);
    const Scene baseline = sceneWithWords({});
    checkImageDestination(options.outputDir / "reference.png", baseline.width, baseline.height);

    TradeResult result;
    result.width = baseline.width;
    result.height = baseline.height;
    const std::vector<TradeSetting> settings = tradeSettings(baseline, knobs, result.skipped);
    DrawContext context(options.threads);
    std::filesystem::create_directories(options.outputDir);

    // Milliseconds since the trade began, or options.clockMs's.
    const auto origin = std::chrono::steady_clock::now();
    const auto now = [&] {
        return options.clockMs
                   ? options.clockMs()
                   : std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - origin)
                         .count();
    };

    // The reference: the scene as the user wrote it, drawn exactly. The reference renderer ignores the
    // rasterizer's approximations (it has no depth or colour buffer, composites every transparent
    // surface in depth order, ray-casts the shadows of every light that casts them, map or ray, and
    // uses exact pow, exp, normalisation and Fresnel), so what remains are the scene's own choices:
    // which lights cast shadows, its materials, maps and normals.
    const double referenceStart = now();
    const PreparedScene referenceScene = prepareScene(baseline);
    ReferenceOptions referenceOptions;
    referenceOptions.samples = options.referenceSamples;
    const LinearImage reference = renderReference(referenceScene, referenceOptions, context.pool);
    result.referenceMs = now() - referenceStart;
    const ColorEncoding encoding = referenceScene.encoding;
    writeImage(options.outputDir / "reference.png", reference, encoding);
    if (options.progress)
        log << "[0/" << settings.size() << "] reference (" << options.referenceSamples << "x"
            << options.referenceSamples << " rays per pixel): " << number(result.referenceMs, 0) << " ms\n"
            << std::flush;

    // Timing in rounds: round r times frames/rounds frames of each setting in turn (the first rounds one
    // more while frames is not a multiple). The first round also makes each setting's image and scores
    // it: the image does not depend on the round. Two phases: the baseline and the knobs, then the
    // presets alongside the baseline again (its frames of both phases pooled), because the fast preset
    // is chosen from the first phase's times.
    const int rounds = std::min(options.rounds, options.frames);
    std::vector<std::vector<double>> frameMs(settings.size()), shadowMs(settings.size());
    std::vector<TradeSetting> rendered = settings;
    LinearImage baselineImage;
    auto timeInRounds = [&](const std::vector<std::size_t>& indices, const char* phase) {
        for (int round = 0; round < rounds; ++round) {
            const int framesThisRound = options.frames / rounds + (round < options.frames % rounds ? 1 : 0);
            for (const std::size_t k : indices) {
                // The reference's models and textures, unless the setting changes how they load.
                PreparedScene prepared =
                    prepareScene(sceneWithWords(rendered[k].words), referenceScene.assets);
                Framebuffer framebuffer(prepared.scene.width, prepared.scene.height);
                FrameMemory
                    memory;  // the transparent triangles' order from frame to frame, as an animation's
                // A frame of the scene in motion: what its shadows need (the maps, the BVH of ray-cast
                // shadows) rebuilt as setTurntable rebuilds it, then the frame drawn. A scene without
                // shadows pays nothing.
                prepareShadows(prepared);  // warm-up: caches, buffers, threads
                renderFrame(prepared, framebuffer, context, memory);
                for (int frame = 0; frame < framesThisRound; ++frame) {
                    const double start = now();
                    prepareShadows(prepared);
                    shadowMs[k].push_back(now() - start);
                    renderFrame(prepared, framebuffer, context, memory);
                    frameMs[k].push_back(now() - start);
                }
                // Rows are made in settings' order: the knobs' in the first phase, the presets' (the
                // last settings) in the second; a setting already scored (the baseline again) is only timed.
                const bool scored = k < result.rows.size();
                if (!scored) {
                    TradeRow row;
                    row.setting = rendered[k];
                    const LinearImage image = toImage(framebuffer);
                    row.error = measureError(image, reference, encoding);
                    if (k == 0)
                        baselineImage = image;
                    else
                        row.noEffect = sameEncoded(image, baselineImage, encoding);
                    const std::string stem = settingFileStem(static_cast<int>(k), row.setting);
                    row.image = stem + ".png";
                    row.errorImage = stem + "-error.png";
                    writeImage(options.outputDir / row.image, image, encoding);
                    writeImage(options.outputDir / row.errorImage, errorImage(image, reference, encoding));
                    result.rows.push_back(std::move(row));
                }
                TradeRow& row = result.rows[k];
                row.msMedian = median(frameMs[k]);
                row.msMin = *std::min_element(frameMs[k].begin(), frameMs[k].end());
                row.msMax = *std::max_element(frameMs[k].begin(), frameMs[k].end());
                row.msShadows = median(shadowMs[k]);
                row.frames = static_cast<int>(frameMs[k].size());
                if (options.progress) {
                    log << "[" << phase;
                    if (rounds > 1) log << "round " << round + 1 << "/" << rounds << ", ";
                    log << k + 1 << "/" << settings.size() << "] " << row.setting.label() << ": "
                        << number(row.msMedian, 1) << " ms";
                    if (!scored)
                        log << ", 1 - SSIM " << std::setprecision(3) << tradeError(row)
                            << (row.noEffect ? ", no effect" : "");
                    log << "\n" << std::flush;
                }
            }
        }
    };
    std::vector<std::size_t> knobRows, presetRows = {0};
    for (std::size_t k = 0; k < settings.size(); ++k)
        (settings[k].knob == "preset" ? presetRows : knobRows).push_back(k);
    timeInRounds(knobRows, "");
    if (presetRows.size() > 1) {
        // The fast preset is what measured fast here: a knob whose fast value was slower keeps the scene's.
        for (const std::size_t k : presetRows)
            if (settings[k].knob == "preset" && settings[k].value == "fast")
                rendered[k] = presetSetting("fast", fastPresetKeeps(result.rows, result.notes));
        timeInRounds(presetRows, "presets, ");
    }

    std::vector<glm::dvec2> points;
    for (const TradeRow& row : result.rows)
        points.push_back({row.msMedian, tradeError(row)});
    for (const std::size_t i : paretoFront(points))
        result.rows[i].pareto = true;

    result.recommendations = tradeRecommendations(result);
    {
        std::ofstream csv(options.outputDir / "trade.csv");
        writeTradeCsv(result, csv);
        if (!csv) throw InputError((options.outputDir / "trade.csv").string() + ": cannot write the file");
    }
    std::string title = "SPEED AND ERROR: ";
    title += baseline.source.filename().string();
    title += " ";
    title += std::to_string(baseline.width);
    title += "X";
    title += std::to_string(baseline.height);
    writeChart(result, title, options.outputDir / "chart.png");
    return result;
}

std::vector<std::string> fastPresetKeeps(const std::vector<TradeRow>& measured,
                                         std::vector<std::string>& notes) {
    constexpr double kSlowerBy = 1.05;  // beyond the medians' own wobble on a quiet machine
    std::vector<std::string> keep;
    if (measured.empty() || measured.front().setting.knob != "baseline") return keep;
    const TradeRow& baseline = measured.front();
    auto rowOf = [&](const TradeSetting& setting) -> const TradeRow* {
        for (const TradeRow& row : measured)
            if (row.setting.words == setting.words) return &row;
        return nullptr;
    };
    for (const Knob& knob : knobTable()) {
        if (knob.fastValue.empty()) continue;
        // A knob under another's value the fast preset does not set (the map's size under --shadows
        // none) is not in the preset: nothing to decide either.
        if (!knob.needsKnob.empty() && knobNamed(knob.needsKnob).fastValue != knob.needsValue) continue;
        const TradeRow* fast = rowOf(knobSetting(knob, knob.fastValue));
        // A fast value that changes nothing costs no accuracy: whatever its time, nothing to decide.
        if (!fast || fast->noEffect) continue;
        if (fast->msMedian <= kSlowerBy * baseline.msMedian) continue;
        keep.push_back(knob.name);
        notes.push_back("preset fast keeps the scene's " + knob.flag + ": " + fast->setting.label() +
                        " measured slower (median " + number(fast->msMedian, 2) + " ms, the baseline's " +
                        number(baseline.msMedian, 2) + " ms)");
    }
    return keep;
}

void writeTradeCsv(const TradeResult& result, std::ostream& out) {
    out << "knob,value,flags,frames,ms_median,ms_min,ms_max,ms_shadow_setup";
    for (const char* space : {"linear", "output8"})
        for (const char* metric : {"psnr_db", "ssim", "mean_abs", "max_abs", "over_1_255", "over_2_255"})
            out << "," << space << "_" << metric;
    out << ",no_effect,pareto,image,error_image\n";
    for (const TradeRow& row : result.rows) {
        out << csvField(row.setting.knob) << "," << csvField(row.setting.value) << ","
            << csvField(row.setting.words.empty() ? "" : row.setting.label()) << "," << row.frames << ","
            << csvNumber(row.msMedian) << "," << csvNumber(row.msMin) << "," << csvNumber(row.msMax) << ","
            << csvNumber(row.msShadows);
        for (const ErrorMetrics* m : {&row.error.linear, &row.error.encoded})
            for (const double value : {m->psnr, m->ssim, m->meanAbs, m->maxAbs, m->over1, m->over2})
                out << "," << csvNumber(value);
        out << "," << row.noEffect << "," << row.pareto << "," << csvField(row.image) << ","
            << csvField(row.errorImage) << "\n";
    }
}

void printTradeTable(const TradeResult& result, std::ostream& out) {
    constexpr int kLabel = 26;
    out << std::string(kLabel, ' ') << "  ms per frame    linear       8-bit output\n";
    out << std::left << std::setw(kLabel) << "setting" << std::right << std::setw(8) << "median"
        << std::setw(7) << "spread" << std::setw(7) << "PSNR" << std::setw(7) << "SSIM" << std::setw(7)
        << "PSNR" << std::setw(7) << "SSIM" << std::setw(6) << "mean" << std::setw(4) << "max" << std::setw(7)
        << ">1/255" << std::setw(7) << ">2/255"
        << "\n";
    for (const TradeRow& row : result.rows) {
        const std::string label =
            row.setting.knob == "preset" ? "preset " + row.setting.value : row.setting.label();
        if (static_cast<int>(label.size()) > kLabel)
            out << label << "\n" << std::string(kLabel, ' ');
        else
            out << std::left << std::setw(kLabel) << label << std::right;
        const ErrorMetrics& lin = row.error.linear;
        const ErrorMetrics& enc = row.error.encoded;
        out << std::setw(8) << number(row.msMedian, 2) << std::setw(7) << number(row.msMax - row.msMin, 2)
            << std::setw(7) << number(lin.psnr, 1) << std::setw(7) << number(lin.ssim, 4) << std::setw(7)
            << number(enc.psnr, 1) << std::setw(7) << number(enc.ssim, 4) << std::setw(6)
            << number(255.0 * enc.meanAbs, 2) << std::setw(4) << std::lround(255.0 * enc.maxAbs)
            << std::setw(6) << number(100.0 * enc.over1, 1) << "%" << std::setw(6)
            << number(100.0 * enc.over2, 1) << "%";
        if (row.pareto) out << " front";
        if (row.noEffect) out << " NO EFFECT";
        out << "\n";
    }
    out << "spread: slowest minus fastest frame; 8-bit mean and max in code steps; front: on the Pareto "
           "front\n(none faster and more accurate, by 1 - SSIM of the 8-bit image); NO EFFECT: the same "
           "8-bit image as the baseline\n";
    for (const std::string& skipped : result.skipped)
        out << "skipped: " << skipped << "\n";
    for (const std::string& note : result.notes)
        out << note << "\n";
}

}  // namespace facet
