// The choice of the frame's copy (render/frame_kernels.h, chooseInstructionSet) fed with made-up CPUs and
// timings, and the record of timings facet bench --instruction-sets keeps per CPU model. Nothing here
// times anything: the timings are given.
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "render/frame_kernels.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

using enum InstructionSet;

const std::vector<InstructionSet> kAll = {Baseline, Avx2, Avx512};
const std::vector<InstructionSet> kNoAvx512 = {Baseline, Avx2};

InstructionSetChoice choose(std::string_view forced, const std::vector<InstructionSet>& runs,
                            const std::vector<MeasuredCopy>& measured) {
    return chooseInstructionSet({forced, kAll, runs, measured});
}

// Catches: the choice ignoring what was measured (always the widest), when AVX2 measured faster.
TEST(InstructionSetChoice, AMeasuredFasterNarrowerCopyWins) {
    const InstructionSetChoice chosen = choose("", kAll, {{Baseline, 35.0}, {Avx2, 13.2}, {Avx512, 14.0}});
    EXPECT_EQ(chosen.set, Avx2);
    EXPECT_NE(chosen.reason.find("measured fastest"), std::string::npos) << chosen.reason;
    EXPECT_NE(chosen.reason.find("avx2 13.20 ms, avx512 14.00 ms"), std::string::npos) << chosen.reason;
}

// Catches: an inverted comparison (the slowest copy chosen) or one that always takes the narrowest.
TEST(InstructionSetChoice, AMeasuredFasterWiderCopyWins) {
    EXPECT_EQ(choose("", kAll, {{Avx512, 13.4}, {Baseline, 35.0}, {Avx2, 13.6}}).set, Avx512);
}

// Catches: a tie settled for the narrower copy, which would move a CPU off the copy it used unmeasured
// for no measured gain.
TEST(InstructionSetChoice, ATieGoesToTheWiderCopy) {
    EXPECT_EQ(choose("", kAll, {{Baseline, 20.0}, {Avx2, 13.5}, {Avx512, 13.5}}).set, Avx512);
}

// Catches: FACET_ISA overruled by a recorded measurement.
TEST(InstructionSetChoice, FacetIsaWinsOverAMeasurement) {
    const InstructionSetChoice chosen =
        choose("avx512", kAll, {{Baseline, 35.0}, {Avx2, 1.0}, {Avx512, 99.0}});
    EXPECT_EQ(chosen.set, Avx512);
    EXPECT_EQ(chosen.reason, "forced by FACET_ISA=avx512");
}

// Catches: a record that leaves out a copy this CPU runs (made by a build with fewer copies) deciding
// anyway, so that the new copy would never run; and a missing record not falling back to the widest.
TEST(InstructionSetChoice, WithoutATimingOfEveryCopyTheWidestIsChosen) {
    const InstructionSetChoice partial = choose("", kAll, {{Baseline, 35.0}, {Avx2, 13.0}});
    EXPECT_EQ(partial.set, Avx512);
    EXPECT_NE(partial.reason.find("not measured on this CPU model, so the widest"), std::string::npos)
        << partial.reason;
    EXPECT_EQ(choose("", kNoAvx512, {}).set, Avx2);
    EXPECT_EQ(choose("", {Baseline}, {}).set, Baseline);
}

// Catches: a recorded copy this CPU cannot run being chosen (it would fault on its first instruction).
TEST(InstructionSetChoice, ARecordedCopyTheCpuCannotRunIsNeverChosen) {
    EXPECT_EQ(choose("", kNoAvx512, {{Baseline, 35.0}, {Avx2, 14.0}, {Avx512, 1.0}}).set, Avx2);
}

// Catches: a bad FACET_ISA followed silently (a benchmark forcing one copy would time another).
TEST(InstructionSetChoice, ABadFacetIsaIsAnError) {
    try {
        choose("avx7", kAll, {});
        ADD_FAILURE() << "accepted avx7";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("names no instruction set (one of: baseline, avx2, avx512)"),
                  std::string::npos)
            << e.what();
    }
    try {
        choose("avx512", kNoAvx512, {{Avx512, 1.0}});
        ADD_FAILURE() << "accepted avx512 on a CPU without it";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("this CPU cannot run avx512"), std::string::npos) << e.what();
    }
}

