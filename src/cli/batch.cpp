#include "cli/batch.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <iostream>
#include <new>
#include <numeric>
#include <sstream>
#include <system_error>
#include <thread>
#include <unordered_map>

#include "base/errors.h"
#include "base/memory_limit.h"
#include "base/quote.h"
#include "cli/render_command.h"
#include "io/output_path.h"
#include "pipeline/thread_pool.h"
#include "render/memory_estimate.h"
#include "scene/scene.h"

namespace facet::cli {

namespace {

constexpr std::size_t kMaxPathCharacters = 4096;  // PATH_MAX

// A path as messages and the progress line show it: whole, but with control characters escaped.
std::string shown(std::string_view path) {
    return facet::printable(path, kMaxPathCharacters);
}

// The text of `line` without the spaces and tabs around it (and the CR of a Windows line end).
std::string_view trimmed(std::string_view line) {
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return {};
    return line.substr(first, line.find_last_not_of(" \t\r") - first + 1);
}

// A whole number from 0 to INT_MAX, digits only (no sign, no spaces).
bool parseCount(std::string_view text, int& value) {
    const char* end = text.data() + text.size();
    const auto [stop, error] = std::from_chars(text.data(), end, value);
    return !text.empty() && text.front() != '-' && error == std::errc() && stop == end;
}

// The one-line message of the exception being handled, as facet prints an error: the input named first
// (the loaders' messages already start with it, "models/x.obj:12: …"; others get it put in front).
std::string failureMessage(const std::string& input) {
    const auto naming = [&input](std::string_view what) {
        std::string message = shown(input);
        if (what.substr(0, input.size()) == input && what.substr(input.size(), 1) == ":")
            return std::string(what);
        message += ": ";
        message += what;
        return message;
    };
    try {
        throw;
    } catch (const facet::InputError& e) {
        return "facet: error: " + naming(e.what());
    } catch (const facet::ResourceError& e) {
        return "facet: error: " + naming(e.what());
    } catch (const std::bad_alloc&) {
        return "facet: error: " + naming(facet::outOfMemoryMessage());
    } catch (const std::exception& e) {
        return "facet: internal error: " + naming(e.what());
    } catch (...) {
        return "facet: internal error: " + naming("an exception that is not a std::exception");
    }
}

// The progress line of a terminal, rewritten in place with a carriage return; spaces (no escape
// sequences, which a dumb terminal would show) erase what a longer line before it left.
class ProgressLine {
  public:
    explicit ProgressLine(const BatchConsole& console) : console_(console) {}
    ~ProgressLine() { clear(); }

    // "[12/100] rendering models/x.obj", the path's start cut to fit the terminal's width.
    void show(std::size_t position, std::size_t count, const std::string& input) {
        if (!console_.terminal) return;
        std::string line = "[" + std::to_string(position) + "/" + std::to_string(count) + "] rendering ";
        std::string path = shown(input);
        const std::size_t width = static_cast<std::size_t>(std::max(console_.columns - 1, 20));
        if (line.size() + path.size() > width) {
            const std::size_t keep = width > line.size() + 3 ? width - line.size() - 3 : 0;
            path = "..." + path.substr(path.size() - std::min(keep, path.size()));
        }
        line += path;
        write(line);
    }

    // Erases the line, before anything else is printed (and at the end).
    void clear() {
        if (shownLength_ == 0) return;
        console_.err << '\r' << std::string(shownLength_, ' ') << '\r' << std::flush;
        shownLength_ = 0;
    }

  private:
    void write(const std::string& line) {
        console_.err << '\r' << line;
        if (line.size() < shownLength_) console_.err << std::string(shownLength_ - line.size(), ' ');
        console_.err << std::flush;
        shownLength_ = std::max(shownLength_, line.size());
    }

