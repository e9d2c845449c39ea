#include "base/memory_limit.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <limits>
#include <mutex>
#include <optional>
#include <sstream>

#include "base/errors.h"
#include "base/quote.h"

namespace facet {

namespace {

constexpr std::uint64_t kUnlimited = std::numeric_limits<std::uint64_t>::max();

std::mutex limitMutex;
std::optional<MemoryLimit> setLimit;  // --memory-limit

// The first number on the line of /proc/meminfo that starts with `key` ("MemTotal:"), in kB.
std::uint64_t meminfoBytes(const char* key) {
    std::ifstream in("/proc/meminfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind(key, 0) == 0)
            return timesSaturating(std::strtoull(line.c_str() + std::strlen(key), nullptr, 10), 1024);
    return 0;
}

// A cgroup's memory limit: v2's memory.max ("max" when none), else v1's memory.limit_in_bytes.
std::uint64_t cgroupBytes() {
    for (const char* file : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
        std::ifstream in(file);
        std::string word;
        if (!(in >> word) || word == "max" || word.empty() ||
            !std::isdigit(static_cast<unsigned char>(word[0])))
            continue;
        const std::uint64_t bytes = std::strtoull(word.c_str(), nullptr, 10);
        if (bytes != 0 && bytes < (std::uint64_t{1} << 62)) return bytes;  // v1 writes ~2^63 for none
    }
    return kUnlimited;
}

MemoryLimit machineLimit() {
    MemoryLimit limit{kUnlimited, "no limit"};
    const auto lower = [&](std::uint64_t bytes, const char* source) {
        if (bytes != 0 && bytes < limit.bytes) limit = {bytes, source};
    };
    lower(meminfoBytes("MemTotal:") / 2, "half of this machine's memory");
    rlimit as{};
    if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY)
        lower(std::uint64_t(as.rlim_cur) / 4 * 3,
              "three quarters of the process's address-space limit, ulimit -v");
    const std::uint64_t cgroup = cgroupBytes();
    if (cgroup != kUnlimited) lower(cgroup / 4 * 3, "three quarters of the container's memory limit");
    return limit;
}

std::atomic<const char*> memoryUse{nullptr};

}  // namespace

std::uint64_t timesSaturating(std::uint64_t a, std::uint64_t b) {
    if (a != 0 && b > kUnlimited / a) return kUnlimited;
    return a * b;
}

std::uint64_t plusSaturating(std::uint64_t a, std::uint64_t b) {
    return b > kUnlimited - a ? kUnlimited : a + b;
}

std::uint64_t parseMemorySize(const std::string& text, const std::string& origin) {
    const auto refuse = [&]() -> std::uint64_t {
        throw InputError(origin + " expects a size like 512M, 4G or 1.5G (K, M, G, T: powers of 1024), got " +
                         inQuotes(text));
    };
    std::size_t end = 0;
    while (end < text.size() && (std::isdigit(static_cast<unsigned char>(text[end])) || text[end] == '.'))
        ++end;
    if (end == 0 || std::count(text.begin(), text.begin() + std::ptrdiff_t(end), '.') > 1) return refuse();
    const double number = std::strtod(text.substr(0, end).c_str(), nullptr);
    std::string unit = text.substr(end);
    for (char& c : unit)
        c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    int power = -1;
    if (unit.empty() || unit == "B") power = 0;
    const std::string prefixes = "KMGT";
    if (!unit.empty() && prefixes.find(unit[0]) != std::string::npos) {
        const std::string rest = unit.substr(1);
        if (rest.empty() || rest == "B" || rest == "IB") power = int(prefixes.find(unit[0])) + 1;
    }
    if (power < 0) return refuse();
    const double bytes = number * std::pow(1024.0, power);
    if (!(bytes >= 1.0)) throw InputError(origin + " must be at least one byte, got " + inQuotes(text));
    if (bytes >= 1.8e19) return kUnlimited;
    return static_cast<std::uint64_t>(bytes);
}

void setMemoryLimit(const std::string& text, const std::string& origin) {
    const std::uint64_t bytes = parseMemorySize(text, origin);
    const std::lock_guard lock(limitMutex);
    setLimit = MemoryLimit{bytes, origin};
}

void resetMemoryLimit() {
    const std::lock_guard lock(limitMutex);
    setLimit.reset();
}

MemoryLimit memoryLimit() {
    {
        const std::lock_guard lock(limitMutex);
        if (setLimit) return *setLimit;
    }
    if (const char* text = std::getenv("FACET_MEMORY_LIMIT"); text && *text)
        return {parseMemorySize(text, "FACET_MEMORY_LIMIT"), "FACET_MEMORY_LIMIT"};
    static const MemoryLimit machine = machineLimit();  // the machine and the process's limits stay put
    return machine;
}

std::string describeBytes(std::uint64_t bytes) {
    if (bytes < 1024) return std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
    const char* units[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    double value = double(bytes) / 1024.0;
    int unit = 0;
    while (value >= 1023.95 && unit < 5) {
        value /= 1024.0;
        ++unit;
    }
    char text[32];
    std::snprintf(text, sizeof text, "%.1f %s", value, units[unit]);
    return text;
}

void requireMemory(const std::string& what, std::uint64_t bytes) {
    const MemoryLimit limit = memoryLimit();
    if (bytes <= limit.bytes) return;
    std::string message = what + " needs " + describeBytes(bytes) + ", more than the memory limit of " +
                          describeBytes(limit.bytes) + " (" + limit.source;
    if (limit.source != "--memory-limit") message += "; --memory-limit SIZE sets it";
    throw ResourceError(message + ")");
}

MemoryUse::MemoryUse(const char* what)
    : previous_(memoryUse.exchange(what)), uncaught_(std::uncaught_exceptions()) {}
// Left set while an exception unwinds through it, for the catch that reports it (outOfMemoryMessage).
MemoryUse::~MemoryUse() {
    if (std::uncaught_exceptions() <= uncaught_) memoryUse.store(previous_);
}
const char* currentMemoryUse() {
    return memoryUse.load();
}

std::string outOfMemoryMessage() {
    if (const char* what = memoryUse.exchange(nullptr))  // read once: the next input starts afresh
        return std::string("out of memory while ") + what +
               " (--memory-limit SIZE refuses such work before it starts)";
    return "out of memory (try a smaller image)";
}

}  // namespace facet