// Catches: the record written by the bench not read back as written, another CPU model's line lost
// when one is replaced, or a model whose name begins another's taking its timings.
TEST(InstructionSetTimings, AModelsLineIsReplacedAndOthersKept) {
    const std::vector<MeasuredCopy> first = {{Baseline, 35.0}, {Avx2, 13.61}, {Avx512, 13.42}};
    const std::vector<MeasuredCopy> second = {{Baseline, 30.5}, {Avx2, 12.25}};
    std::string text = withInstructionSetTimings("", "AMD EPYC", first);
    text = withInstructionSetTimings(text, "AMD EPYC 9B45", second);
    text = withInstructionSetTimings(text, "AMD EPYC", second);
    const std::vector<MeasuredCopy> epyc = parseInstructionSetTimings(text, "AMD EPYC");
    const std::vector<MeasuredCopy> other = parseInstructionSetTimings(text, "AMD EPYC 9B45");
    for (const std::vector<MeasuredCopy>* read : {&epyc, &other}) {
        ASSERT_EQ(read->size(), second.size()) << text;
        for (std::size_t k = 0; k < second.size(); ++k) {
            EXPECT_EQ((*read)[k].set, second[k].set);
            EXPECT_DOUBLE_EQ((*read)[k].msPerFrame, second[k].msPerFrame);
        }
    }
    EXPECT_TRUE(parseInstructionSetTimings(text, "AMD").empty());
}

// Catches: a damaged record (cut short, a name a later build added, a negative or unreadable time)
// taken at its word, or throwing where it should be skipped.
TEST(InstructionSetTimings, EntriesThatDoNotReadAreSkipped) {
    const std::vector<MeasuredCopy> read = parseInstructionSetTimings(
        "# "
        "comment\tavx2=1\nCPU\tavx2=13.5\tavx1024=2\tavx512=-3\tbaseline=x\tavx512=nan\tbaseline\tbaseline=3",
        "CPU");
    ASSERT_EQ(read.size(), 2u);
    EXPECT_EQ(read[0].set, Avx2);
    EXPECT_DOUBLE_EQ(read[0].msPerFrame, 13.5);
    EXPECT_EQ(read[1].set, Baseline);
    EXPECT_TRUE(parseInstructionSetTimings("# CPU\tavx2=1\n", "# CPU").empty());
}

// Catches: the record written somewhere else than $XDG_CACHE_HOME/facet/instruction-sets, or under a
// key that is not this CPU's model, so that no later run would find it.
TEST(InstructionSetTimings, TheRecordGoesUnderXdgCacheHomeKeyedByTheCpuModel) {
    const testing_support::TempFolder folder;
    const char* old = std::getenv("XDG_CACHE_HOME");
    const std::string saved = old ? old : "";
    ::setenv("XDG_CACHE_HOME", folder.path().c_str(), 1);
    const std::vector<MeasuredCopy> measured = {{Baseline, 3.0}, {Avx2, 2.0}};
    const std::filesystem::path file = recordInstructionSetTimings(measured);
    if (old)
        ::setenv("XDG_CACHE_HOME", saved.c_str(), 1);
    else
        ::unsetenv("XDG_CACHE_HOME");
    EXPECT_EQ(file, folder.path() / "facet" / "instruction-sets");
    std::ifstream in(file);
    std::ostringstream text;
    text << in.rdbuf();
    const std::string model = cpuModelName();
    EXPECT_FALSE(model.empty());
    EXPECT_NE(model.back(), ' ');
    const std::vector<MeasuredCopy> read = parseInstructionSetTimings(text.str(), model);
    ASSERT_EQ(read.size(), 2u) << text.str();
    EXPECT_EQ(read[1].set, Avx2);
}

}  // namespace
}  // namespace facet
