// The one place where tests that need Mesa (OSMesa, loaded at run time by oracle/mesa_peer.h) decide
// to skip. A test that needs it derives its fixture from MesaTest<driver>: SetUp opens the driver, and
// where OSMesa is not installed (or cannot give that driver) the test is skipped with one message
// saying why, before its body runs. Everything else about Mesa is the test's own business: a skipped
// test asserts nothing, so nothing important may be guarded only by such tests (CI runs the suite once
// more without OSMesa to see that the rest stands on its own; see .ci/run).
//
// Mesa takes one Gallium driver per process: ctest runs every test in a process of its own, so each
// test gets its driver; running a whole binary at once skips the tests of the driver not opened first.
#pragma once

#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "oracle/mesa_peer.h"

namespace facet {

// `Base` is ::testing::Test, or ::testing::TestWithParam<T> for parameterised tests.
template <MesaDriver kDriver, class Base = ::testing::Test>
class MesaTest : public Base {
  protected:
    void SetUp() override {
        std::string whyNot;
        peer_ = MesaPeer::open(MesaOptions{kDriver, 1}, whyNot);
        if (!peer_)
            GTEST_SKIP() << "Mesa " << driverName(kDriver) << " (OSMesa) cannot be opened: " << whyNot;
    }

    // The peer SetUp opened (one thread); only reached when it did.
    MesaPeer& mesa() { return *peer_; }

  private:
    std::unique_ptr<MesaPeer> peer_;
};

using SoftpipeTest = MesaTest<MesaDriver::Softpipe>;
using LlvmpipeTest = MesaTest<MesaDriver::Llvmpipe>;

}  // namespace facet
