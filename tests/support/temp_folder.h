// The one temporary-folder helper of the tests: TempFolder (a folder of one test's own files) and the
// TempFolderTest fixture that gives each test one; and errorWithoutOpening, for input that must be
// refused without being opened (a FIFO).
#pragma once

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <iostream>
#include <string>
#include <string_view>
#include <thread>

#include <fcntl.h>
#include <unistd.h>

#include <gtest/gtest.h>

namespace facet::testing_support {

namespace fs = std::filesystem;

// A fresh, empty folder under the system's temporary folder, made by the constructor and removed by the
// destructor. Its name is facet-test-<process id>-<suite>-<test>[-<tag>] (a parameterized test's '/'
// made '-'; outside a test, in SetUpTestSuite, the suite's name alone): unique per test and per
// process, so tests run at once (ctest -j runs each test in a process of its own) never share one, and
// a folder left by an earlier run is never met. `tag` tells two folders of one test apart.
//
// Kept on failure: when the test (or, for a suite's folder, the suite) has failed by the time the
// folder is removed, it is left in place and its path printed on standard error, so the files the test
// wrote can be looked at. A passing test leaves nothing behind.
class TempFolder {
  public:
    explicit TempFolder(std::string_view tag = {}) {
        const ::testing::UnitTest& unit = *::testing::UnitTest::GetInstance();
        // Appended piece by piece: GCC 12 reports a false -Wrestrict on chains of std::string operator+.
        std::string name = "facet-test-";
        name += std::to_string(::getpid());
        if (const ::testing::TestInfo* info = unit.current_test_info()) {
            name += '-';
            name += info->test_suite_name();
            name += '-';
            name += info->name();
        } else if (const ::testing::TestSuite* suite = unit.current_test_suite()) {
            name += '-';
            name += suite->name();
        }
        if (!tag.empty()) {
            name += '-';
            name += tag;
        }
        for (char& c : name) {
            if (c == '/') c = '-';
        }
        path_ = fs::temp_directory_path() / name;
        fs::remove_all(path_);
        fs::create_directories(path_);
    }
    ~TempFolder() {
        const ::testing::UnitTest& unit = *::testing::UnitTest::GetInstance();
        const bool failed = unit.current_test_info() != nullptr
                                ? ::testing::Test::HasFailure()
                                : unit.current_test_suite() != nullptr && unit.current_test_suite()->Failed();
        if (failed) {
            std::cerr << "kept for inspection (the test failed): " << path_.string() << "\n";
            return;
        }
        std::error_code ignored;  // a destructor must not throw; a folder that will not go stays
        fs::remove_all(path_, ignored);
    }
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;

    const fs::path& path() const { return path_; }

    // Writes `text` byte for byte (no newline translation) to `relative`, making its folders.
    fs::path write(const fs::path& relative, const std::string& text) const {
        const fs::path file = path_ / relative;
        fs::create_directories(file.parent_path());
        std::ofstream(file, std::ios::binary) << text;
        return file;
    }
    // An empty file: loadScene only checks that model files exist, so one stands in for an OBJ.
    fs::path touch(const fs::path& relative) const { return write(relative, ""); }

  private:
    fs::path path_;
};

// A TempFolder for each test, as folder_.
class TempFolderTest : public ::testing::Test {
  protected:
    fs::path write(const fs::path& relative, const std::string& text) const {
        return temp_.write(relative, text);
    }
    fs::path touch(const fs::path& relative) const { return temp_.touch(relative); }

    TempFolder temp_;
    const fs::path folder_ = temp_.path();
};

// Runs `load` on another thread and returns the message of what it threw ("" if nothing), failing the
// test if `load` opened `fifo`. A reader blocked opening a FIFO is what lets the writing end be opened
// without blocking (with no reader that open fails), and opening it releases the reader, which then
// reads an empty file; so a `load` that wrongly opens the FIFO is both caught and let go. No clock
// decides: the test waits for `load` however slow the machine is.
inline std::string errorWithoutOpening(const fs::path& fifo, const std::function<void()>& load) {
    std::promise<std::string> promise;
    std::future<std::string> message = promise.get_future();
    std::thread thread([&] {
        try {
            load();
            promise.set_value("");
        } catch (const std::exception& e) {
            promise.set_value(e.what());
        }
    });
    bool opened = false;
    while (message.wait_for(std::chrono::milliseconds(5)) != std::future_status::ready) {
        const int writer = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
        if (writer >= 0) {
            opened = true;
            ::close(writer);
        }
    }
    thread.join();
    EXPECT_FALSE(opened) << fifo << " was opened for reading";
    return message.get();
}

}  // namespace facet::testing_support
