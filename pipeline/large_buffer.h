// Storage for the framebuffer's planes: at 1920×1080 a float colour plane is 33 MB, which the kernel
// maps page by page (8,000 faults of 4 KiB, each zeroed, when the buffer is first written: a fifth of
// the time of a one-image render). Buffers of 4 MiB and more are mapped here in 2 MiB-aligned runs the
// kernel may back with transparent huge pages (madvise MADV_HUGEPAGE: 16 faults instead of 8,000);
// smaller ones, and every buffer under AddressSanitizer (which checks heap blocks only), come from new.
#pragma once

#include <sys/mman.h>

#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

namespace facet {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kMapLargeBuffers = false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kMapLargeBuffers = false;
#else
inline constexpr bool kMapLargeBuffers = true;
#endif
#else
inline constexpr bool kMapLargeBuffers = true;
#endif

template <class T>
struct LargeBufferAllocator {
    using value_type = T;
    static constexpr std::size_t kMapFrom = std::size_t{4} << 20;
    static constexpr std::size_t kHugePage = std::size_t{2} << 20;

    LargeBufferAllocator() = default;
    template <class U>
    LargeBufferAllocator(const LargeBufferAllocator<U>&) {}

    static std::size_t mappedBytes(std::size_t count) {
        return (count * sizeof(T) + kHugePage - 1) / kHugePage * kHugePage;
    }

    T* allocate(std::size_t count) {
        if (count > std::size_t(-1) / sizeof(T)) throw std::bad_alloc();
        const std::size_t bytes = count * sizeof(T);
        if (!kMapLargeBuffers || bytes < kMapFrom) return static_cast<T*>(::operator new(bytes));
        // A run aligned to 2 MiB: map a huge page more than needed and give back the ends.
        const std::size_t length = mappedBytes(count);
        void* mapped =
            ::mmap(nullptr, length + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (mapped == MAP_FAILED) throw std::bad_alloc();
        const auto base = reinterpret_cast<std::uintptr_t>(mapped);
        const std::uintptr_t aligned = (base + kHugePage - 1) / kHugePage * kHugePage;
        if (aligned > base) ::munmap(mapped, aligned - base);
        const std::uintptr_t end = base + length + kHugePage;
        if (end > aligned + length)
            ::munmap(reinterpret_cast<void*>(aligned + length), end - (aligned + length));
        ::madvise(reinterpret_cast<void*>(aligned), length, MADV_HUGEPAGE);  // a hint: fine if refused
        return reinterpret_cast<T*>(aligned);
    }

    void deallocate(T* pointer, std::size_t count) noexcept {
        const std::size_t bytes = count * sizeof(T);
        if (!kMapLargeBuffers || bytes < kMapFrom)
            ::operator delete(pointer);
        else
            ::munmap(pointer, mappedBytes(count));
    }

    template <class U>
    bool operator==(const LargeBufferAllocator<U>&) const {
        return true;
    }
};

template <class T>
using LargeBuffer = std::vector<T, LargeBufferAllocator<T>>;

}  // namespace facet