    const BatchConsole& console_;
    std::size_t shownLength_ = 0;  // characters the line covers now
};

// "facet: wrote out/spot.png (64x48, 5856 triangles, 12 ms)": one short line per input.
std::string wroteLine(const RenderedInput& rendered) {
    std::ostringstream line;
    line << "facet: wrote " << rendered.written.front().string();
    if (rendered.written.size() > 1) line << " and " << rendered.written.size() - 1 << " more images";
    line << " (" << rendered.width << "x" << rendered.height << ", " << rendered.triangles << " triangles, "
         << static_cast<long>(rendered.milliseconds + 0.5) << " ms)\n";
    return line.str();
}

}  // namespace

Shard parseShard(const std::string& text) {
    const std::size_t slash = text.find('/');
    Shard shard;
    const std::string_view view = text;
    if (slash == std::string::npos || !parseCount(view.substr(0, slash), shard.index) ||
        !parseCount(view.substr(slash + 1), shard.count) || shard.count < 1 || shard.index >= shard.count)
        throw facet::InputError("--shard expects I/N, two whole numbers with 0 <= I < N, like 0/4 (got " +
                                facet::inQuotes(text) + ")");
    return shard;
}

std::vector<std::string> readInputList(const std::filesystem::path& list) {
    // A file, a pipe (--list <(find …)), "-" (standard input) or a FIFO, which may wait for its writer
    // (openInputStream says so, and gives up after a while): never forever.
    const int fd = facet::openInputStream(shown(list.string()), "the list of inputs");
    struct FdCloser {
        int fd;
        ~FdCloser() {
            if (fd != STDIN_FILENO) ::close(fd);
        }
    } closer{fd};
    const std::string name = list == "-" ? "standard input (--list -)" : shown(list.string());
    const auto cannotRead = [&](int error) {
        throw facet::InputError(name + ": cannot read the list of inputs (" + std::strerror(error) + ")");
    };
    // Read a character at a time, so that a line is bounded before it is stored: a list may be a pipe,
    // and one from /dev/zero must stop at its first byte, not fill the memory. An endless one (yes x |)
    // stops at kMostListedInputs inputs or kMostListBytes bytes.
    // A pipe has no folder of its own: its relative paths are the working folder's.
    std::error_code error;
    const std::filesystem::path folder = list != "-" && std::filesystem::is_regular_file(list, error)
                                             ? list.parent_path()
                                             : std::filesystem::path();
    std::vector<std::string> inputs;
    std::string line;
    char buffer[1 << 16];
    std::size_t bufferSize = 0, bufferAt = 0, bytesRead = 0;
    constexpr int kEnd = -1;
    const auto next = [&]() -> int {
        if (bufferAt == bufferSize) {
            ssize_t count;
            while ((count = ::read(fd, buffer, sizeof buffer)) < 0 && errno == EINTR) {
            }
            if (count < 0) cannotRead(errno);
            if (count == 0) return kEnd;
            bytesRead += static_cast<std::size_t>(count);
            if (bytesRead > kMostListBytes)
                throw facet::InputError(name + ": the list of inputs is longer than " +
                                        std::to_string(kMostListBytes >> 20) +
                                        " MiB (split it, or give it in shards with --shard)");
            bufferSize = static_cast<std::size_t>(count);
            bufferAt = 0;
        }
        return static_cast<unsigned char>(buffer[bufferAt++]);
    };
    for (int number = 1, c = 0; c != kEnd; ++number) {
        const auto where = [&] { return name + ":" + std::to_string(number) + ": "; };
        line.clear();
        while ((c = next()) != kEnd && c != '\n') {
            if (c == '\0')
                throw facet::InputError(where() +
                                        "a NUL byte: the list must be a text file, one path a line");
            if (line.size() == kMaxPathCharacters)
                throw facet::InputError(where() + "a line longer than " + std::to_string(kMaxPathCharacters) +
                                        " characters (a path is at most that)");
            line += static_cast<char>(c);
        }
        const std::string_view path = trimmed(line);
        if (path.empty() || path.front() == '#') continue;
        if (inputs.size() == kMostListedInputs)
            throw facet::InputError(where() + "the list names more than " +
                                    std::to_string(kMostListedInputs) +
                                    " inputs (split it, or give it in shards with --shard)");
        const std::filesystem::path input(path);
        inputs.push_back(input.is_absolute() ? input.string() : (folder / input).string());
    }
    if (inputs.empty())
        throw facet::InputError(name + ": the list names no input (one path a line; # starts a comment)");
    return inputs;
}

bool hasPlaceholder(std::string_view output) {
    return output.find("{name}") != std::string_view::npos ||
           output.find("{index}") != std::string_view::npos;
}

std::string expandOutput(std::string_view output, const std::string& input, std::size_t index) {
    const std::string name = std::filesystem::path(input).stem().string();
    std::string expanded;
    while (!output.empty()) {
        if (output.starts_with("{name}")) {
            expanded += name;
            output.remove_prefix(6);
        } else if (output.starts_with("{index}")) {
            expanded += std::to_string(index);
            output.remove_prefix(7);
        } else {
            expanded += output.front();
            output.remove_prefix(1);
        }
    }
    return expanded;
}

BatchPlan planBatch(const std::vector<std::string>& inputs, const std::string& output, Shard shard,
                    bool components) {
    if (inputs.size() > 1 && !hasPlaceholder(output))
        throw facet::InputError("-o " + shown(output) + " names one image for " +
                                std::to_string(inputs.size()) +
                                " inputs: put {name} (the input's file name) or {index} (its place in the "
                                "list) in it, like -o out/{name}.png");
    BatchPlan plan;
    plan.listSize = inputs.size();
    plan.shard = shard;
    // Every image of the whole list, by its path as written (out/./a.png is out/a.png): whose it is.
    std::unordered_map<std::string, std::size_t> owners;
    for (std::size_t index = 0; index < inputs.size(); ++index) {
        const std::string expanded = expandOutput(output, inputs[index], index);
        std::vector<std::filesystem::path> images = {expanded};
        if (components)
            for (const facet::EnumName<facet::LightingTerm>& term : facet::kLightingTermNames)
                images.push_back(componentPath(expanded, term.name));
        for (const std::filesystem::path& image : images) {
            const auto [owner, added] = owners.try_emplace(image.lexically_normal().string(), index);
            if (added) continue;
            const std::size_t other = owner->second;
            std::string message = "-o " + shown(output) + ": ";
            if (inputs[other] == inputs[index])
                message += shown(inputs[index]) + " is in the list twice (inputs " + std::to_string(other) +
                           " and " + std::to_string(index) + ", counted from 0): both would write ";
            else
                message += shown(inputs[other]) + " and " + shown(inputs[index]) + " (inputs " +
                           std::to_string(other) + " and " + std::to_string(index) +
                           ", counted from 0) would both write ";
            message += shown(image.string());
            if (output.find("{index}") == std::string::npos)
                message += "; add {index}, like -o out/{name}-{index}.png";
            throw facet::InputError(message);
        }
        if (index % static_cast<std::size_t>(shard.count) == static_cast<std::size_t>(shard.index))
            plan.items.push_back({index, inputs[index], expanded});
    }
    return plan;
}

bool isBatch(const RenderArgs& args) {
    return args.inputs.size() > 1 || args.list || args.shard;
}

BatchPlan planBatch(const RenderArgs& args) {
    renderSettings(args);
    const Shard shard = args.shard ? parseShard(*args.shard) : Shard{};
    std::vector<std::string> inputs = args.inputs;
    if (args.list) {
        std::vector<std::string> listed = readInputList(*args.list);
        inputs.insert(inputs.end(), std::make_move_iterator(listed.begin()),
                      std::make_move_iterator(listed.end()));
    }
    if (args.frames && inputs.size() > 1)
        throw facet::InputError("--frames renders the turntable of one input, not of a batch of " +
                                std::to_string(inputs.size()) + ": run one facet render --frames per input");
    return planBatch(inputs, args.output, shard, args.components);
}

BatchLanes planLanes(int threads, std::size_t items) {
    if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    const std::size_t lanes = std::max<std::size_t>(1, std::min<std::size_t>(std::size_t(threads), items));
    BatchLanes plan;
    // threads / lanes each, the remainder one more to the first lanes: 5 threads, 2 inputs → 3 and 2.
    for (std::size_t lane = 0; lane < lanes; ++lane)
        plan.threads.push_back(threads / static_cast<int>(lanes) +
                               (lane < std::size_t(threads) % lanes ? 1 : 0));
    return plan;
}

std::uint64_t inputMemoryEstimate(const facet::Scene& scene) {
    std::uint64_t modelBytes = 0;
    std::vector<std::filesystem::path> counted;  // a model drawn by several objects is read once
    for (const facet::ObjectSpec& object : scene.objects) {
        if (std::find(counted.begin(), counted.end(), object.model) != counted.end()) continue;
        counted.push_back(object.model);
        std::error_code error;
        const std::uintmax_t size = std::filesystem::file_size(object.model, error);
        if (!error) modelBytes = facet::plusSaturating(modelBytes, size);
    }
    return facet::plusSaturating(facet::frameImageBytes(scene),
                                 facet::timesSaturating(modelBytes, kModelBytesPerFileByte));
}

void MemoryGate::enter(std::uint64_t bytes) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return inFlight_ == 0 || facet::plusSaturating(held_, bytes) <= limit_; });
    held_ += bytes;
    ++inFlight_;
}

