// facet render with many inputs (cli/batch.h): the plan (each input's image, the list file, the shards)
// and the run (each image the bytes of a render of its own; a broken input reported, the others
// rendered). Above each test, the one-line break it catches.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "base/errors.h"
#include "cli/batch.h"
#include "cli/parse_render.h"
#include "cli/render_command.h"
#include "support/bundled_models.h"
#include "support/file_bytes.h"
#include "support/temp_folder.h"

namespace facet::cli {
namespace {

namespace fs = std::filesystem;
using testing_support::TempFolderTest;

using testing_support::kModels;

// The InputError message of `body`, which must throw one; one line.
template <class Body>
std::string refusal(const Body& body) {
    try {
        body();
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        return message;
    }
    ADD_FAILURE() << "not refused";
    return {};
}

using testing_support::fileBytes;

std::vector<std::string> outputsOf(const BatchPlan& plan) {
    std::vector<std::string> outputs;
    for (const BatchItem& item : plan.items)
        outputs.push_back(item.output);
    return outputs;
}

// Several inputs and an -o without {name} or {index}: refused before anything is loaded (the inputs do
// not exist, so a render would have failed on them instead). One input needs no placeholder. Breaks if
// planBatch's placeholder check is dropped (every input would write out/x.png in turn).
TEST(BatchPlan, SeveralInputsNeedAPlaceholderInTheOutput) {
    EXPECT_EQ(refusal([] {
                  planBatch({"a.obj", "b.obj"}, "out/x.png", {}, false);
              }),
              "-o out/x.png names one image for 2 inputs: put {name} (the input's file name) or {index} (its "
              "place in the list) in it, like -o out/{name}.png");
    EXPECT_EQ(refusal([] {
                  render(parseRender({"no/a.obj", "no/b.obj", "-o", "out/x.png"}));
              }),
              "-o out/x.png names one image for 2 inputs: put {name} (the input's file name) or {index} (its "
              "place in the list) in it, like -o out/{name}.png");
    EXPECT_EQ(outputsOf(planBatch({"a.obj"}, "out/x.png", {}, false)), std::vector<std::string>{"out/x.png"});
    EXPECT_EQ(outputsOf(planBatch({"a.obj", "b.obj"}, "out/{index}.png", {}, false)),
              (std::vector<std::string>{"out/0.png", "out/1.png"}));
}

// {name} is the file name without its extension (and its folders), {index} the place in the whole
// list from 0; every occurrence is replaced. Breaks if {name} takes filename() ("spot.obj.png") or only
// the first occurrence is replaced.
TEST(BatchPlan, NameIsTheFileStemAndIndexThePlaceInTheList) {
    EXPECT_EQ(expandOutput("out/{name}.png", "models/spot/spot_triangulated.obj", 3),
              "out/spot_triangulated.png");
    EXPECT_EQ(expandOutput("out/{index}-{name}/{name}.exr", "scenes/a.b.json", 12), "out/12-a.b/a.b.exr");
    EXPECT_EQ(expandOutput("out/{nam}{index}.png", "x.obj", 7), "out/{nam}7.png");
    EXPECT_EQ(outputsOf(planBatch({"m/a.obj", "b.json", "c"}, "out/{index}-{name}.png", {}, false)),
              (std::vector<std::string>{"out/0-a.png", "out/1-b.png", "out/2-c.png"}));
}

// Two inputs whose images would have one path are refused before rendering, naming both and the
// path; paths are compared as the file system sees them (out/a/../x.png is out/x.png), the terms'
// images of --components count, and the whole list is checked, not only this shard's inputs. Breaks if
// the check compares the strings as written, leaves out the components' paths, or runs over the shard's
// items only.
TEST(BatchPlan, TwoInputsWritingOneImageAreRefused) {
    EXPECT_EQ(
        refusal([] {
            planBatch({"a/spot.obj", "b/cow.obj", "c/spot.obj"}, "out/{name}.png", {}, false);
        }),
        "-o out/{name}.png: a/spot.obj and c/spot.obj (inputs 0 and 2, counted from 0) would both write "
        "out/spot.png; "
        "add {index}, like -o out/{name}-{index}.png");
    EXPECT_NO_THROW(planBatch({"a/spot.obj", "c/spot.obj"}, "out/{name}-{index}.png", {}, false));
    EXPECT_EQ(
        refusal([] {
            planBatch({"x.obj", "y.obj", "x.obj"}, "out/{name}.png", {}, false);
        }),
        "-o out/{name}.png: x.obj is in the list twice (inputs 0 and 2, counted from 0): both would write "
        "out/x.png; add {index}, like -o out/{name}-{index}.png");
    EXPECT_NE(refusal([] {
                  planBatch({"a.obj", "b.obj"}, "out/{name}/../same.png", {}, false);
              }).find("would both write out/b/../same.png"),
              std::string::npos);
    EXPECT_NO_THROW(planBatch({"spot.obj", "spot-diffuse.obj"}, "out/{name}.png", {}, false));
    EXPECT_NE(refusal([] {
                  planBatch({"spot.obj", "spot-diffuse.obj"}, "out/{name}.png", {}, true);
              }).find("would both write out/spot-diffuse.png"),
              std::string::npos);
    // Shard 1/2 renders only b.obj, yet refuses the clash of inputs 0 and 2.
    EXPECT_THROW(planBatch({"a/x.obj", "b.obj", "c/x.obj"}, "out/{name}.png", Shard{1, 2}, false),
                 InputError);
}

// For lists of 0 to 7 inputs and 1 to 9 shards (more shards than inputs too): every input is in
// exactly one shard, shard I holds the inputs whose index is I modulo N, in list order, with the images
// the whole plan gives them. Breaks if planBatch's shard test is changed (index / N, <=, a shard
// counted from 1) or shards take contiguous ranges of the list.
TEST(BatchPlan, ShardsPartitionTheListByIndexModuloN) {
    for (std::size_t size = 0; size <= 7; ++size) {
        std::vector<std::string> inputs;
        for (std::size_t k = 0; k < size; ++k)
            inputs.push_back("models/m" + std::to_string(k) + ".obj");
        const BatchPlan whole = planBatch(inputs, "out/{name}.png", {}, false);
        ASSERT_EQ(whole.items.size(), size);
        for (int count = 1; count <= 9; ++count) {
            SCOPED_TRACE(std::to_string(size) + " inputs, " + std::to_string(count) + " shards");
            std::vector<int> seen(size, 0);
            for (int index = 0; index < count; ++index) {
                const BatchPlan shard = planBatch(inputs, "out/{name}.png", Shard{index, count}, false);
                EXPECT_EQ(shard.listSize, size);
                for (std::size_t k = 0; k < shard.items.size(); ++k) {
                    const BatchItem& item = shard.items[k];
                    ASSERT_LT(item.index, size);
                    ++seen[item.index];
                    EXPECT_EQ(item.index % static_cast<std::size_t>(count), static_cast<std::size_t>(index));
                    EXPECT_EQ(item.index,
                              static_cast<std::size_t>(index) +
                                  k * static_cast<std::size_t>(count));  // in list order, none skipped
                    EXPECT_EQ(item.input, inputs[item.index]);
                    EXPECT_EQ(item.output, whole.items[item.index].output);
                }
            }
            EXPECT_EQ(seen, std::vector<int>(size, 1));
        }
    }
}

// I/N with 0 <= I < N is taken; anything else is refused with the same one line, quoting the text.
// Breaks if the bound becomes I <= N (a shard N/N that renders nothing), N = 0 is let through (a
// division by zero), or trailing text is ignored.
TEST(BatchPlan, ShardIsIOverNAndNothingElse) {
    for (const auto& [text, index, count] :
         {std::tuple{"0/1", 0, 1}, std::tuple{"3/4", 3, 4}, std::tuple{"99/100", 99, 100}}) {
        const Shard shard = parseShard(text);
        EXPECT_EQ(shard.index, index) << text;
        EXPECT_EQ(shard.count, count) << text;
    }
    for (const std::string text : {"4/4", "5/4", "-1/4", "1/0", "0/0", "a/4", "1/4x", "1 /4", "/4", "1/", "",
                                   "1", "+1/4", "1/-4", "1/4/2", "99999999999/4"})
        EXPECT_EQ(refusal([&] { parseShard(text); }),
                  "--shard expects I/N, two whole numbers with 0 <= I < N, like 0/4 (got \"" + text + "\")");
}

class InputList : public TempFolderTest {};

// Comments, blank lines, spaces and CR line ends are skipped; a relative path is taken from the list's
// folder, an absolute one as it is; a # inside a path is part of it. Breaks if relative paths are left
// relative to the working folder, comments or blank lines become inputs, or the line is not trimmed.
TEST_F(InputList, SkipsCommentsAndBlankLinesAndReadsPathsFromTheListsFolder) {
    const fs::path list = write("lists/batch.txt",
                                "# models for the catalogue\n"
                                "models/a.obj\n"
                                "\n"
                                "   # an indented comment\n"
                                "  models/b.json \t\n"
                                "/abs/c.obj\r\n"
                                "../up/d.obj\n"
                                "with#hash.obj\n"
                                "   \n");
    const fs::path folder = folder_ / "lists";
    EXPECT_EQ(readInputList(list),
              (std::vector<std::string>{
                  (folder / "models/a.obj").string(), (folder / "models/b.json").string(), "/abs/c.obj",
                  (folder / "../up/d.obj").string(), (folder / "with#hash.obj").string()}));
}

// A list that cannot be read, names nothing or is not text is refused, naming it (and the line), and a
// line is bounded before it is stored (/dev/zero). Breaks if a missing list is taken as empty, an empty
// list renders nothing and succeeds, or the NUL and length checks wait for the end of the line.
TEST_F(InputList, AMissingEmptyOrBinaryListIsRefusedWithItsName) {
    const fs::path missing = folder_ / "missing.txt";
    EXPECT_EQ(refusal([&] { readInputList(missing); }),
              missing.string() + ": cannot read the list of inputs (No such file or directory)");
    EXPECT_EQ(refusal([&] { readInputList(folder_); }),
              folder_.string() + ": cannot read the list of inputs (is a folder)");
    const fs::path empty = write("empty.txt", "# nothing yet\n\n");
    EXPECT_EQ(refusal([&] { readInputList(empty); }),
              empty.string() + ": the list names no input (one path a line; # starts a comment)");
    const fs::path binary = write("binary.txt", std::string("a.obj\nb\0c.obj\n", 13));
    EXPECT_EQ(refusal([&] { readInputList(binary); }),
              binary.string() + ":2: a NUL byte: the list must be a text file, one path a line");
    EXPECT_EQ(refusal([&] { readInputList("/dev/zero"); }),
              "/dev/zero:1: a NUL byte: the list must be a text file, one path a line");
    const fs::path longLine = write("long.txt", "a.obj\n" + std::string(5000, 'x') + "\n");
    EXPECT_EQ(refusal([&] { readInputList(longLine); }),
              longLine.string() + ":2: a line longer than 4096 characters (a path is at most that)");
}

// A list read from a pipe (--list <(find …)) has no folder: its relative paths stay as written, the
// working folder's. Breaks if the pipe's folder (/dev/fd, here the temporary folder) is put in front.
TEST_F(InputList, APipesRelativePathsAreTheWorkingFolders) {
    const fs::path fifo = folder_ / "list.fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::thread writer([&] { std::ofstream(fifo) << "models/a.obj\n/abs/b.obj\n"; });
    const std::vector<std::string> inputs = readInputList(fifo);
    writer.join();
    EXPECT_EQ(inputs, (std::vector<std::string>{"models/a.obj", "/abs/b.obj"}));
}

// The command line's inputs come first, then the list's, and {index} counts over both; --frames is for
// one input. Breaks if the list's inputs are put first, or --frames is let into a batch.
TEST_F(InputList, TheCommandLinesInputsComeBeforeTheLists) {
    const fs::path list = write("list.txt", "b.obj\nc.obj\n");
    const BatchPlan plan =
        planBatch(parseRender({"a.obj", "--list", list.string(), "-o", "out/{index}-{name}.png"}));
    EXPECT_EQ(plan.listSize, 3u);
    EXPECT_EQ(outputsOf(plan), (std::vector<std::string>{"out/0-a.png", "out/1-b.png", "out/2-c.png"}));
    EXPECT_EQ(plan.items[2].input, (folder_ / "c.obj").string());
    EXPECT_EQ(
        refusal([&] {
            planBatch(parseRender({"--list", list.string(), "-o", "out/{name}.png", "--frames", "0-9"}));
        }),
        "--frames renders the turntable of one input, not of a batch of 2: run one facet render --frames "
        "per input");
    EXPECT_NO_THROW(
        planBatch(parseRender({"a.obj", "--shard", "0/1", "-o", "out/{name}.png", "--frames", "0-9"})));
}

class BatchRun : public TempFolderTest {
  protected:
    // Two bundled models and a bundled scene, at a small size.
    const std::vector<std::string> inputs_ = {(kModels / "spot/spot_triangulated.obj").string(),
                                              (kModels / "cube/cube.obj").string(),
                                              (kModels / "example-scene.json").string()};
    const std::vector<std::string> size_ = {"--width", "64", "--height", "48"};

