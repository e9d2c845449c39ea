// A draw's fixed-function choices, resolved once by draw() from DrawState into the values the back
// end acts on, so that no block or fragment re-derives them from the state (and the step mode can
// print what a draw will do).
#pragma once

#include "state.h"

namespace facet {

struct DrawPlan {
    // The depth test as it runs: Always when DrawState::depth.testEnabled is off.
    CompareOp depthCompare = CompareOp::Less;
    // Whether stored depths are read and compared at all (false when every fragment passes).
    bool depthTest = true;
    // Whether a fragment that passes writes its depth. OpenGL: with GL_DEPTH_TEST disabled the depth
    // buffer is neither tested nor written, even with the depth mask on (OpenGL 4.6 §14.9.4, 17.3.4).
    bool depthWrite = true;
    BlendMode blend = BlendMode::Replace;
    FragmentOutput output = FragmentOutput::Blend;
    DepthBufferFormat depthFormat = DepthBufferFormat::Float;
    ColorBufferFormat colorBuffer = ColorBufferFormat::Float;
    int samples = 1;  // per pixel: more than one draws into the framebuffer's sample planes
};

inline DrawPlan planDraw(const DrawState& state) {
    DrawPlan plan;
    plan.depthCompare = state.depth.testEnabled ? state.depth.compare : CompareOp::Always;
    plan.depthTest = plan.depthCompare != CompareOp::Always;
    plan.depthWrite = state.depth.testEnabled && state.depth.writeEnabled;
    plan.blend = state.blend;
    plan.output = state.output;
    plan.depthFormat = state.depth.format;
    plan.colorBuffer = state.colorBuffer;
    plan.samples = state.samples;
    return plan;
}

}  // namespace facet
