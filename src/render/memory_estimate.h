// What a frame's large buffers take, estimated before the work from the size functions that then
// allocate them (Framebuffer::bytesFor, shadowMapBytes), and checked against the memory limit
// (base/memory_limit.h): "rendering a 8192x8192 image with 16 samples per pixel (--aa msaa16) needs
// 21.0 GiB, more than the memory limit of 12.0 GiB (...)", exit status 4.
#pragma once

#include <cstdint>
#include <string>

namespace facet {

struct Scene;
struct PreparedScene;

// The image's buffers for one frame of `scene`: the framebuffer (and its samples under --aa msaaN),
// the running sum of --aa ssaaN's passes and the finished linear image handed to the writer.
std::uint64_t frameImageBytes(const Scene& scene);
// Those buffers in words: "a 1280x960 image" or "a 8192x8192 image with 16 samples per pixel (--aa msaa16)".
std::string frameImageWords(const Scene& scene);
// Refuses (ResourceError) a frame whose image buffers exceed the limit, before anything is loaded.
void checkFrameMemory(const Scene& scene);

// The bytes the shadow maps of `prepared`'s lights that use them take, with the frame's image; their
// faces in all (0: no shadow map) in `faces`.
std::uint64_t shadowMapsMemory(const PreparedScene& prepared, std::uint64_t& faces, int& lights);
// Refuses (ResourceError) shadow maps that, with the image, exceed the limit, before any is drawn.
void checkShadowMapMemory(const PreparedScene& prepared);

// Refuses the frame whose exact transparency's fragment lists were stopped at the limit (their budget,
// FragmentLists::setByteBudget, is the limit less frameImageBytes): call after the frame's resolve.
void checkFragmentListMemory(const Scene& scene, std::uint64_t refusedNodeBytes);
// The budget to give the fragment lists for a frame of `scene`.
std::uint64_t fragmentListBudget(const Scene& scene);

}  // namespace facet
