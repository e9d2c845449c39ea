// The memory a run may use, checked before the work: every large allocation (the image's planes, the
// samples of antialiasing, shadow maps, exact transparency's fragment lists, textures, the step page's
// traces) is estimated from the same size functions that then allocate it, and refused with one line
// naming what needs the memory, exit status 4 (ResourceError), instead of a swap storm, the kernel's
// OOM killer, or a std::bad_alloc half way through.
#pragma once

#include <cstdint>
#include <string>

namespace facet {

// The limit, in bytes, and where it came from, in words a user knows ("--memory-limit", "half of this
// machine's memory", ...).
struct MemoryLimit {
    std::uint64_t bytes = 0;
    std::string source;
};

// The limit now: the one set by setMemoryLimit, else FACET_MEMORY_LIMIT from the environment, else the
// default: the smallest of half this machine's memory (/proc/meminfo MemTotal), three quarters of the
// process's address-space limit (RLIMIT_AS, `ulimit -v`: code, stacks and the allocator's slack use the
// rest) and three quarters of the container's memory limit (cgroup v2 memory.max, or v1's
// memory.limit_in_bytes).
MemoryLimit memoryLimit();

// A size as a user writes it: a whole or decimal number with an optional unit K, M, G, T (powers of
// 1024; KiB, MB, GB... are read the same way, B alone is bytes), e.g. "512M", "1.5G", "4GiB", "123456".
// Throws InputError naming `origin` (the option or variable) when it is not one, or is zero.
std::uint64_t parseMemorySize(const std::string& text, const std::string& origin);

// Sets the limit for the rest of the run (--memory-limit SIZE); `origin` names where it came from.
void setMemoryLimit(const std::string& text, const std::string& origin);
// Forgets a limit set by setMemoryLimit (tests): memoryLimit() reads the environment and machine again.
void resetMemoryLimit();

// Bytes as a reader wants them: "512 bytes", "3.0 KiB", "12.0 GiB" (one decimal, powers of 1024).
std::string describeBytes(std::uint64_t bytes);

// Throws ResourceError when `bytes` exceed the limit: "WHAT needs 21.0 GiB, more than the memory limit
// of 12.0 GiB (half of this machine's memory; --memory-limit SIZE or FACET_MEMORY_LIMIT sets it)".
// `what` names the thing and its size, e.g. "the shadow maps of 8 point lights at 8192x8192".
void requireMemory(const std::string& what, std::uint64_t bytes);

// a × b (× c), saturating at the largest uint64_t instead of wrapping: an estimate of an absurd size
// must stay absurd.
std::uint64_t timesSaturating(std::uint64_t a, std::uint64_t b);
std::uint64_t plusSaturating(std::uint64_t a, std::uint64_t b);

// What a std::bad_alloc that still happens was allocating, for its message: set by a MemoryUse for the
// duration of a large allocation's phase (loading textures, drawing shadow maps...), read by the
// command's catch. Empty outside any: the message then names the image.
class MemoryUse {
  public:
    explicit MemoryUse(const char* what);
    ~MemoryUse();
    MemoryUse(const MemoryUse&) = delete;
    MemoryUse& operator=(const MemoryUse&) = delete;

  private:
    const char* previous_;
    int uncaught_;
};
// The innermost MemoryUse's words, or nullptr.
const char* currentMemoryUse();
// The message for a std::bad_alloc: "out of memory while WHAT (...)" or the image's default. A MemoryUse
// an exception left is read here and forgotten.
std::string outOfMemoryMessage();

}  // namespace facet
