// libFuzzer target: a whole small render, from scene file to framebuffer (loadScene, prepareScene,
// renderFrame) on arbitrary bytes.
// Input: scene JSON, a NUL byte, OBJ text, a NUL byte, MTL text, written as scene.json, model.obj and
// model.mtl in one folder (a missing part: no such file); the scene's objects name "model.obj".
// The image is at most 32×32 pixels (a smaller size in the scene is kept) and drawn on one thread, so
// that each input takes milliseconds. InputError is the expected answer to bad input; anything else
// (a crash, a sanitizer report, another exception, a hang, runaway memory) is a finding.
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "base/errors.h"
#include "fuzz_files.h"
#include "pipeline/pipeline.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace {

constexpr int kMaxFuzzSide = 32;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const facet::fuzz::ScratchFolder folder;
    static facet::DrawContext context(1);
    const auto parts = facet::fuzz::splitAtNul(data, size, 3);
    const auto sceneFile = folder.write(facet::fuzz::kSceneName, parts[0]);
    const char* const names[] = {facet::fuzz::kObjName, facet::fuzz::kMtlName};
    for (std::size_t i = 0; i < 2; ++i)
        if (parts.size() > i + 1)
            folder.write(names[i], parts[i + 1]);
        else
            folder.remove(names[i]);
    try {
        facet::Scene scene = facet::loadScene(sceneFile);
        scene.width = std::min(scene.width, kMaxFuzzSide);
        scene.height = std::min(scene.height, kMaxFuzzSide);
        const facet::PreparedScene prepared = facet::prepareScene(scene);
        facet::Framebuffer framebuffer(scene.width, scene.height);
        facet::FrameMemory memory;
        facet::renderFrame(prepared, framebuffer, context, memory);
    } catch (const facet::InputError&) {
    }
    return 0;
}
