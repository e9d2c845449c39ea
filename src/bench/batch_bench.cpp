#include "bench/batch_bench.h"

#include <fcntl.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

#include "base/errors.h"
#include "bench/process_stats.h"

extern char** environ;

namespace facet {

namespace {

namespace fs = std::filesystem;

// The inputs a list names: its lines that are neither blank nor a # comment (as facet render --list
// reads it; the children refuse a list that is not one).
std::size_t listedInputs(const fs::path& list) {
    std::ifstream in(list);
    if (!in) throw InputError(list.string() + ": cannot read the list of inputs");
    std::size_t count = 0;
    for (std::string line; std::getline(in, line);) {
        const std::size_t first = line.find_first_not_of(" \t\r");
        if (first != std::string::npos && line[first] != '#') ++count;
    }
    if (count == 0) throw InputError(list.string() + ": the list names no input");
    return count;
}

// CPU seconds (user and system) of the children waited for so far.
double childrenCpuSeconds() {
    rusage usage{};
    getrusage(RUSAGE_CHILDREN, &usage);
    return double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
           double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) * 1e-6;
}

// Starts `words` (this program's arguments) with its standard output and error thrown away.
pid_t start(const std::vector<std::string>& words) {
    std::vector<char*> argv;
    for (const std::string& word : words)
        argv.push_back(const_cast<char*>(word.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    pid_t child = 0;
    const int started = posix_spawn(&child, "/proc/self/exe", &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (started != 0)
        throw InputError(std::string("cannot start facet render for the batch bench (") +
                         std::strerror(started) + ")");
    return child;
}

// Waits for `child`; refuses a status other than 0 (every input rendered) or 1 (some failed, as they
// fail the same both ways).
void finish(pid_t child, const std::string& way) {
    int status = 0;
    while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) > 1)
        throw InputError(way + ": facet render ended with " +
                         (WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                            : "signal " + std::to_string(WTERMSIG(status))) +
                         " (run it alone to see why)");
}

struct Timing {
    double seconds = 0, cpuSeconds = 0;
};

// One round of a way: `processes` children of `words` (with --shard I/processes when more than one)
// started at once, timed until the last ends.
Timing timeRound(std::vector<std::string> words, int processes, const std::string& way) {
    const double cpuBefore = childrenCpuSeconds();
    const auto begin = std::chrono::steady_clock::now();
    std::vector<pid_t> children;
    for (int shard = 0; shard < processes; ++shard) {
        std::vector<std::string> shardWords = words;
        if (processes > 1)
            shardWords.insert(shardWords.end(),
                              {"--shard", std::to_string(shard) + "/" + std::to_string(processes)});
        children.push_back(start(shardWords));
    }
    for (pid_t child : children)
        finish(child, way);
    Timing timing;
    timing.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    timing.cpuSeconds = childrenCpuSeconds() - cpuBefore;
    return timing;
}

std::string bytesOf(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The images of two folders: how many the first holds, and whether the second holds the same files
// with the same bytes.
bool sameImages(const fs::path& a, const fs::path& b, std::size_t& count) {
    count = 0;
    bool same = true;
    std::error_code error;
    for (const fs::directory_entry& entry : fs::directory_iterator(a, error)) {
        ++count;
        same = same && bytesOf(entry.path()) == bytesOf(b / entry.path().filename());
    }
    std::size_t other = 0;
    for ([[maybe_unused]] const fs::directory_entry& entry : fs::directory_iterator(b, error))
        ++other;
    return same && other == count;
}

// A folder of its own under the system's temporary folder, removed when done.
struct TemporaryFolder {
    fs::path path;
    TemporaryFolder() {
        std::string pattern = (fs::temp_directory_path() / "facet-bench-batch-XXXXXX").string();
        if (!mkdtemp(pattern.data()))
            throw InputError("cannot make a temporary folder for the batch bench (" +
                             std::string(std::strerror(errno)) + ")");
        path = pattern;
    }
    ~TemporaryFolder() {
        std::error_code error;
        fs::remove_all(path, error);
    }
};

}  // namespace

void runBatchBench(const BatchBenchOptions& options, std::ostream& out) {
    if (options.list == "-")
        throw InputError("--batch reads its list once per round: give a file, not standard input");
    const std::size_t inputs = listedInputs(options.list);
    const int threads = options.threads > 0
                            ? options.threads
                            : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    const TemporaryFolder folder;
    // The words both ways share; each adds its output folder, threads and (the shards) --shard.
    std::vector<std::string> common = {"facet", "render", "--list", options.list.string(), "-q"};
    if (options.width) common.insert(common.end(), {"--width", std::to_string(*options.width)});
    if (options.height) common.insert(common.end(), {"--height", std::to_string(*options.height)});
    const auto wayWords = [&](const std::string& name, int round, int wayThreads) {
        std::vector<std::string> words = common;
        words.insert(words.end(),
                     {"-o", (folder.path / (name + std::to_string(round)) / "{index}.png").string(),
                      "--threads", std::to_string(wayThreads)});
        return words;
    };
    out << "facet bench --batch: " << inputs << " inputs of " << options.list.string() << ", " << threads
        << (threads == 1 ? " thread" : " threads") << ", " << options.rounds
        << " rounds of each way taking turns (medians)\n";
    std::vector<double> oneSeconds, oneCpu, shardSeconds, shardCpu;
    bool same = true;
    std::size_t images = 0;
    for (int round = 0; round < options.rounds; ++round) {
        const Timing one = timeRound(wayWords("one", round, threads), 1, "one process");
        const Timing shards = timeRound(wayWords("shards", round, 1), threads, "the shards");
        oneSeconds.push_back(one.seconds);
        oneCpu.push_back(one.cpuSeconds);
        shardSeconds.push_back(shards.seconds);
        shardCpu.push_back(shards.cpuSeconds);
        same = sameImages(folder.path / ("one" + std::to_string(round)),
                          folder.path / ("shards" + std::to_string(round)), images) &&
               same;
        std::error_code error;
        fs::remove_all(folder.path / ("one" + std::to_string(round)), error);
        fs::remove_all(folder.path / ("shards" + std::to_string(round)), error);
    }
    const double one = median(oneSeconds), shards = median(shardSeconds);
    char line[256];
    std::snprintf(line, sizeof line, "  one process on %d threads:   %8.3f s  %8.2f inputs/s  CPU %.3f s\n",
                  threads, one, double(inputs) / one, median(oneCpu));
    out << line;
    std::snprintf(line, sizeof line, "  %d one-thread shards:         %8.3f s  %8.2f inputs/s  CPU %.3f s\n",
                  threads, shards, double(inputs) / shards, median(shardCpu));
    out << line;
    std::snprintf(line, sizeof line,
                  "  one process / shards: %.2fx the inputs per second; %zu images written, %s\n",
                  shards / one, images, same ? "the same bytes both ways" : "SOME IMAGES DIFFER");
    out << line;
    if (!same) throw std::runtime_error("the batch bench's two ways wrote different images");
}

}  // namespace facet
