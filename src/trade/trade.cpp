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
#include "io/text_file.h"
#include "reference/reference.h"
#include "render/renderer.h"
#include "render/user_shaders.h"
#include "trade/blank.h"
#include "trade/pareto.h"
#include "trade/presets.h"
#include "trade/progress.h"
#include "trade/recommend.h"
#include "trade/reference_floor.h"
#include "trade/report.h"
#include "trade/time_verdicts.h"

namespace facet {

namespace {

// The settings of the trade, in order: the baseline, each selected knob at each of its values, the
// presets (unless `presets` is false; they set only the selected knobs); those the baseline already has
// are left out (their labels in `skipped`).
std::vector<TradeSetting> tradeSettings(const Scene& baseline, const std::vector<const Knob*>& knobs,
                                        bool presets, std::vector<std::string>& skipped) {
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
    if (presets)
        for (const std::string& preset : kPresetNames)
            add(presetSetting(preset, knobsNotTraded(knobs)));
    return settings;
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
    const std::vector<TradeSetting> settings =
        tradeSettings(baseline, knobs, options.presets, result.skipped);
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
    // CPU milliseconds of the process, or options.cpuClockMs's.
    const auto cpuNow = [&] { return options.cpuClockMs ? options.cpuClockMs() : processCpuMs(); };

    // The reference: the scene as the user wrote it, drawn exactly. The reference renderer ignores the
    // rasterizer's approximations (it has no depth or colour buffer, composites every transparent
    // surface in depth order, ray-casts the shadows of every light that casts them, map or ray, and
    // uses exact pow, exp, normalisation and Fresnel), so what remains are the scene's own choices:
    // which lights cast shadows, its materials, maps and normals.
    TradeProgress progress(log, options.progress, now);
    const double referenceStart = now();
    progress.referenceStarted(referenceStart);
    // The settings draw the scene in several kinds of draw (depth formats, anti-aliasing, transparency):
    // a shader of one's own is compiled for all of them at once, not for the first and then again.
    compileEveryWalk();
    const PreparedScene referenceScene = prepareScene(baseline);
    ReferenceOptions referenceOptions;
    referenceOptions.samples = options.referenceSamples;
    std::vector<float> raySpread;  // where the reference's rays disagree: where its own error lies
    referenceOptions.raySpread = &raySpread;
    if (options.progress)
        referenceOptions.onRows = [&](int rowsDone, int rows) { progress.referenceRows(rowsDone, rows); };
    LinearImage reference = renderReference(referenceScene, referenceOptions, context.pool);
    result.referenceMs = now() - referenceStart;
    const ColorEncoding encoding = referenceScene.encoding;
    if (options.progress)
        log << "[0/" << settings.size() << "] reference (" << options.referenceSamples << "x"
            << options.referenceSamples << " rays per pixel): " << number(result.referenceMs, 0) << " ms\n"
            << std::flush;
    // Its own error estimated, and more rays while that is not small beside the baseline's error.
    settleReference(
        sceneWithWords, referenceScene, referenceOptions, reference, raySpread, result.referenceMs, context,
        now,
        [&](const std::string& line) {
            if (options.progress) log << "[0/" << settings.size() << "] " << line << "\n" << std::flush;
        },
        result);
    writeImage(options.outputDir / "reference.png", reference, encoding);
    // Where the reference shows the scene, against which each image is judged blank or not; a reference
    // that shows nothing is refused.
    const std::vector<bool> referenceSurface =
        surfacePixels(reference, emptyReference(referenceScene, referenceOptions, context.pool), encoding);
    requireReferenceShowsScene(referenceSurface, baseline.source.string());
    const LinearLight linearLight = linearLightFor(reference);
    if (linearLight == LinearLight::ToneMapped) {
        result.linearToneMapped = true;
        result.notes.push_back(
            "linear columns: the reference is brighter than 2 in places (an emission or a light above 1), "
            "so both images are compared after the tone map x / (1 + x)");
    }

    // Timing in rounds: round r times frames/rounds frames of each setting in turn (the first rounds one
    // more while frames is not a multiple). The first round also makes each setting's image and scores
    // it: the image does not depend on the round. Two phases: the baseline and the knobs, then the
    // presets alongside the baseline again (its frames of both phases pooled), because the presets are
    // chosen from the first phase's measurements.
    // Every frame is timed twice: by the wall clock (what a user waits) and by the CPU time of the whole
    // process, every render thread included, which other work on a shared machine disturbs far less
    // (the time slices it takes are not counted); the verdicts use the CPU time (time_verdicts.h).
    const int rounds = std::min(options.rounds, options.frames);
    std::vector<std::vector<double>> frameMs(settings.size()), shadowMs(settings.size()),
        cpuMs(settings.size());
    // Each setting's CPU median of each round (the baseline's of both phases): the same work timed
    // again, from which the run's noise is measured.
    std::vector<std::vector<double>> roundCpuMs(settings.size());
    std::vector<TradeSetting> rendered = settings;
    result.rows.resize(settings.size());
    std::vector<bool> scoredYet(settings.size(), false);
    LinearImage baselineImage;
    // What other processes took from this process's CPUs while the frames were timed (busy warning).
    double othersCpuMs = 0, timedWallMs = 0;
    auto timeInRounds = [&](const std::vector<std::size_t>& indices, const char* phase) {
        const auto wallStart = std::chrono::steady_clock::now();
        const double busyStart = allowedCpusBusyMs(), ownStart = processCpuMs();
        for (int round = 0; round < rounds; ++round) {
            const int framesThisRound = options.frames / rounds + (round < options.frames % rounds ? 1 : 0);
            for (const std::size_t k : indices) {
                progress.runStarted(k);
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
                    const double start = now(), cpuStart = cpuNow();
                    prepareShadows(prepared);
                    shadowMs[k].push_back(now() - start);
                    renderFrame(prepared, framebuffer, context, memory);
                    frameMs[k].push_back(now() - start);
                    cpuMs[k].push_back(cpuNow() - cpuStart);
                }
                progress.framesTimed(k);
                if (framesThisRound > 0)
                    roundCpuMs[k].push_back(
                        median(std::vector<double>(cpuMs[k].end() - framesThisRound, cpuMs[k].end())));
                // A row per setting, scored the first time it is drawn (the knobs' in the first phase, the
                // presets' in the second); a setting already scored (the baseline again) is only timed. A
                // preset no knob went into is never drawn, and keepPresetPromises drops its row.
                const bool scored = scoredYet[k];
                if (!scored) {
                    scoredYet[k] = true;
                    TradeRow& row = result.rows[k];
                    row.setting = rendered[k];
                    const LinearImage image = toImage(framebuffer);
                    row.error = measureError(image, reference, encoding, linearLight);
                    const Coverage coverage = coverageOf(
                        surfacePixels(image, emptyFrame(prepared, context), encoding), referenceSurface);
                    row.blank = coverage.blank();
                    if (row.blank) result.warnings.push_back(blankWarning(row.setting, coverage));
                    row.changesContent = settingChangesContent(baseline, row.setting);
                    if (k == 0)
                        baselineImage = image;
                    else  // two images that both draw nothing of the scene say nothing of the knob
                        row.noEffect =
                            !result.rows.front().blank && sameEncoded(image, baselineImage, encoding);
                    const std::string stem = settingFileStem(static_cast<int>(k), row.setting);
                    row.image = stem + ".png";
                    row.errorImage = stem + "-error.png";
                    writeImage(options.outputDir / row.image, image, encoding);
                    writeImage(options.outputDir / row.errorImage, errorImage(image, reference, encoding));
                }
                TradeRow& row = result.rows[k];
                row.msMedian = median(frameMs[k]);
                row.msMin = *std::min_element(frameMs[k].begin(), frameMs[k].end());
                row.msMax = *std::max_element(frameMs[k].begin(), frameMs[k].end());
                row.msShadows = median(shadowMs[k]);
                row.frames = static_cast<int>(frameMs[k].size());
                row.cpuMsMedian = median(cpuMs[k]);
                row.cpuMsMin = *std::min_element(cpuMs[k].begin(), cpuMs[k].end());
                row.cpuMsMax = *std::max_element(cpuMs[k].begin(), cpuMs[k].end());
                progress.runFinished(k);
                if (options.progress) {
                    log << "[" << phase;
                    if (rounds > 1) log << "round " << round + 1 << "/" << rounds << ", ";
                    log << k + 1 << "/" << settings.size() << "] " << tradeRowLabel(row.setting) << ": "
                        << number(row.msMedian, 1) << " ms";
                    if (!scored)
                        log << ", 1 - SSIM " << std::setprecision(3) << tradeError(row)
                            << (row.noEffect ? ", no effect" : "");
                    log << progress.leftSuffix() << "\n" << std::flush;
                }
            }
        }
        const double busyEnd = allowedCpusBusyMs();
        if (busyStart >= 0 && busyEnd >= 0) {
            othersCpuMs += std::max(0.0, (busyEnd - busyStart) - (processCpuMs() - ownStart));
            timedWallMs +=
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wallStart)
                    .count();
        }
    };
    std::vector<std::size_t> knobRows, presetRows = {0};
    for (std::size_t k = 0; k < settings.size(); ++k)
        (settings[k].knob == "preset" ? presetRows : knobRows).push_back(k);
    {  // the runs to come, for the estimate of the time left: the phases below, round by round
        std::vector<std::size_t> runs;
        for (const std::vector<std::size_t>* phase : {&knobRows, &presetRows})
            for (int round = 0; round < rounds && (phase == &knobRows || presetRows.size() > 1); ++round)
                runs.insert(runs.end(), phase->begin(), phase->end());
        progress.plan(std::move(runs));
    }
    timeInRounds(knobRows, "");
    if (presetRows.size() > 1) {
        // The fast and best presets are what measured fast (accurate) here, judged against the noise of
        // the first phase: a knob goes in only where its own row showed the gain (presets.h).
        // The knobs' errors judged against the reference's own first: best takes no value whose gain lies
        // within it.
        markWithinReferenceFloor(result.rows, result.referenceFloor);
        std::vector<TradeRow> measured(result.rows.begin(), result.rows.begin() + presetRows[1]);
        TradeResult firstPhase;
        firstPhase.rows = measured;
        judgeTimes(firstPhase, roundCpuMs);
        std::vector<std::size_t> timed = {0};
        for (const std::size_t k : presetRows) {
            if (k == 0) continue;
            if (settings[k].value == "fast" || settings[k].value == "best")
                rendered[k] = choosePreset(settings[k].value, firstPhase.rows, knobs, result.notes);
            result.rows[k].setting = rendered[k];
            if (!rendered[k].words.empty()) timed.push_back(k);  // no knob chosen: it is the baseline
        }
        std::vector<std::size_t> presetRuns;
        for (int round = 0; timed.size() > 1 && round < rounds; ++round)
            presetRuns.insert(presetRuns.end(), timed.begin(), timed.end());
        progress.replanRest(std::move(presetRuns));
        if (timed.size() > 1) timeInRounds(timed, "presets, ");
    }

    markWithinReferenceFloor(result.rows, result.referenceFloor);
    // Verdicts against the run's own noise, then the presets checked against them, then the front.
    judgeTimes(result, roundCpuMs);
    keepPresetPromises(result);
    markParetoFront(result.rows, result.timeNoise, result.referenceFloor);
    if (timedWallMs > 0)
        if (const std::string warning = busyMachineWarning(othersCpuMs / timedWallMs, allowedCpuCount(),
                                                           context.pool.threads(), result.timeNoise);
            !warning.empty())
            result.warnings.push_back(warning);

    result.recommendations = tradeRecommendations(result);
    markBlankBaseline(result);
    {
        std::ostringstream csv;  // written whole, as every output is (io/output_path.h)
        writeTradeCsv(result, csv);
        writeTextFile(options.outputDir / "trade.csv", csv.str());
    }
    std::string title = "SPEED AND ERROR: ";
    title += baseline.source.filename().string();
    title += " ";
    title += std::to_string(baseline.width);
    title += "X";
    title += std::to_string(baseline.height);
    writeTradeChart(result, title, options.outputDir / "chart.png");
    return result;
}

}  // namespace facet
