// The optional record the shading formulas fill (the step mode's "show the numbers"). A formula ends
// its parameters with a pack, `class... Recording` and `Recording*... recording`: empty (the pipeline's
// case), the formula's signature and code are exactly what they are without records; one pointer to a
// record type (LightingRecord, FogRecord, …: plain structs with `enabled` true), and the very values the
// formula computes are copied into it, for one lane (F = float). So the numbers a lecture screen shows
// are never a second copy of a formula. In the body,
//   using Record = RecordOf<Recording...>;                                   // NoRecord: none
//   if constexpr (Record::enabled) recordOf(recording...)->cosAngle = cosAngle;  // compiled out then
// and a formula it calls gets its part of the record: spotFactor(light, L, &recording->spot...), no
// argument at all when not recording. The formulas' bodies otherwise stay as they were: GCC's inlining
// and function splitting follow small details (a helper function, a result returned from a named local),
// and the eight-lane code is to stay the same instructions (checked by disassembling the renderer). A
// result returned as an expression is recorded by calling the formula again without a record
// (applyFog, brdfLobes, spotFactor…) or by the caller (the shaders' outputs).
#pragma once

namespace facet {

// No record: what a formula records into when its caller asked for none.
struct NoRecord {
    static constexpr bool enabled = false;
};

template <class... Recording>
struct RecordOfPack;
template <>
struct RecordOfPack<> {
    using Type = NoRecord;
};
template <class Record>
struct RecordOfPack<Record> {
    using Type = Record;
};
// The record type of a formula's pack: NoRecord for none, else the one given.
template <class... Recording>
using RecordOf = typename RecordOfPack<Recording...>::Type;

// The record pointer of a formula's pack: null for none.
inline NoRecord* recordOf() {
    return nullptr;
}
template <class Record>
Record* recordOf(Record* record) {
    return record;
}

}  // namespace facet
