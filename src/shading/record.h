// The optional record the shading formulas fill (the step mode's "show the numbers"). A formula takes
// a template parameter `class Record = NoRecord` and a `Record* record = nullptr` argument: with
// NoRecord (the pipeline's case) every `if constexpr (Record::enabled)` block is compiled out and the
// code is the formula alone; with a record type (LightingRecord, FogRecord, …: plain structs with
// `enabled` true) the very values the formula computes are copied into it, for one lane (F = float).
// So the numbers a lecture screen shows are never a second copy of a formula.
#pragma once

#include <type_traits>

namespace facet {

// No record: what every formula takes unless a caller asks for the numbers.
struct NoRecord {
    static constexpr bool enabled = false;
};

// The record a formula hands to a formula it calls: `Inner` when the caller records, else NoRecord.
template <class Outer, class Inner>
using InnerRecord = std::conditional_t<Outer::enabled, Inner, NoRecord>;

// `&record->*member` when recording, else a null NoRecord*: what a formula passes to the formula it
// calls, e.g. standardLighting(…, innerRecord(record, &SurfaceTermsRecord::lighting)).
template <class Outer, class Record, class Inner>
InnerRecord<Outer, Inner>* innerRecord(Outer* record, Inner Record::*member) {
    if constexpr (Outer::enabled)
        return &(record->*member);
    else
        return nullptr;
}

}  // namespace facet
