#include "oracle/shader_compare.h"

#include <algorithm>
#include <cstdlib>

#include "shading/gamma.h"

namespace facet {

ShaderAgainstScenes shaderAgainstScenes(Scene scene, ReflectionModel model) {
    scene.lighting.model = model;
    scene.lighting.shading = ShadingFrequency::Phong;
    for (ObjectSpec& object : scene.objects) {
        object.reflection = model;
        object.shading = ShadingFrequency::Phong;
    }
    ShaderAgainstScenes scenes{scene, scene};
    scenes.builtIn.shader.reset();
    scenes.builtIn.uniforms.clear();
    for (ObjectSpec& object : scenes.builtIn.objects)
        object.shader.reset();
    return scenes;
}

namespace {

LinearImage draw(const PreparedScene& prepared, DrawContext& context) {
    Framebuffer target(prepared.scene.width, prepared.scene.height);
    FrameMemory memory;
    renderFrame(prepared, target, context, memory);
    return toImage(target);
}

}  // namespace

ShaderComparison compareShaderWithBuiltIn(const ShaderAgainstScenes& scenes, int threads,
                                          PreparedScene* preparedMine, PreparedScene* preparedBuiltIn) {
    const PreparedScene mine = prepareScene(scenes.mine);
    const PreparedScene builtIn = prepareScene(scenes.builtIn, mine.assets);
    DrawContext context(threads);
    ShaderComparison c;
    c.width = mine.scene.width;
    c.height = mine.scene.height;
    c.encoding = mine.encoding;
    c.warnings = mine.warnings;
    c.mine = draw(mine, context);
    c.builtIn = draw(builtIn, context);
    for (int y = 0; y < c.height; ++y)
        for (int x = 0; x < c.width; ++x) {
            const vec4 a = c.mine.at(x, y), b = c.builtIn.at(x, y);
            int largest = 0;
            for (int k = 0; k < 3; ++k)
                largest = std::max(largest, std::abs(int(encodeChannel(a[k], c.encoding)) -
                                                     int(encodeChannel(b[k], c.encoding))));
            if (largest == 0) continue;
            ++c.differing;
            c.largest = std::max(c.largest, largest);
            if (!c.first) c.first = std::pair(x, y);
        }
    if (preparedMine) *preparedMine = mine;
    if (preparedBuiltIn) *preparedBuiltIn = builtIn;
    return c;
}

}  // namespace facet
