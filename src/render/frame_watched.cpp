// renderFrameWatched (renderer.h): the one copy of the watched frame, for every FrameWatcher.
#include "render/renderer.h"

namespace facet {

namespace {

// renderFrame's observer for a FrameWatcher: the pipeline's hooks through WatcherRef, and onPlannedDraw
// to the same watcher.
struct FrameWatcherRef : WatcherRef {
    void onPlannedDraw(const PlannedDraw& call, const PreparedDraw& draw) {
        static_cast<FrameWatcher*>(watcher)->onPlannedDraw(call, draw);
    }
};

}  // namespace

FrameStats renderFrameWatched(const PreparedScene& prepared, Framebuffer& target, DrawContext& context,
                              FrameMemory& memory, FrameWatcher& watcher, std::uint8_t terms) {
    FrameWatcherRef observer{{&watcher}};
    return renderFrame(prepared, target, context, memory, observer, terms);
}

}  // namespace facet
