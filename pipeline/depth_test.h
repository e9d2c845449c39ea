// Depth test: keeps the fragment nearest the eye (z-buffer, Catmull 1974) under a configurable compare.
// In: the fragment's window depth and the stored depth. Out: pass or fail (the write is the caller's).
#pragma once

#include "state.h"
#include "wide.h"

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

// The same for eight fragments: a lane mask (all bits set where the fragment passes).
inline Int8 depthTestPasses(CompareOp op, Float8 fragmentDepth, Float8 storedDepth) {
    const Int8 none = {0, 0, 0, 0, 0, 0, 0, 0};
    switch (op) {
        case CompareOp::Never:
            return none;
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
            return none == none;
    }
    return none;
}

}  // namespace facet
