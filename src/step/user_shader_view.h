// The shading of one fragment drawn with a shader of one's own (--shader, docs/shaders.md): its name and
// file, its uniforms for the draw, the fragment part's inputs, every value it recorded with
// gl.record(), and its output. The fragment part is run once more, one lane, on the very varyings the
// pipeline interpolated for the fragment (FragmentEvent), its record on: the same code the frame ran
// eight fragments at a time. The built-in lighting formulas are never shown for such a draw.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/types.h"
#include "render/renderer.h"
#include "step/screens.h"

namespace facet::step {

// One declared uniform and its value for the draw.
struct UserUniformShown {
    std::string name;
    UniformType type = UniformType::Float;
    std::string help;
    std::array<float, 4> value{};
    std::array<float, 4> defaults{};
    std::string setBy;  // empty: the default; else where it was set ("--uniform bands=3", a scene file)
};

// One value the fragment part recorded with gl.record().
struct UserRecordedValue {
    std::string name;
    int count = 1;
    std::array<float, 4> values{};
};

struct UserShaderTrace {
    std::string name;  // the shader's struct, as FACET_SHADER named it
    std::string file;  // as the user gave it
    int x = 0, y = 0;
    std::uint32_t triangle = 0;
    FragmentFate fate = FragmentFate::Written;
    std::vector<UserUniformShown> uniforms;  // every declared one, in declaration order
    std::vector<std::string> varyingNames;   // one per float
    std::vector<float> varyings;             // the fragment's, interpolated
    vec3 barycentrics{0.0f};
    float invW = 0.0f;
    std::array<float, 4> uvDerivatives{};  // ∂u/∂x, ∂v/∂x, ∂u/∂y, ∂v/∂y (zero without kDerivativeVarying)
    bool shaderRan = true;                 // not when the depth test failed first (early depth test)
    std::vector<UserRecordedValue> recorded;  // in the order recorded
    bool discarded = false;                   // the fragment part discarded the fragment
    vec4 output{0.0f};                        // its colour (when not discarded)
    vec4 pipelineOutput{0.0f};                // FragmentEvent::shaded
    bool matchesPipeline = false;             // output == pipelineOutput, bit for bit (when kept)
};

// The fragment part of `draw`'s user shader run again on fragment `f` with its record on. `uniforms`
// are the scene's uniforms of the call as the frame drew it (callUniforms), `state` its pipeline state.
// `scene` (for where each uniform was set) may be null.
UserShaderTrace traceUserShader(const PreparedDraw& draw, const SurfaceUniforms& uniforms,
                                const DrawState& state, const FragmentEvent& f, const Scene* scene);

// How many values of the trace are NaN or infinite: recorded values, the output and the varyings
// (each value with such a component counted once).
int nonFiniteCount(const UserShaderTrace& trace);

// The screens "uniforms" (the shader and its uniforms) and "shader" (inputs, recorded values, output),
// each line at most 80 columns; NaN and infinity flagged where they appear, with what may cause them.
std::vector<Screen> userShaderScreens(const UserShaderTrace& trace);

nlohmann::json toJson(const UserShaderTrace& trace);

}  // namespace facet::step
