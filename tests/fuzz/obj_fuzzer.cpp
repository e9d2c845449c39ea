// libFuzzer target: the OBJ + MTL loader (loadObj) on arbitrary bytes.
// Input: OBJ text, a NUL byte, MTL text. The OBJ is written as model.obj and the MTL as model.mtl
// beside it (no NUL: no MTL file at all); textures the MTL names are missing. InputError is the
// expected answer to bad input; anything else (a crash, a sanitizer report, another exception, a hang,
// runaway memory) is a finding.
#include <cstddef>
#include <cstdint>

#include "base/errors.h"
#include "fuzz_files.h"
#include "io/obj_import.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const facet::fuzz::ScratchFolder folder;
    const auto parts = facet::fuzz::splitAtNul(data, size, 2);
    const auto obj = folder.write(facet::fuzz::kObjName, parts[0]);
    if (parts.size() > 1)
        folder.write(facet::fuzz::kMtlName, parts[1]);
    else
        folder.remove(facet::fuzz::kMtlName);
    try {
        facet::loadObj(obj);
    } catch (const facet::InputError&) {
    }
    return 0;
}
