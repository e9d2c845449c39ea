// The framebuffer planes' storage (large_buffer.h): large buffers are mapped on 2 MiB boundaries (so
// the kernel may back them with huge pages), small ones come from new, and both behave as vectors.
#include "large_buffer.h"

#include <cstdint>

#include <gtest/gtest.h>

#include "framebuffer.h"
#include "thread_pool.h"

namespace facet {
namespace {

// Breaks caught: the alignment arithmetic off (a run not on a 2 MiB boundary), the ends given back
// wrongly (the buffer's last bytes unmapped: the write to the last element faults), or a small buffer
// sent to munmap.
TEST(LargeBuffer, LargeOnesAreAlignedToHugePagesAndHoldTheirValues) {
    LargeBuffer<float> large(std::size_t{3} << 20, 1.5f);  // 12 MiB
    if (kMapLargeBuffers) {
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(large.data()) % (std::uintptr_t{2} << 20), 0u);
    }
    large.back() = 7.0f;
    EXPECT_EQ(large.front(), 1.5f);
    EXPECT_EQ(large.back(), 7.0f);
    LargeBuffer<float> small(1000, 2.0f);
    EXPECT_EQ(small[999], 2.0f);
    large.resize(10);  // shrinking keeps the mapping; growing past it moves to a new one
    large.resize(std::size_t{5} << 20, 3.0f);
    EXPECT_EQ(large[9], 1.5f);
    EXPECT_EQ(large.back(), 3.0f);
    LargeBuffer<float>().swap(large);
    EXPECT_TRUE(large.empty());
}

// A 1080p framebuffer in mapped planes clears and reads back like any other. Break caught: the colour
// plane's copy (colorPixels) or its view (colorSpan) reading another plane.
TEST(LargeBuffer, FramebufferPlanesClearAndReadBack) {
    Framebuffer framebuffer(1920, 1080);
    ThreadPool pool(2);
    framebuffer.clear(vec4(0.25f, 0.5f, 0.75f, 1.0f), 0.5f, pool);
    framebuffer.color(1919, 1079) = vec4(1.0f);
    EXPECT_EQ(framebuffer.colorSpan().size(), std::size_t{1920} * 1080);
    EXPECT_EQ(framebuffer.colorPixels().back(), vec4(1.0f));
    EXPECT_EQ(framebuffer.colorSpan().front(), vec4(0.25f, 0.5f, 0.75f, 1.0f));
    EXPECT_EQ(framebuffer.depthPixels().front(), 0.5f);
}

}  // namespace
}  // namespace facet
