// facet render over many inputs in one process (docs/batch.md). First the plan: the inputs of the
// command line and of --list, each one's image named by -o's {name} and {index}, and the share of them
// this process renders (--shard). Then the run: several inputs in flight at once, each on its own share
// of the threads, loaded, prepared, rendered and written on its own (as many as the memory limit lets
// in); their messages in list order; an input that fails is reported at the end and the others rendered.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "cli/options.h"

namespace facet {
struct Scene;
}

namespace facet::cli {

// --shard I/N: this process renders the inputs whose index in the whole list is I modulo N, so that N
// processes started with I = 0 … N−1 render every input exactly once, whatever their timing.
struct Shard {
    int index = 0;  // I, from 0 to count − 1
    int count = 1;  // N
};

// "I/N", two whole numbers with 0 ≤ I < N; throws InputError quoting the text otherwise.
Shard parseShard(const std::string& text);

// The most a list of inputs (--list) may hold, so that an endless one (yes model.obj | facet render
// --list -) ends with a message instead of filling the memory: inputs, and bytes read.
constexpr std::size_t kMostListedInputs = 1'000'000;
constexpr std::size_t kMostListBytes = std::size_t{256} << 20;

// The inputs a list file names, in order: one path a line, spaces and tabs around it (and the CR of
// Windows line ends) trimmed; blank lines and lines starting with # are skipped. A relative path is taken
// from the list's folder, so that a list and its models can move together (from the working folder
// when the list is a pipe; "-" is standard input). Throws InputError when the file cannot be read, holds a
// NUL byte (not a text file) or a line longer than a path can be, or names no input.
std::vector<std::string> readInputList(const std::filesystem::path& list);

// Does `output` hold {name} or {index}?
bool hasPlaceholder(std::string_view output);

// `output` with every {name} replaced by the input's file name without its extension
// ("models/spot/spot.obj" → "spot") and every {index} by `index` in decimal.
std::string expandOutput(std::string_view output, const std::string& input, std::size_t index);

// One input of a batch and its image.
struct BatchItem {
    std::size_t index = 0;  // in the whole list, from 0
    std::string input;
    std::string output;  // -o expanded
};

struct BatchPlan {
    std::size_t listSize = 0;  // inputs in the whole list, every shard's
    Shard shard;
    std::vector<BatchItem> items;  // this shard's, in list order
};

// The items of `inputs` (the whole list) that `shard` renders, with their images. Checked on the whole
// list, so that every shard refuses the same mistakes before anything is rendered: several inputs need
// {name} or {index} in `output`, and no two images (with `components`, the terms' images too) may have
// the same path. Throws InputError.
BatchPlan planBatch(const std::vector<std::string>& inputs, const std::string& output, Shard shard,
                    bool components);

// Is this command line a batch: several inputs, --list or --shard? One input without them is rendered as
// always (its -o may still hold {name} and {index}).
bool isBatch(const RenderArgs& args);

// The batch of a command line: every check of renderSettings, the inputs (the command line's, then
// --list's), --frames refused for more than one input (a turntable's frames are numbered images of one
// input), then planBatch. Throws InputError.
BatchPlan planBatch(const RenderArgs& args);

// An input that failed, and its one-line message as facet prints it: "facet: error: models/x.obj:12: …".
struct BatchFailure {
    std::string input;
    std::string message;
};

struct BatchResult {
    std::size_t rendered = 0;
    std::vector<BatchFailure> failures;  // in list order
    double seconds = 0;                  // the whole run, loading included
};

// Where a batch reports. On a terminal (`terminal`: `err` is one, `columns` wide) a progress line,
// "[12/100] rendering models/x.obj", is rewritten in place and erased at the end; elsewhere (a log
// file) nothing of it is written.
struct BatchConsole {
    std::ostream& out;
    std::ostream& err;
    bool terminal = false;
    int columns = 80;
};

// How a batch shares its threads: one lane per input in flight, each drawing with its own DrawContext
// (thread pool) of threads[lane] threads. An input alone on one thread has no job to hand out, wake up
// or wait for (docs/batch.md measures it): as many lanes as threads, one thread each, while the list has
// at least as many inputs; a shorter list gets one lane per input and the threads shared out among
// them. The threads of all lanes add up to the batch's.
struct BatchLanes {
    std::vector<int> threads;  // one entry per lane, each at least 1
};
// `threads` ≤ 0: one per hardware thread (as ThreadPool); `items`: the inputs to render.
BatchLanes planLanes(int threads, std::size_t items);

// The memory an input in flight is counted for, from what is known before its models are read: its
// image's buffers (frameImageBytes, the estimate a render checks against the limit) and
// kModelBytesPerFileByte per byte of its model files (the text read, the mesh built from it and the
// prepared copy of its triangles).
constexpr std::uint64_t kModelBytesPerFileByte = 4;
std::uint64_t inputMemoryEstimate(const facet::Scene& scene);

// The inputs in flight count together against the memory limit: an input is let in while the
// estimates of those in flight and its own stay within the limit, or when nothing else is in flight
// (then it meets the usual checks against the whole limit, exactly as rendered alone). Waits otherwise.
class MemoryGate {
  public:
    explicit MemoryGate(std::uint64_t limit) : limit_(limit) {}
    void enter(std::uint64_t bytes);
    void leave(std::uint64_t bytes);

  private:
    std::mutex mutex_;
    std::condition_variable changed_;
    std::uint64_t limit_;
    std::uint64_t held_ = 0;  // the estimates of the inputs in flight
    int inFlight_ = 0;
};

// Renders the items of `plan`, each with `args`' options, several at once (planLanes; the memory limit
// counting the inputs in flight together, MemoryGate): each image is the same bytes as `facet render
// INPUT -o IMAGE` with those options, whatever the threads. An input that fails (InputError, out of
// memory, any exception) is skipped and reported. Each input's messages are held until those of the
// inputs before it are printed, so the output is in list order, as when rendered one after another:
// its warnings, then "facet: wrote …" (not with --quiet); then the summary: "facet: rendered N of M
// inputs in T s (R models per second)" to `out` (not with --quiet), or, when an input failed, to `err`
// followed by every failure's message. Throws InputError only for a bad command line, before rendering.
BatchResult runBatch(const RenderArgs& args, const BatchPlan& plan, const BatchConsole& console);

// facet render with a batch: planned, run on standard output and error; 0 when every input was rendered,
// else 1.
int renderBatch(const RenderArgs& args);

}  // namespace facet::cli
