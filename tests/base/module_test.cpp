// loadModuleEntry (base/module.h): where a module is looked for and what the user reads when it is not
// there. A library every machine running Facet has (zlib, which the PNG writer links) stands in for a
// module, found at the build path given.
#include "base/module.h"

#include <string>

#include <gtest/gtest.h>

#include "base/errors.h"

namespace facet {
namespace {

constexpr const char* kZlib = "/lib/x86_64-linux-gnu/libz.so.1";

std::string messageOf(const char* fileName, const char* buildPath, const char* entry) {
    try {
        loadModuleEntry(fileName, buildPath, entry, "this needs the example module");
    } catch (const InputError& error) {
        return error.what();
    }
    return "(no error)";
}

// Found at the build path when it is not beside the program: the entry's address.
// Break caught: the build path not tried (every test program would miss the modules).
TEST(Module, FoundAtTheBuildPathGivesTheEntry) {
    using Version = const char* (*)();
    const auto version = reinterpret_cast<Version>(
        loadModuleEntry("libfacet_no_such_module.so", kZlib, "zlibVersion", "this needs zlib"));
    ASSERT_NE(version, nullptr);
    EXPECT_EQ(version()[0], '1');  // zlib 1.x
}

// Missing, or without the entry: one line that starts with what needed it and says what to do.
// Breaks caught: the purpose left out of the message, or a library without the entry taken as found
// (a null function called later).
TEST(Module, MissingModuleOrEntryIsOneLineSayingWhatNeedsIt) {
    const std::string missing =
        messageOf("libfacet_no_such_module.so", "/nonexistent/libfacet_no_such_module.so", "entry");
    EXPECT_EQ(missing,
              "this needs the example module, and libfacet_no_such_module.so was not found beside the facet "
              "program nor in the build folder (copy it next to facet)");
    const std::string noEntry = messageOf("libfacet_no_such_module.so", kZlib, "noSuchEntry");
    EXPECT_EQ(noEntry,
              std::string("this needs the example module, and libfacet_no_such_module.so could not be "
                          "loaded: ") +
                  kZlib + " has no noSuchEntry");
    EXPECT_EQ(missing.find('\n'), std::string::npos);
}

}  // namespace
}  // namespace facet
