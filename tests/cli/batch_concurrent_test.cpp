// A batch with several inputs in flight at once (cli/batch.h): how the threads are shared out, the
// memory limit counting the inputs in flight together, every image the bytes of a render of its own,
// and the messages in list order whatever order the inputs finish in. Above each test, the break it
// catches.
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "cli/batch.h"
#include "cli/parse_render.h"
#include "cli/render_command.h"
#include "render/memory_estimate.h"
#include "scene/scene.h"
#include "support/bundled_models.h"
#include "support/file_bytes.h"
#include "support/temp_folder.h"

namespace facet::cli {
namespace {

namespace fs = std::filesystem;
using testing_support::TempFolderTest;

using testing_support::kModels;

using testing_support::fileBytes;

// Catches: lanes whose threads add up to more or fewer than the batch was given (a machine
// oversubscribed, or cores left idle), a lane with no thread, or more lanes than inputs.
TEST(BatchLanes, TheLanesShareOutExactlyTheBatchsThreads) {
    for (int threads : {1, 2, 3, 5, 16})
        for (std::size_t items : {std::size_t{1}, std::size_t{2}, std::size_t{3}, std::size_t{64}}) {
            const BatchLanes lanes = planLanes(threads, items);
            EXPECT_EQ(lanes.threads.size(), std::min<std::size_t>(std::size_t(threads), items))
                << threads << " threads, " << items << " items";
            EXPECT_EQ(std::accumulate(lanes.threads.begin(), lanes.threads.end(), 0), threads);
            for (int laneThreads : lanes.threads)
                EXPECT_GE(laneThreads, 1);
        }
    EXPECT_EQ(planLanes(5, 2).threads, (std::vector<int>{3, 2}));
    EXPECT_EQ(planLanes(0, 1000).threads.size(),
              std::size_t(std::max(1u, std::thread::hardware_concurrency())));
}

// Catches: a second input let in while the first holds memory that, with its own, passes the limit;
// or an input larger than the whole limit waiting forever instead of going alone (to meet the render's
// own refusal).
TEST(BatchMemoryGate, InputsInFlightCountTogetherAgainstTheLimit) {
    MemoryGate gate(100);
    gate.enter(1000);  // alone: let in, whatever its size
    gate.leave(1000);
    gate.enter(60);
    std::atomic<bool> entered{false};
    std::thread second([&] {
        gate.enter(60);
        entered = true;
        gate.leave(60);
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    EXPECT_FALSE(entered) << "60 + 60 bytes in flight under a limit of 100";
    gate.leave(60);
    second.join();
    EXPECT_TRUE(entered);
    gate.enter(40);
    gate.enter(60);  // 100 fits exactly: does not wait
    gate.leave(40);
    gate.leave(60);
}

// Catches: an estimate that leaves out the image's buffers (the render's own check) or the models.
TEST(BatchMemoryGate, AnInputIsCountedForItsImageAndItsModels) {
    RenderArgs args = parseRender({(kModels / "spot/spot_triangulated.obj").string(), "-o", "x.png"});
    args.input = args.inputs.front();
    const Scene scene = inputScene(args);
    const std::uint64_t estimate = inputMemoryEstimate(scene);
    EXPECT_EQ(estimate, frameImageBytes(scene) +
                            kModelBytesPerFileByte * fs::file_size(kModels / "spot/spot_triangulated.obj"));
}

class BatchConcurrent : public TempFolderTest {
  protected:
    // Bundled models and scenes of different sizes, so that inputs in flight finish out of list order.
    const std::vector<std::string> inputs_ = {
        (kModels / "spot/spot_triangulated.obj").string(), (kModels / "cube/cube.obj").string(),
        (kModels / "example-scene.json").string(),         (kModels / "sphere/sphere.obj").string(),
        (kModels / "fog-and-glass.json").string(),         (kModels / "shared-edge.json").string()};

    RenderArgs args(std::vector<std::string> inputs, const fs::path& output,
                    std::vector<std::string> options) const {
        inputs.insert(inputs.end(), {"-o", output.string(), "--width", "96", "--height", "72"});
        inputs.insert(inputs.end(), options.begin(), options.end());
        return parseRender(inputs);
    }
};

// Catches: an image of a batch on 2 threads (two inputs in flight, one thread each) that differs from
// the input rendered alone, by one process on one thread: state shared between lanes, an input drawn
// with another's scene or options.
TEST_F(BatchConcurrent, EveryImageIsTheBytesOfTheInputRenderedAlone) {
    std::ofstream(folder_ / "list.txt") << [&] {
        std::string text;
        for (const std::string& input : inputs_)
            text += input + "\n";
        return text;
    }();
    ASSERT_EQ(render(args({}, folder_ / "batch/{index}-{name}.png",
                          {"--list", (folder_ / "list.txt").string(), "--threads", "2", "-q"})),
              0);
    for (std::size_t k = 0; k < inputs_.size(); ++k) {
        const std::string name = std::to_string(k) + "-" + fs::path(inputs_[k]).stem().string() + ".png";
        ASSERT_EQ(render(args({inputs_[k]}, folder_ / "alone" / name, {"--threads", "1", "-q"})), 0);
        const std::string alone = fileBytes(folder_ / "alone" / name);
        EXPECT_GT(alone.size(), 100u) << name;
        EXPECT_TRUE(fileBytes(folder_ / "batch" / name) == alone) << name;
    }
}

// Catches: messages printed in the order the inputs finish instead of the list's (a small model after a
// large one finishes first), a failure listed out of order, or an input's lines split from each other.
TEST_F(BatchConcurrent, MessagesComeInListOrderWhateverFinishesFirst) {
    const fs::path broken = write("broken.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n");
    const fs::path missing = folder_ / "missing.obj";
    std::vector<std::string> inputs = inputs_;
    inputs.insert(inputs.begin() + 1, broken.string());
    inputs.push_back(missing.string());
    const RenderArgs batch = args(inputs, folder_ / "out/{name}.png", {"--threads", "3", "--stats"});
    std::ostringstream out, err;
    const BatchResult result = runBatch(batch, planBatch(batch), BatchConsole{out, err});
    EXPECT_EQ(result.rendered, inputs_.size());
    ASSERT_EQ(result.failures.size(), 2u);
    EXPECT_EQ(result.failures[0].input, broken.string());
    EXPECT_EQ(result.failures[1].input, missing.string());
    // Each input's "frame 0:" stats line, then its "facet: wrote" line, input after input.
    std::istringstream lines(out.str());
    std::vector<std::string> wrote;
    std::string line, previous;
    while (std::getline(lines, line)) {
        if (line.rfind("facet: wrote ", 0) == 0) {
            wrote.push_back(line);
            EXPECT_EQ(previous.rfind("frame 0: ", 0), 0u) << line;
        }
        previous = line;
    }
    ASSERT_EQ(wrote.size(), inputs_.size()) << out.str();
    for (std::size_t k = 0; k < inputs_.size(); ++k) {
        const std::string image =
            (folder_ / "out" / (fs::path(inputs_[k]).stem().string() + ".png")).string();
        EXPECT_EQ(wrote[k].rfind("facet: wrote " + image + " (", 0), 0u) << wrote[k];
    }
    EXPECT_NE(
        err.str().find("; 2 failed:\n" + result.failures[0].message + "\n" + result.failures[1].message),
        std::string::npos)
        << err.str();
}

}  // namespace
}  // namespace facet::cli
