#include "render/memory_estimate.h"

#include "base/errors.h"
#include "base/memory_limit.h"
#include "pipeline/framebuffer.h"
#include "render/renderer.h"
#include "render/shadow_maps.h"

namespace facet {

std::uint64_t frameImageBytes(const Scene& scene) {
    const PipelineOptions& pipeline = scene.pipeline;
    const int multisamples =
        isMultisampled(pipeline.antialiasing) ? samplesPerPixel(pipeline.antialiasing) : 1;
    const std::uint64_t pixels = std::uint64_t(scene.width) * std::uint64_t(scene.height);
    std::uint64_t bytes = Framebuffer::bytesFor(scene.width, scene.height, multisamples);
    if (multisamples == 1 && samplesPerPixel(pipeline.antialiasing) > 1)  // FrameMemory::sampleSum
        bytes = plusSaturating(bytes, timesSaturating(pixels, sizeof(vec4)));
    return plusSaturating(bytes, timesSaturating(pixels, sizeof(vec4)));  // LinearImage (toImage)
}

std::string frameImageWords(const Scene& scene) {
    std::string words = "a " + std::to_string(scene.width) + "x" + std::to_string(scene.height) + " image";
    const Antialiasing aa = scene.pipeline.antialiasing;
    if (samplesPerPixel(aa) > 1)
        words += " with " + std::to_string(samplesPerPixel(aa)) + " samples per pixel (--aa " +
                 std::string(nameOf(aa)) + ")";
    return words;
}

void checkFrameMemory(const Scene& scene) {
    requireMemory("rendering " + frameImageWords(scene), frameImageBytes(scene));
}

std::uint64_t shadowMapsMemory(const PreparedScene& prepared, std::uint64_t& faces, int& lights) {
    faces = 0;
    lights = 0;
    if (prepared.draws.empty()) return 0;
    for (std::size_t i = 0; i < kMaxLights; ++i)
        if (prepared.shadowMethods[i] == ShadowMethod::Map) {
            faces += std::uint64_t(shadowMapFaces(prepared.draws.front().uniforms.lights[i]));
            ++lights;
        }
    if (faces == 0) return 0;
    return plusSaturating(frameImageBytes(prepared.scene),
                          shadowMapBytes(faces, prepared.shadowMapOptions.size));
}

void checkShadowMapMemory(const PreparedScene& prepared) {
    std::uint64_t faces = 0;
    int lights = 0;
    const std::uint64_t bytes = shadowMapsMemory(prepared, faces, lights);
    if (faces == 0) return;
    const std::string size = std::to_string(prepared.shadowMapOptions.size);
    requireMemory("drawing the shadow maps of " + std::to_string(lights) +
                      (lights == 1 ? " light (" : " lights (") + std::to_string(faces) +
                      (faces == 1 ? " image" : " images") + " of " + size + "x" + size +
                      " texels, --shadow-map-size) for " + frameImageWords(prepared.scene),
                  bytes);
}

std::uint64_t fragmentListBudget(const Scene& scene) {
    const std::uint64_t limit = memoryLimit().bytes, image = frameImageBytes(scene);
    return limit > image ? limit - image : 0;
}

void checkFragmentListMemory(const Scene& scene, std::uint64_t refusedNodeBytes) {
    if (refusedNodeBytes == 0) return;
    // More than the budget, so more than the limit with the image: requireMemory throws.
    requireMemory("keeping every transparent layer of " + frameImageWords(scene) +
                      " (--transparency exact; --transparency sorted needs no more memory)",
                  plusSaturating(frameImageBytes(scene), refusedNodeBytes));
    throw ResourceError(
        "the fragment lists of --transparency exact reached the memory limit");  // limit raised meanwhile
}

}  // namespace facet
