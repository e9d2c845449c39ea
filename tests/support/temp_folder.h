// A fresh temporary folder per test, named after it, for the scene and model files the test writes;
// and errorWithinASecond, for input that must be refused without blocking (a FIFO).
#pragma once

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <string>
#include <thread>

#include <fcntl.h>
#include <unistd.h>

#include <gtest/gtest.h>

namespace facet::testing_support {

namespace fs = std::filesystem;

// A fresh temporary folder holding the scene files and (empty) model files of one test.
class TempFolderTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        std::string name = std::string(info->test_suite_name()) + "-" + info->name();
        for (char& c : name) {
            if (c == '/') c = '-';
        }
        folder_ = fs::temp_directory_path() / ("facet-test-" + std::to_string(::getpid()) + "-" + name);
        fs::remove_all(folder_);
        fs::create_directories(folder_);
    }
    void TearDown() override { fs::remove_all(folder_); }

    fs::path write(const fs::path& relative, const std::string& text) const {
        const fs::path path = folder_ / relative;
        fs::create_directories(path.parent_path());
        std::ofstream(path, std::ios::binary) << text;
        return path;
    }
    // loadScene only checks that model files exist, so an empty file stands in for an OBJ.
    fs::path touch(const fs::path& relative) const { return write(relative, ""); }

    fs::path folder_;
};

// Runs `load` on another thread and waits a second for it. Should it be blocked opening `fifo` for
// reading, opening the other end releases it (it then reads an empty file), so the test ends.
inline std::string errorWithinASecond(const fs::path& fifo, const std::function<void()>& load) {
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
    const bool finished = message.wait_for(std::chrono::seconds(1)) == std::future_status::ready;
    while (message.wait_for(std::chrono::milliseconds(20)) != std::future_status::ready) {
        const int writer = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
        if (writer >= 0) ::close(writer);
    }
    thread.join();
    EXPECT_TRUE(finished) << "still reading " << fifo << " after a second";
    return message.get();
}

}  // namespace facet::testing_support
