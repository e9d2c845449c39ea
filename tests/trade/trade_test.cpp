// facet trade: its knob table speaks the render command's language, its CSV is whole and finite, a knob
// that changes the image is scored as such, and the Pareto front and the metrics mean what they say.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "cli/render_command.h"
#include "cli/trade_command.h"
#include "reference/reference.h"
#include "support/temp_folder.h"
#include "support/user_shader_files.h"
#include "trade/knobs.h"
#include "trade/metrics.h"
#include "trade/pareto.h"
#include "trade/trade.h"

namespace facet {
namespace {

const std::string kModel = FACET_SOURCE_DIR "/models/spot/spot_triangulated.obj";

std::vector<std::string> splitCsvLine(const std::string& line) {  // the trade's CSV quotes no number
    std::vector<std::string> fields;
    std::string field;
    bool quoted = false;
    for (const char c : line) {
        if (c == '"')
            quoted = !quoted;
        else if (c == ',' && !quoted) {
            fields.push_back(field);
            field.clear();
        } else
            field += c;
    }
    fields.push_back(field);
    return fields;
}

// `facet trade spot.obj --knobs shading,transparency --frames 3 --rounds 2 ...` on a tiny image, parsed by
// the command's own parser and run once for the suite; its CSV read back, one map per row, and its
// progress lines kept.
class TradeRun : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        // The suite's folder (ctest runs each test in its own process, two at a time); the trade makes
        // its output folder in it.
        folder_ = std::make_unique<testing_support::TempFolder>();
        dir_ = folder_->path() / "trade";
        CLI::App app;
        cli::TradeArgs args;
        cli::addTradeCommand(app, args);
        // clang-format off
        const std::vector<std::string> words = {"trade", kModel, "--knobs", "shading,transparency",
                                                "--frames", "3", "--rounds", "2", "--reference-samples", "1",
                                                "--width", "48", "--height", "36", "--threads", "1",
                                                "-o", dir_.string()};
        // clang-format on
        app.parse(std::vector<std::string>(words.rbegin(), words.rend()));
        ::testing::internal::CaptureStderr();
        const int status = cli::trade(args);
        progress_ = ::testing::internal::GetCapturedStderr();
        ASSERT_EQ(status, 0);
        std::ifstream csv(dir_ / "trade.csv");
        std::string line;
        std::getline(csv, line);
        header_ = splitCsvLine(line);
        while (std::getline(csv, line)) {
            const std::vector<std::string> fields = splitCsvLine(line);
            ASSERT_EQ(fields.size(), header_.size()) << line;
            std::map<std::string, std::string> row;
            for (std::size_t k = 0; k < fields.size(); ++k)
                row[header_[k]] = fields[k];
            rows_.push_back(row);
        }
    }
    static void TearDownTestSuite() { folder_.reset(); }
    static const std::map<std::string, std::string>* row(const std::string& flags) {
        for (const auto& r : rows_)
            if (r.at("flags") == flags) return &r;
        return nullptr;
    }
    static double number(const std::map<std::string, std::string>& row, const std::string& column) {
        return std::stod(row.at(column));
    }
    static inline std::unique_ptr<testing_support::TempFolder> folder_;
    static inline std::filesystem::path dir_;
    static inline std::vector<std::string> header_;
    static inline std::vector<std::map<std::string, std::string>> rows_;
    static inline std::string progress_;
};

// --frames 3 over --rounds 2: every setting is timed in both rounds, in turn (round 1 of every setting
// before round 2 of any), and gets all three frames (2 + 1); the presets are timed after the knobs
// (the fast one is chosen from the knobs' times), in rounds of their own alongside the baseline, whose
// frames of both phases count (6). Breaks if the rounds are ignored (one round), if a later round's
// frames are not added to the first's (2 frames), if the remainder of frames / rounds is dropped, or
// if the presets are timed among the knobs.
TEST_F(TradeRun, EverySettingIsTimedInEveryRoundWithAllItsFrames) {
    for (const auto& r : rows_)
        EXPECT_EQ(r.at("frames"), r.at("knob") == "baseline" ? "6" : "3") << r.at("flags");
    auto count = [&](const std::string& text) {
        std::size_t n = 0;
        for (std::size_t at = progress_.find(text); at != std::string::npos;
             at = progress_.find(text, at + 1))
            ++n;
        return n;
    };
    const std::size_t presets = 2;  // fast and best; default is the baseline's own
    EXPECT_EQ(count("[round 1/2, "), rows_.size() - presets) << progress_;
    EXPECT_EQ(count("[round 2/2, "), rows_.size() - presets) << progress_;
    EXPECT_EQ(count("[presets, round 2/2, "), presets + 1) << progress_;  // and the baseline
    EXPECT_LT(progress_.rfind("[round 1/2, "), progress_.find("[round 2/2, "));
    EXPECT_LT(progress_.rfind("[round 2/2, "), progress_.find("[presets, round 1/2, "));
}