void MemoryGate::leave(std::uint64_t bytes) {
    {
        const std::lock_guard lock(mutex_);
        held_ -= bytes;
        --inFlight_;
    }
    changed_.notify_all();
}

namespace {

// What one input of a batch has to say, held until the inputs before it have said theirs.
struct InputReport {
    bool finished = false;
    bool rendered = false;
    std::string warnings;  // to standard error
    std::string out;       // --stats lines and "facet: wrote …", to standard output
    BatchFailure failure;  // when not rendered
};

// Prints the inputs' reports in list order as they finish, and keeps the progress line on the first
// input not yet reported. Called from every lane.
class InOrderReporter {
  public:
    InOrderReporter(const BatchConsole& console, std::size_t count, BatchResult& result)
        : console_(console), progress_(console), reports_(count), result_(result) {}

    void showFirst(const std::string& input) {
        const std::lock_guard lock(mutex_);
        if (next_ == 0) progress_.show(1, reports_.size(), input);
    }

    // `report` of input k, and what follows it in the list that had finished before it.
    void finish(std::size_t k, InputReport report, const std::vector<BatchItem>& items) {
        const std::lock_guard lock(mutex_);
        report.finished = true;
        reports_[k] = std::move(report);
        while (next_ < reports_.size() && reports_[next_].finished) {
            InputReport& done = reports_[next_];
            progress_.clear();  // warnings and --stats lines wait for it to be erased
            console_.err << done.warnings << std::flush;
            console_.out << done.out << std::flush;
            if (done.rendered)
                ++result_.rendered;
            else
                result_.failures.push_back(std::move(done.failure));
            done = InputReport{};  // its text is printed: free it
            done.finished = true;
            if (++next_ < reports_.size()) progress_.show(next_ + 1, reports_.size(), items[next_].input);
        }
    }

