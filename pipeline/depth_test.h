// Depth test: keeps the fragment nearest the eye (z-buffer, Catmull 1974) under a configurable compare.
// In: the fragment's window depth and the stored depth. Out: pass or fail (the write is the caller's).
#pragma once

#include "state.h"
#include "wide.h"

namespace facet {

// glDepthFunc semantics: the fragment passes when `fragmentDepth OP storedDepth`. For float operands
// the verdict is a bool; for Float8 (eight fragments) a lane mask, all bits set where a lane passes.
// Always inlined into the per-block depth test (out of line, the call and the switch cost more than the
// compare).
template <class Depth>
[[gnu::always_inline]] inline auto depthTestPasses(CompareOp op, Depth fragmentDepth, Depth storedDepth) {
    const auto never = fragmentDepth < fragmentDepth;  // false (or all lanes false), of the right type
    switch (op) {
        case CompareOp::Never:
            return never;
        case CompareOp::Less:
            return fragmentDepth < storedDepth;
        case CompareOp::Equal:
            return fragmentDepth == storedDepth;
        case CompareOp::LessEqual:
            return fragmentDepth <= storedDepth;
        case CompareOp::Greater:
            return fragmentDepth > storedDepth;
        case CompareOp::NotEqual:
            return fragmentDepth != storedDepth;
        case CompareOp::GreaterEqual:
            return fragmentDepth >= storedDepth;
        case CompareOp::Always:
            return never == never;
    }
    return never;
}

}  // namespace facet