// Every progress line of a setting but the first (whose scoring loads the comparison) and the last says
// how long the trade still needs. Catches: the estimate dropped from the lines, or printed after the
// last run.
TEST_F(TradeRun, ProgressLinesEstimateTheTimeLeft) {
    std::vector<std::string> lines;
    std::istringstream in(progress_);
    for (std::string line; std::getline(in, line);)
        if (line.rfind("[", 0) == 0 && line.rfind("[0/", 0) != 0)
            lines.push_back(line);  // not the reference's
    ASSERT_GT(lines.size(), 3u) << progress_;
    const std::regex estimate("; (about [0-9]+ (min( [0-9]+ s)?|s)|under a second) left$");
    for (std::size_t i = 0; i < lines.size(); ++i)
        EXPECT_EQ(std::regex_search(lines[i], estimate), i > 0 && i + 1 < lines.size()) << lines[i];
}

TEST_F(TradeRun, CsvHoldsARowPerSettingWithFiniteNumbers) {
    // The baseline (Phong shading, sorted transparency), flat, Gouraud, unsorted, exact, the fast and best
    // presets; the default preset, --shading phong and --transparency sorted are the baseline's own
    // settings, skipped.
    ASSERT_EQ(rows_.size(), 7u);
    EXPECT_EQ(rows_[0].at("knob"), "baseline");
    EXPECT_NE(row("--shading flat"), nullptr);
    EXPECT_NE(row("--shading gouraud"), nullptr);
    EXPECT_EQ(row("--shading phong"), nullptr);
    std::size_t numbers = 0;
    for (const auto& r : rows_)
        for (const std::string& column : header_) {
            if (column.rfind("ms_", 0) != 0 && column.rfind("cpu_ms_", 0) != 0 &&
                column.rfind("linear_", 0) != 0 && column.rfind("output8_", 0) != 0)
                continue;
            SCOPED_TRACE(r.at("flags") + " " + column);
            const double value = number(r, column);
            EXPECT_TRUE(std::isfinite(value)) << r.at(column);
            ++numbers;
        }
    // 4 wall-clock times, 3 CPU times, 6 metrics in linear light and in 8 bits
    EXPECT_EQ(numbers, rows_.size() * 19);
    for (const auto& r : rows_) {
        EXPECT_TRUE(std::filesystem::exists(dir_ / r.at("image")));
        EXPECT_TRUE(std::filesystem::exists(dir_ / r.at("error_image")));
    }
    EXPECT_TRUE(std::filesystem::exists(dir_ / "reference.png"));
    EXPECT_TRUE(std::filesystem::exists(dir_ / "chart.png"));
}

TEST_F(TradeRun, FlatShadingIsFartherFromTheReferenceAndHasAnEffect) {
    const auto* flat = row("--shading flat");
    ASSERT_NE(flat, nullptr);
    EXPECT_EQ(flat->at("no_effect"), "0");
    EXPECT_LT(number(*flat, "output8_ssim"), number(rows_[0], "output8_ssim"));
    EXPECT_GT(number(*flat, "linear_mean_abs"), number(rows_[0], "linear_mean_abs"));
    EXPECT_LT(number(*flat, "linear_psnr_db"), number(rows_[0], "linear_psnr_db"));
}

// The cow is opaque: no transparency mode changes a pixel, and the trade says so.
TEST_F(TradeRun, ASettingThatChangesNothingIsFlagged) {
    for (const char* flags : {"--transparency unsorted", "--transparency exact"}) {
        SCOPED_TRACE(flags);
        const auto* r = row(flags);
        ASSERT_NE(r, nullptr);
        EXPECT_EQ(r->at("no_effect"), "1");
        EXPECT_EQ(r->at("output8_ssim"), rows_[0].at("output8_ssim"));
    }
    EXPECT_EQ(rows_[0].at("no_effect"), "0");  // the baseline is not compared with itself
}

