// Waiting in a test for something other threads bring about, without hanging the test run when they
// never do.
#pragma once

#include <chrono>
#include <thread>

namespace facet::testing_support {

// Yields until `reached` holds; false only if it never does within a minute (a pool that never gets
// there: a loaded machine reaches it in milliseconds).
template <class Reached>
bool eventually(const Reached& reached) {
    const auto giveUp = std::chrono::steady_clock::now() + std::chrono::minutes(1);
    while (!reached()) {
        if (std::chrono::steady_clock::now() > giveUp) return false;
        std::this_thread::yield();
    }
    return true;
}

}  // namespace facet::testing_support
