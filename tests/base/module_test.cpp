// loadModuleEntry (base/module.h): where a module is looked for and what the user reads when it is not
// there. A library every machine running Facet has (zlib, which the PNG writer links) stands in for a
// module, found at the build path given or copied where the install layout keeps modules.
#include "base/module.h"

#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "base/errors.h"

namespace facet {
namespace {

constexpr const char* kZlib = "/lib/x86_64-linux-gnu/libz.so.1";

using Paths = std::vector<std::filesystem::path>;

std::string messageOf(const char* fileName, const char* buildPath, const char* entry) {
    try {
        loadModuleEntry(fileName, buildPath, entry, "this needs the example module");
    } catch (const InputError& error) {
        return error.what();
    }
    return "(no error)";
}

// Found at the build path when it is not beside the program: the entry's address (this test program is
// in the build tree).
// Break caught: the build path not tried (every test program would miss the modules).
TEST(Module, FoundAtTheBuildPathGivesTheEntry) {
    using Version = const char* (*)();
    const auto version = reinterpret_cast<Version>(
        loadModuleEntry("libfacet_no_such_module.so", kZlib, "zlibVersion", "this needs zlib"));
    ASSERT_NE(version, nullptr);
    EXPECT_EQ(version()[0], '1');  // zlib 1.x
}

// An installed program looks beside itself, then in the install layout's module folder relative to its
// own (a moved prefix keeps working), and never in the build tree it was built in.
// Breaks caught: the install-relative search removed (an installed facet finds no module), made absolute,
// or the build path tried for a program outside the build tree (an installed facet loading stale modules
// from a build folder).
TEST(Module, InstalledProgramLooksBesideItselfThenInTheModuleFolder) {
    EXPECT_EQ(moduleCandidates("/nonexistent-prefix/bin", "../lib/facet", "/nonexistent-build", "libm.so",
                               "/nonexistent-build/src/libm.so"),
              (Paths{"/nonexistent-prefix/bin/libm.so", "/nonexistent-prefix/lib/facet/libm.so"}));
    // A folder whose name only starts like the build tree's is not inside it.
    EXPECT_EQ(moduleCandidates("/nonexistent-build-2/bin", "../lib/facet", "/nonexistent-build", "libm.so",
                               "/nonexistent-build/src/libm.so"),
              (Paths{"/nonexistent-build-2/bin/libm.so", "/nonexistent-build-2/lib/facet/libm.so"}));
}

// A program in the build tree (the facet program, the test programs) also tries the build path, last.
// Break caught: the build path dropped for programs in the build (the tests would find no module).
TEST(Module, ProgramInTheBuildTreeAlsoTriesTheBuildPath) {
    EXPECT_EQ(moduleCandidates("/nonexistent-build/tests", "../lib/facet", "/nonexistent-build", "libm.so",
                               "/nonexistent-build/src/libm.so"),
              (Paths{"/nonexistent-build/tests/libm.so", "/nonexistent-build/lib/facet/libm.so",
                     "/nonexistent-build/src/libm.so"}));
}

// The real search, with the folder compiled in: a module in <program folder>/../lib/facet (this test
// program's, in the build) is loaded even when the build path names nothing.
// Break caught: loadModuleEntry not searching the install layout's folder, or searching another one than
// the install rules fill (FACET_MODULE_FOLDER_FROM_PROGRAM, from GNUInstallDirs).
TEST(Module, FoundInTheModuleFolderRelativeToTheProgram) {
    const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe");
    const std::filesystem::path folder = program.parent_path() / FACET_MODULE_FOLDER_FROM_PROGRAM;
    const std::string fileName = "libfacet_module_test_" + std::to_string(::getpid()) + ".so";
    std::filesystem::create_directories(folder);
    std::filesystem::copy_file(kZlib, folder / fileName);
    using Version = const char* (*)();
    Version version = nullptr;
    try {
        version = reinterpret_cast<Version>(
            loadModuleEntry(fileName.c_str(), "/nonexistent/libz.so", "zlibVersion", "this needs zlib"));
    } catch (const InputError& error) {
        ADD_FAILURE() << error.what();
    }
    std::filesystem::remove(folder / fileName);
    std::error_code notEmpty;  // the folders made for the test, left when they hold anything else
    std::filesystem::remove(folder, notEmpty);
    std::filesystem::remove(folder.parent_path(), notEmpty);
    ASSERT_NE(version, nullptr);
    EXPECT_EQ(version()[0], '1');
}

// Missing, or without the entry: one line that starts with what needed it and names every place looked.
// Breaks caught: the purpose left out of the message, a place searched but not named (the user cannot
// tell where to put the module), or a library without the entry taken as found (a null function called
// later).
TEST(Module, MissingModuleOrEntryIsOneLineSayingWhatNeedsIt) {
    const std::string missing =
        messageOf("libfacet_no_such_module.so", "/nonexistent/libfacet_no_such_module.so", "entry");
    const std::filesystem::path folder = std::filesystem::read_symlink("/proc/self/exe").parent_path();
    // The expected messages appended piece by piece: GCC 12 at -O1 warns falsely (-Warray-bounds) on a
    // chain of + on a temporary string.
    std::string expectedMissing =
        "this needs the example module, and libfacet_no_such_module.so was not found (looked for ";
    expectedMissing.append((folder / "libfacet_no_such_module.so").string())
        .append(", ")
        .append((folder / FACET_MODULE_FOLDER_FROM_PROGRAM / "libfacet_no_such_module.so")
                    .lexically_normal()
                    .string())
        .append(" and /nonexistent/libfacet_no_such_module.so; copy it to one of them)");
    EXPECT_EQ(missing, expectedMissing);
    const std::string noEntry = messageOf("libfacet_no_such_module.so", kZlib, "noSuchEntry");
    std::string expectedNoEntry =
        "this needs the example module, and libfacet_no_such_module.so could not be loaded: ";
    expectedNoEntry.append(kZlib).append(" has no noSuchEntry");
    EXPECT_EQ(noEntry, expectedNoEntry);
    EXPECT_EQ(missing.find('\n'), std::string::npos);
}

}  // namespace
}  // namespace facet