// Each row's times are its own setting's frames: a clock of the test's (TradeOptions::clockMs) advances
// by a step of each setting's own at every reading, so a frame of setting k (from before its shadows'
// rebuild to after the draw: two readings after the start) takes 2·step_k ms and the rebuild step_k,
// in every round and both phases. Catches every row given the baseline's times (median(frameMs[0])),
// a row's min, max or shadow time taken from another setting's frames, or the clock option ignored.
TEST(TradeTimes, EachRowReportsItsOwnSettingsFrames) {
    const testing_support::TempFolder folder;
    const std::filesystem::path dir = folder.path() / "trade";
    cli::SceneArgs args;
    args.input = kModel;
    args.width = 32;
    args.height = 24;
    // A distinct step for each setting's words, in the order the trade first asks for them.
    std::map<std::vector<std::string>, double> steps;
    std::vector<std::string> current;
    auto stepOf = [&](const std::vector<std::string>& words) {
        return steps.emplace(words, 0.5 * double(steps.size() + 1)).first->second;
    };
    double now = 1000.0;
    TradeOptions options;
    options.knobs = "shading";
    options.frames = 3;
    options.rounds = 2;
    options.threads = 1;
    options.referenceSamples = 1;
    options.outputDir = dir;
    options.progress = false;
    options.clockMs = [&] {
        const double reading = now;
        now += stepOf(current);
        return reading;
    };
    std::ostringstream log;
    const TradeResult result = runTrade(
        [&](const std::vector<std::string>& words) {
            current = words;
            return cli::sceneWithWords(args, words);
        },
        options, log);
    // The baseline, flat, Gouraud, the fast and best presets (phong and the default preset are skipped).
    ASSERT_EQ(result.rows.size(), 5u);
    std::vector<double> medians;
    for (const TradeRow& row : result.rows) {
        SCOPED_TRACE(row.setting.knob + " " + row.setting.value);
        ASSERT_EQ(steps.count(row.setting.words), 1u);
        const double step = steps.at(row.setting.words);
        EXPECT_DOUBLE_EQ(row.msMedian, 2.0 * step);
        EXPECT_DOUBLE_EQ(row.msMin, 2.0 * step);
        EXPECT_DOUBLE_EQ(row.msMax, 2.0 * step);
        EXPECT_DOUBLE_EQ(row.msShadows, step);
        medians.push_back(row.msMedian);
    }
    std::sort(medians.begin(), medians.end());
    EXPECT_EQ(std::unique(medians.begin(), medians.end()), medians.end());  // five different times
    EXPECT_DOUBLE_EQ(result.referenceMs, steps.at({}));  // the reference: one reading, the baseline's step
}

// Every knob's every value is a command line `facet render` accepts (a renamed flag or value fails
// here), and reaches the scene so that the knob reads it back (what the trade's skipping relies on).
TEST(TradeKnobs, EverySettingIsAcceptedByTheRenderParserAndReachesTheScene) {
    for (const Knob& knob : knobTable())
        for (const std::string& value : knob.values) {
            const TradeSetting setting = knobSetting(knob, value);
            SCOPED_TRACE(setting.label());
            CLI::App app;
            cli::RenderArgs args;
            cli::addRenderCommand(app, args);
            std::vector<std::string> words = {"render", kModel, "-o", "out.png"};
            words.insert(words.end(), setting.words.begin(), setting.words.end());
            EXPECT_NO_THROW(app.parse(std::vector<std::string>(words.rbegin(), words.rend())));
            Scene scene = sceneForModel(kModel);
            cli::applyLightingOptions(args, scene);
            EXPECT_TRUE(sceneHasSetting(scene, setting));
        }
    for (const std::string& preset : kPresetNames) {
        SCOPED_TRACE(preset);
        cli::SceneArgs args;
        args.input = kModel;
        EXPECT_TRUE(
            sceneHasSetting(cli::sceneWithWords(args, presetSetting(preset).words), presetSetting(preset)));
    }
}

