// Depth test: keeps the fragment nearest the eye (z-buffer, Catmull 1974) under a configurable compare.
// In: the fragment's window depth and the stored depth. Out: pass or fail (the write is the caller's).
#pragma once

#include "state.h"

namespace facet {

// glDepthFunc semantics: the fragment passes when `fragmentDepth OP storedDepth`.
inline bool depthTestPasses(CompareOp op, float fragmentDepth, float storedDepth) {
    switch (op) {
        case CompareOp::Never:
            return false;
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
            return true;
    }
    return false;
}

}  // namespace facet
