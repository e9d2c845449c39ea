// The reference renderer tells how far its image is (facet trade prints it while the reference renders).
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "reference/reference.h"
#include "render/renderer.h"

namespace facet {
namespace {

// Catches: the callback called from the pool's worker threads (two calls at once, a caller's printing
// racing), a count that goes back or skips the end (a progress that never reaches 100%), a count past
// the rows, or the callback changing the image.
TEST(ReferenceProgress, RowsDoneRiseToEveryRowOnTheCallingThread) {
    Scene scene = loadSceneOrModel(FACET_SOURCE_DIR "/models/spot/spot_triangulated.obj");
    scene.width = 40;
    scene.height = 30;
    const PreparedScene prepared = prepareScene(scene);
    ThreadPool pool(3);
    struct Call {
        int done, rows;
        std::thread::id thread;
    };
    std::vector<Call> calls;
    ReferenceOptions options;
    options.samples = 1;
    options.onRows = [&](int done, int rows) { calls.push_back({done, rows, std::this_thread::get_id()}); };
    const LinearImage image = renderReference(prepared, options, pool);
    ASSERT_FALSE(calls.empty());
    for (std::size_t i = 0; i < calls.size(); ++i) {
        EXPECT_EQ(calls[i].thread, std::this_thread::get_id());
        EXPECT_EQ(calls[i].rows, 30);
        EXPECT_GE(calls[i].done, 1);
        EXPECT_LE(calls[i].done, 30);
        if (i > 0) {
            EXPECT_GT(calls[i].done, calls[i - 1].done);
        }
    }
    EXPECT_EQ(calls.back().done, 30);
    options.onRows = nullptr;
    EXPECT_EQ(renderReference(prepared, options, pool).pixels, image.pixels);
}

}  // namespace
}  // namespace facet