// The fast preset keeps the scene's value of a knob whose fast value changed the image and measured
// slower than the baseline (its median over 5% slower than the baseline's) and names it in a note; a knob
// whose fast value measured faster, changed nothing, or was not measured, keeps its fast value. Catches: the
// comparison reversed or dropped (flat shading back in the preset, or normalize fast left out), a knob
// without effect kept for noise, a note for a knob the preset does not set (the map's size), a kept knob's
// dependants (the map's size under --shadows none) still set, and the note missing.
TEST(TradePresets, TheFastPresetKeepsTheScenesValueWhereTheFastOneMeasuredSlower) {
    auto row = [](const std::string& knob, const std::string& value, double msMin, double msMedian,
                  bool noEffect = false) {
        TradeRow r;
        r.setting =
            knob == "baseline" ? TradeSetting{"baseline", "", {}} : knobSetting(knobNamed(knob), value);
        r.msMin = msMin;
        r.msMedian = msMedian;
        r.noEffect = noEffect;
        return r;
    };
    const std::vector<TradeRow> measured = {
        row("baseline", "", 9.0, 10.0),
        row("shading", "flat", 15.0, 16.0),                 // slower: the preset keeps the scene's shading
        row("normalize", "fast", 8.5, 10.4),                // within 5%: --normalize fast stays
        row("shadows", "none", 10.5, 11.0),                 // slower (noise, but the rule is the rule)
        row("aa", "msaa4", 40.0, 41.0),                     // not the knob's fast value: not a reason
        row("transparency", "unsorted", 12.0, 13.0, true),  // slower but no effect: stays
        row("shadows", "map", 30.0, 31.0),
        row("shadow-map-size", "512", 25.0, 26.0),  // slower than the baseline, but not in the preset
    };
    std::vector<std::string> notes;
    const std::vector<std::string> keep = fastPresetKeeps(measured, notes);
    EXPECT_EQ(keep, (std::vector<std::string>{"shading", "shadows"}));
    ASSERT_EQ(notes.size(), 2u);
    EXPECT_NE(notes[0].find("preset fast keeps the scene's --shading: --shading flat measured slower"),
              std::string::npos)
        << notes[0];
    const std::vector<std::string> words = presetSetting("fast", keep).words;
    auto has = [&](const std::string& flag) {
        return std::find(words.begin(), words.end(), flag) != words.end();
    };
    EXPECT_FALSE(has("--shading"));
    EXPECT_FALSE(has("--shadows"));
    EXPECT_FALSE(has("--shadow-map-size"));  // needs --shadows map, which the preset no longer sets
    EXPECT_TRUE(has("--normalize"));
    EXPECT_TRUE(has("--transparency"));
    // The map's size is not in the fast preset (its shadows are none): never a note, however slow.
    EXPECT_EQ(fastPresetKeeps({measured[0], measured[6], row("shadow-map-size", "512", 32.0, 33.0)}, notes),
              std::vector<std::string>{});
    EXPECT_TRUE(has("--interpolation"));  // not measured: its fast value stays
    EXPECT_TRUE(presetSetting("fast").words.size() > words.size());
}