    void clearProgress() {
        const std::lock_guard lock(mutex_);
        progress_.clear();
    }

  private:
    std::mutex mutex_;
    const BatchConsole& console_;
    ProgressLine progress_;
    std::vector<InputReport> reports_;
    std::size_t next_ = 0;  // the first input not yet printed
    BatchResult& result_;
};

// One input of the batch on `context`'s threads, let in by `gate` once its scene says what it needs.
InputReport renderItem(RenderArgs& item, const BatchItem& planned, const RenderSettings& settings,
                       facet::DrawContext& context, MemoryGate& gate, bool quiet) {
    item.input = planned.input;
    item.output = planned.output;
    InputReport report;
    std::ostringstream out, warnings;
    try {
        const facet::Scene scene = inputScene(item);
        const std::uint64_t bytes = inputMemoryEstimate(scene);
        gate.enter(bytes);
        const struct Leave {
            MemoryGate& gate;
            std::uint64_t bytes;
            ~Leave() { gate.leave(bytes); }
        } leave{gate, bytes};
        const RenderedInput rendered = renderScene(item, settings, scene, context, out, warnings);
        report.rendered = true;
        if (!quiet) out << wroteLine(rendered);
    } catch (...) {
        report.failure = {item.input, failureMessage(item.input)};
    }
    report.out = out.str();
    report.warnings = warnings.str();
    return report;
}

}  // namespace

