// renderFrameWatched (renderer.h): the one copy of the watched frame, for every FrameWatcher.
#include "render/renderer.h"

namespace facet {

namespace {

// renderFrame's observer for a FrameWatcher: the pipeline's hooks through WatcherRef, and onPlannedDraw.
struct FrameWatcherRef : WatcherRef {
    FrameWatcher* frameWatcher;
    void onPlannedDraw(const PlannedDraw& call, const PreparedDraw& draw) {
        frameWatcher->onPlannedDraw(call, draw);
    }
};

}  // namespace

FrameStats renderFrameWatched(const PreparedScene& prepared, Framebuffer& target, DrawContext& context,
                              FrameMemory& memory, FrameWatcher& watcher, std::uint8_t terms) {
    FrameWatcherRef observer{{&watcher}, &watcher};
    return renderFrame(prepared, target, context, memory, observer, terms);
}

}  // namespace facet