TEST(TradeKnobs, AnUnknownNameIsOneLineListingTheValidOnes) {
    try {
        selectKnobs("shading,shadwos");
        FAIL() << "no error";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("--knobs: unknown knob \"shadwos\""), std::string::npos) << message;
        EXPECT_NE(message.find("shading, interpolation, shadows"), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    EXPECT_THROW(selectKnobs("shading,"), InputError);
    EXPECT_EQ(selectKnobs("shadows,shading").size(), 2u);
}

TEST(TradePareto, TheFrontIsThePointsNoneBeatsOnBothCounts) {
    // x: ms, y: error.
    const std::vector<glm::dvec2> points = {
        {10, 0.5},   // 0: on the front (fastest)
        {20, 0.1},   // 1: on the front
        {15, 0.6},   // 2: slower and worse than 0
        {30, 0.01},  // 3: on the front (most accurate)
        {30, 0.1},   // 4: as accurate as 1, slower
        {20, 0.1},   // 5: equal to 1: not beaten, on the front
        {40, 0.02},  // 6: slower and worse than 3
    };
    EXPECT_EQ(paretoFront(points), (std::vector<std::size_t>{0, 1, 5, 3}));
    EXPECT_EQ(paretoFront({{1, std::nan("")}, {2, 1}}), (std::vector<std::size_t>{1}));
}

TEST(TradeMetrics, IdenticalImagesHaveTheCappedPsnrAndAnSsimOfOne) {
    LinearImage image;
    image.width = 24;
    image.height = 16;
    for (int k = 0; k < image.width * image.height; ++k)
        image.pixels.push_back(glm::vec4(0.01f * (k % 97), 0.3f, 0.002f * (k % 13), 1.0f));
    const ImageError same = measureError(image, image, kSrgbEncoding);
    for (const ErrorMetrics* m : {&same.linear, &same.encoded}) {
        EXPECT_EQ(m->psnr, kMaxPsnr);
        EXPECT_DOUBLE_EQ(m->ssim, 1.0);
        EXPECT_EQ(m->meanAbs, 0.0);
        EXPECT_EQ(m->over1, 0.0);
    }
    // One pixel's red two codes off in the 8-bit image: above 1/255, not above 2/255.
    LinearImage other = image;
    other.pixels[5] = glm::vec4(0.5f, 0.3f, 0.0f, 1.0f);
    image.pixels[5] =
        glm::vec4(srgbToLinear((encodeChannel(0.5f, kSrgbEncoding) + 2) / 255.0f), 0.3f, 0.0f, 1.0f);
    const ImageError two = measureError(image, other, kSrgbEncoding);
    EXPECT_DOUBLE_EQ(two.encoded.over1, 1.0 / (24 * 16));
    EXPECT_EQ(two.encoded.over2, 0.0);
    EXPECT_NEAR(two.encoded.maxAbs, 2.0 / 255.0, 1e-6);
    EXPECT_LT(two.encoded.psnr, kMaxPsnr);
    EXPECT_LT(two.encoded.ssim, 1.0);
}

// facet trade --shader: the knobs timed and scored with a shader of one's own, against the reference
// traced with it (displace_cutout.cpp, its vertices moved along the normal). Breaks caught: the trade's
// settings parsed onto a fresh scene that drops --shader or --uniform (the rows drawn with the built-in
// shader, far from the reference); the reference traced with the built-in shader or at the mesh's own
// positions (its image the built-in's, the rows far from it).
TEST(TradeWithShader, TheKnobsAreScoredAgainstTheReferenceOfTheShader) {
    const testing_support::OwnShaderCache cache;
    const testing_support::TempFolder folder;
    CLI::App app;
    cli::TradeArgs args;
    cli::addTradeCommand(app, args);
    const std::string shader = (testing_support::kUserShaders / "displace_cutout.cpp").string();
    // clang-format off
    const std::vector<std::string> words = {"trade", kModel, "--shader", shader, "--uniform", "displacement=0.04",
                                            "--knobs", "depth", "--frames", "1", "--rounds", "1",
                                            "--reference-samples", "1", "--width", "48", "--height", "36",
                                            "--threads", "1", "-q", "-o", (folder.path() / "trade").string()};
    // clang-format on
    app.parse(std::vector<std::string>(words.rbegin(), words.rend()));
    TradeOptions options;
    options.knobs = args.knobs;
    selectKnobs(options.knobs);
    options.frames = args.frames;
    options.rounds = args.rounds;
    options.threads = 1;
    options.referenceSamples = args.referenceSamples;
    options.progress = false;
    options.outputDir = folder.path() / "trade";
    std::ostringstream log;
    const TradeResult result = runTrade(
        [&](const std::vector<std::string>& settingWords) {
            return cli::sceneWithWords(args.scene, settingWords);
        },
        options, log);
    ASSERT_GE(result.rows.size(), 2u);
    // The baseline (the shader as given) is close to the shader's reference.
    EXPECT_EQ(result.rows[0].setting.knob, "baseline");
    EXPECT_GT(result.rows[0].error.encoded.ssim, 0.95) << result.rows[0].image;
    // That reference is not the built-in shader's: the built-in's own reference image differs from it.
    Scene builtIn = loadSceneOrModel(kModel);
    builtIn.width = 48;
    builtIn.height = 36;
    ReferenceOptions referenceOptions;
    referenceOptions.samples = 1;
    ThreadPool pool(1);
    const LinearImage builtInReference = renderReference(prepareScene(builtIn), referenceOptions, pool);
    const LinearImage reference = readImage(options.outputDir / "reference.png");
    const ImageError error = measureError(reference, builtInReference, kSrgbEncoding);
    EXPECT_LT(error.encoded.ssim, 0.9) << error.encoded.ssim;
}

}  // namespace
}  // namespace facet
