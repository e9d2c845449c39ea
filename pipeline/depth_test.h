// Depth test: keeps the fragment nearest the eye (z-buffer, Catmull 1974) under a configurable compare.
// In: the fragment's window depth and the stored depth. Out: pass or fail (the write is the caller's).
#pragma once

#include <cstdint>

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

// A draw's compare resolved once (planDraw) into which orderings of (fragment, stored) pass: less,
// equal and greater, each kept or not, and the verdict inverted for NotEqual, the one compare that
// passes an unordered (NaN) pair, as `!=` does. The back end's test is then the same few operations
// for every compare, with no choice left per block row or fragment, and each verdict is
// depthTestPasses's, NaN included: Never keeps none, Always none inverted, LessEqual less and equal,
// NotEqual equal inverted, and so on.
struct DepthCompare {
    std::int32_t less = -1, equal = 0, greater = 0, invert = 0;  // each all bits set, or none

    DepthCompare() = default;  // Less
    explicit DepthCompare(CompareOp op) {
        const auto keep = [](bool on) { return on ? std::int32_t{-1} : std::int32_t{0}; };
        const bool notEqual = op == CompareOp::NotEqual, always = op == CompareOp::Always;
        less = keep(op == CompareOp::Less || op == CompareOp::LessEqual);
        equal = keep(op == CompareOp::Equal || op == CompareOp::LessEqual || op == CompareOp::GreaterEqual ||
                     notEqual);
        greater = keep(op == CompareOp::Greater || op == CompareOp::GreaterEqual);
        invert = keep(notEqual || always);
    }

    bool passes(float fragmentDepth, float storedDepth) const {
        const std::int32_t orderings = (-std::int32_t{fragmentDepth < storedDepth} & less) |
                                       (-std::int32_t{fragmentDepth == storedDepth} & equal) |
                                       (-std::int32_t{fragmentDepth > storedDepth} & greater);
        return (orderings ^ invert) != 0;
    }
    // A lane mask: all bits set where a lane passes.
    Int8 passes(Float8 fragmentDepth, Float8 storedDepth) const {
        return (((fragmentDepth < storedDepth) & less) | ((fragmentDepth == storedDepth) & equal) |
                ((fragmentDepth > storedDepth) & greater)) ^
               invert;
    }
};

}  // namespace facet