BatchResult runBatch(const RenderArgs& args, const BatchPlan& plan, const BatchConsole& console) {
    const RenderSettings settings = renderSettings(args);
    const auto start = std::chrono::steady_clock::now();
    const BatchLanes lanes = planLanes(args.threads, plan.items.size());
    MemoryGate gate(facet::memoryLimit().bytes);
    BatchResult result;
    {
        InOrderReporter reporter(console, plan.items.size(), result);
        if (!plan.items.empty()) reporter.showFirst(plan.items.front().input);
        std::atomic<std::size_t> next{0};  // the next item a lane takes, in list order
        std::mutex failedMutex;
        std::exception_ptr failed;  // a lane's own failure (not an input's): rethrown once all have stopped
        // A lane: its own threads, made once (the bytes do not depend on their number), and its own
        // copy of the options, input and output being each item's.
        const auto lane = [&](int threads) {
            try {
                facet::DrawContext context(threads);
                RenderArgs item = args;
                item.inputs.clear();
                for (std::size_t k; (k = next.fetch_add(1)) < plan.items.size();)
                    reporter.finish(k, renderItem(item, plan.items[k], settings, context, gate, args.quiet),
                                    plan.items);
            } catch (...) {
                const std::lock_guard lock(failedMutex);
                if (!failed) failed = std::current_exception();
                next = plan.items.size();  // the other lanes stop after their input
            }
        };
        std::vector<std::thread> others;
        for (std::size_t k = 1; k < lanes.threads.size(); ++k) {
            try {
                others.emplace_back(lane, lanes.threads[k]);
            } catch (const std::system_error& refused) {
                // The lanes started take every input, more slowly: said once, as a pool says it.
                const auto sum = [&](std::size_t end) {
                    return std::accumulate(lanes.threads.begin(),
                                           lanes.threads.begin() + static_cast<std::ptrdiff_t>(end), 0);
                };
                facet::reportThreadShortfall(sum(k), sum(lanes.threads.size()), refused.code().message());
                break;
            }
        }
        lane(lanes.threads.front());  // the calling thread is the first lane
        for (std::thread& other : others)
            other.join();
        if (failed) std::rethrow_exception(failed);
        reporter.clearProgress();
    }
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    // The summary: to standard output on success, to standard error with every failure otherwise.
    if (result.failures.empty() && args.quiet) return result;
    char rate[64];
    std::snprintf(rate, sizeof rate, " in %.2f s (%.2f models per second)", result.seconds,
                  result.seconds > 0 ? double(result.rendered) / result.seconds : 0.0);
    std::ostringstream summary;
    summary << "facet: rendered " << result.rendered << " of " << plan.items.size() << " inputs";
    if (args.shard)
        summary << " (shard " << plan.shard.index << "/" << plan.shard.count << " of a list of "
                << plan.listSize << ")";
    summary << rate;
    if (result.failures.empty()) {
        console.out << summary.str() << "\n" << std::flush;
        return result;
    }
    summary << "; " << result.failures.size() << " failed:\n";
    for (const BatchFailure& failure : result.failures)
        summary << failure.message << "\n";
    console.err << summary.str() << std::flush;
    return result;
}

int renderBatch(const RenderArgs& args) {
    const BatchPlan plan = planBatch(args);
    BatchConsole console{std::cout, std::cerr};
    console.terminal = isatty(STDERR_FILENO) == 1;
    winsize size{};
    if (console.terminal && ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0)
        console.columns = size.ws_col;
    const BatchResult result = runBatch(args, plan, console);
    return result.failures.empty() ? 0 : 1;
}

}  // namespace facet::cli