    RenderArgs batchArgs(std::vector<std::string> inputs, const std::string& output,
                         std::vector<std::string> options) const {
        inputs.insert(inputs.end(), {"-o", output});
        inputs.insert(inputs.end(), options.begin(), options.end());
        inputs.insert(inputs.end(), size_.begin(), size_.end());
        return parseRender(inputs);
    }
};

// Every image of a batch (on 3 threads) is the same bytes as the input rendered alone (on 1): the
// batch draws each input with its own scene, framebuffer and frame memory, only the threads are
// shared. Breaks if an item is rendered with the batch's first input or without the command line's
// options (the image size), or if a frame's state leaks from one input into the next.
TEST_F(BatchRun, EachImageIsTheBytesOfTheInputRenderedAlone) {
    ASSERT_EQ(render(batchArgs(inputs_, (folder_ / "batch/{name}.png").string(), {"--threads", "3", "-q"})),
              0);
    for (const std::string& input : inputs_) {
        const std::string name = fs::path(input).stem().string();
        const fs::path alone = folder_ / "alone" / (name + ".png");
        ASSERT_EQ(render(batchArgs({input}, alone.string(), {"--threads", "1", "-q"})), 0);
        const std::string bytes = fileBytes(alone);
        EXPECT_GT(bytes.size(), 100u) << name;
        EXPECT_TRUE(fileBytes(folder_ / "batch" / (name + ".png")) == bytes) << name;
    }
}

// A broken model in the middle: the inputs before and after it are rendered, the batch returns 1 and
// its summary names the file and line of the fault, as a single render prints it; no image is left for
// it. Breaks if an exception escapes the loop (the third input is never rendered), the status ignores
// the failures, or the failure's message is lost.
TEST_F(BatchRun, ABrokenModelIsReportedAndTheOthersRendered) {
    const fs::path broken = write("broken/broken.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n");
    const std::vector<std::string> inputs = {inputs_[0], broken.string(), inputs_[1]};
    const RenderArgs args = batchArgs(inputs, (folder_ / "out/{name}.png").string(), {"--threads", "2"});
    std::ostringstream out, err;
    const BatchResult result = runBatch(args, planBatch(args), BatchConsole{out, err});
    EXPECT_EQ(result.rendered, 2u);
    ASSERT_EQ(result.failures.size(), 1u);
    EXPECT_EQ(result.failures[0].input, broken.string());
    const std::string message = result.failures[0].message;
    EXPECT_EQ(message.rfind("facet: error: " + broken.string() + ":3: ", 0), 0u) << message;
    EXPECT_NE(err.str().find("facet: rendered 2 of 3 inputs in "), std::string::npos) << err.str();
    EXPECT_NE(err.str().find("; 1 failed:\n" + message + "\n"), std::string::npos) << err.str();
    EXPECT_TRUE(fs::exists(folder_ / "out/spot_triangulated.png"));
    EXPECT_TRUE(fs::exists(folder_ / "out/cube.png"));
    EXPECT_FALSE(fs::exists(folder_ / "out/broken.png"));
    // The program's status.
    fs::remove_all(folder_ / "out");
    EXPECT_EQ(render(batchArgs(inputs, (folder_ / "out/{name}.png").string(), {"-q"})), 1);
    EXPECT_TRUE(fs::exists(folder_ / "out/cube.png"));
}

// On a terminal the progress line is rewritten in place (a carriage return, never wider than the
// terminal) and erased at the end; in a log nothing of it is written. --quiet leaves only failures.
// Breaks if ProgressLine writes without a terminal, the path is not cut to the width, or --quiet is
// ignored.
TEST_F(BatchRun, AProgressLineOnlyOnATerminal) {
    const std::vector<std::string> inputs = {inputs_[1], (kModels / "shared-edge.json").string()};
    const RenderArgs args = batchArgs(inputs, (folder_ / "out/{name}.png").string(), {});
    {
        std::ostringstream out, err;
        runBatch(args, planBatch(args), BatchConsole{out, err});
        EXPECT_EQ(err.str(), "");
        EXPECT_EQ(out.str().rfind(
                      "facet: wrote " + (folder_ / "out/cube.png").string() + " (64x48, 12 triangles, ", 0),
                  0u)
            << out.str();
        EXPECT_NE(out.str().find("\nfacet: rendered 2 of 2 inputs in "), std::string::npos) << out.str();
    }
    {
        std::ostringstream out, err;
        runBatch(args, planBatch(args), BatchConsole{out, err, true, 40});
        const std::string text = err.str();
        EXPECT_EQ(text.rfind("\r[1/2] rendering ...", 0), 0u) << text;
        EXPECT_NE(text.find("\r[2/2] rendering ...els/shared-edge.json"), std::string::npos) << text;
        std::istringstream lines(text);
        for (std::string line; std::getline(lines, line, '\r');)
            EXPECT_LE(line.size(), 39u) << line;
        EXPECT_EQ(text.back(), '\r');  // erased: blanks, back to the line's start
        EXPECT_EQ(text.substr(text.rfind("\r", text.size() - 2) + 1).find_first_not_of(" \r"),
                  std::string::npos);
    }
    {
        std::ostringstream out, err;
        RenderArgs quiet = args;
        quiet.quiet = true;
        runBatch(quiet, planBatch(quiet), BatchConsole{out, err});
        EXPECT_EQ(out.str(), "");
        EXPECT_EQ(err.str(), "");
    }
}

}  // namespace
}  // namespace facet::cli
