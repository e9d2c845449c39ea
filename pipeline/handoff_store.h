// Stores of data that another core reads next: what the front end hands the tiles (set-ups and their
// varying planes), and what the vertex stage spread over threads hands the set-up.
//
// An ordinary store first takes its cache line from the core that read it last (the reader of the
// previous frame's copy), and a core may have only so many such stores waiting: on a machine whose two
// cores hand a line to each other in ~200 ns (a virtual machine whose vCPUs sit on different core
// complexes), the set-up lambda spent most of its time waiting for them. A non-temporal store (x86
// `movnti`) writes the line towards memory without taking it first (Intel SDM vol. 1 §10.4.6.2;
// AMD64 APM vol. 1 §3.9.1), and the reader fetches it from there when it needs it.
// With one thread the reader is the writer, whose own cache held the line: there streaming only sends
// it away, so callers stream only when other threads will read. Measured (`facet bench`, frames back to
// back, alternating runs, the cores far apart): 2 threads, Lost Empire 0.98 and the bunny 0.94 of
// their frame times; 1 thread, streaming everything, 1.00–1.19: slower.
//
// Non-temporal stores are weakly ordered: finishStreamedStores() (sfence) must run after a job's last
// one, before the pool tells another thread the job is done.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace facet {

// Copies `bytes` (a multiple of 4, both ends 4-byte aligned) with non-temporal stores of 4 bytes (the
// widest with no alignment demand beyond 4: a set-up is 168 bytes, its planes 4·3·n).
inline void copyStreamed(void* to, const void* from, std::size_t bytes) {
#if defined(__x86_64__) || defined(__i386__)
    auto* out = static_cast<int*>(to);
    const auto* in = static_cast<const int*>(from);
    for (std::size_t i = 0; i < bytes / sizeof(int); ++i)
        _mm_stream_si32(out + i, in[i]);
#else
    std::memcpy(to, from, bytes);
#endif
}

// Orders every earlier non-temporal store before any later store (the pool's "done").
inline void finishStreamedStores() {
#if defined(__x86_64__) || defined(__i386__)
    _mm_sfence();
#endif
}

// A value, stored with copyStreamed or plainly.
template <class T>
void storeMaybeStreamed(T& to, const T& value, bool streamed) {
    static_assert(std::is_trivially_copyable_v<T> && sizeof(T) % 4 == 0 && alignof(T) >= 4);
    if (streamed)
        copyStreamed(&to, &value, sizeof value);
    else
        to = value;
}

// An allocator whose vector grows by resize() without writing the new elements (value-initialising
// them would be ordinary stores, the very ones streaming avoids): for vectors of trivially copyable
// elements that the caller fills right after (appendMaybeStreamed).
template <class T>
struct UnfilledAllocator : std::allocator<T> {
    template <class U>
    struct rebind {
        using other = UnfilledAllocator<U>;
    };
    UnfilledAllocator() = default;
    template <class U>
    UnfilledAllocator(const UnfilledAllocator<U>&) {}

    template <class U>
    void construct(U*) noexcept {
        static_assert(std::is_trivially_copyable_v<U>, "left unwritten: the caller writes every byte");
    }
    template <class U, class... Args>
    void construct(U* at, Args&&... args) {
        ::new (static_cast<void*>(at)) U(std::forward<Args>(args)...);
    }
};

template <class T>
using UnfilledVector = std::vector<T, UnfilledAllocator<T>>;

// Appends values [first, first + count) to `out`, streamed or plainly.
template <class T>
[[gnu::always_inline]] inline void appendMaybeStreamed(UnfilledVector<T>& out, const T* first,
                                                       std::size_t count, bool streamed) {
    static_assert(std::is_trivially_copyable_v<T> && sizeof(T) % 4 == 0 && alignof(T) >= 4);
    if (!streamed) {
        out.insert(out.end(), first, first + count);
        return;
    }
    const std::size_t at = out.size();
    out.resize(at + count);  // writes nothing (UnfilledAllocator)
    copyStreamed(out.data() + at, first, count * sizeof(T));
}

}  // namespace facet
