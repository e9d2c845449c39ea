// libFuzzer target: the JSON scene reader (loadScene) on arbitrary bytes.
// Input: the scene file's text, written as scene.json next to a one-triangle model.obj, so that a scene
// naming "model.obj" loads (the reader checks that model files exist; it does not read them).
// InputError is the expected answer to bad input; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "base/errors.h"
#include "fuzz_files.h"
#include "scene/scene.h"

namespace {

const facet::fuzz::ScratchFolder& folderWithModel() {
    static const facet::fuzz::ScratchFolder folder;
    static const bool written =
        (folder.write(facet::fuzz::kObjName, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), true);
    (void)written;
    return folder;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const facet::fuzz::ScratchFolder& folder = folderWithModel();
    const auto scene =
        folder.write(facet::fuzz::kSceneName, std::string_view(reinterpret_cast<const char*>(data), size));
    try {
        facet::loadScene(scene);
    } catch (const facet::InputError&) {
    }
    return 0;
}
