// The camera's and the scene's messages through the program: documented bounds accepted at the bound,
// an object transform that overflows named for the key the user gave, a camera for a model of 1e-30
// units, a model too small for floats, and a huge scene seen from inside drawn with its default near
// plane.
#include <string>

#include <gtest/gtest.h>

#include "cli/run_facet.h"
#include "support/bundled_models.h"

namespace facet {
namespace {

using testing_support::runFacet;
using testing_support::RunResult;
using testing_support::TempFolder;

using testing_support::kCube;

class CameraMessagesCli : public ::testing::Test {
  protected:
    TempFolder dir_;
    // facet render ARGS, a small image into the test's folder.
    RunResult render(const std::string& args) {
        return runFacet(
            "render " + args + " --width 64 --height 48 -o '" + (dir_.path() / "out.png").string() + "'",
            dir_);
    }
    std::string file(const std::string& name, const std::string& text) {
        std::string quoted = "'";  // appended piece by piece: GCC 12 warns falsely on "'" + s (-Wrestrict)
        quoted += dir_.write(name, text).string();
        quoted += "'";
        return quoted;
    }
};

// Catches: --fovy 0.01, the documented lower bound, refused ("must be from 0.01 to 179 ... got 0.01")
// because the float it becomes is compared with the double 0.01.
TEST_F(CameraMessagesCli, FieldOfViewBoundsAreAccepted) {
    for (const std::string fovy : {"0.01", "179"}) {
        const RunResult run = render("'" + kCube + "' --fovy " + fovy);
        EXPECT_EQ(run.status, 0) << fovy << ": " << run.err;
    }
}

// A scale of 1e30 on a model of 1e20 units places it at 1e50, beyond any float.
// Catches: the message speaking of "(-nan, -nan)" near and far planes the user never set, instead of
// the object's "scale".
TEST_F(CameraMessagesCli, OverflowingObjectTransformNamesTheKey) {
    file("big.obj", "v -1e20 -1e20 0\nv 1e20 -1e20 0\nv 0 1e20 0\nf 1 2 3\n");
    const std::string scene = file("over.json", R"({"objects": [{"model": "big.obj", "scale": 1e30}]})");
    const RunResult run = render(scene);
    EXPECT_EQ(run.status, 1) << run.err;
    EXPECT_NE(run.err.find("over.json: \"objects[0].scale\" scales the model"), std::string::npos) << run.err;
    EXPECT_EQ(run.err.find("nan"), std::string::npos) << run.err;
    // A translation that overflows blames "translate".
    file("edge.obj", "v 3e38 0 0\nv 3e38 1 0\nv 3e38 0 1\nf 1 2 3\n");
    const std::string moved =
        file("moved.json", R"({"objects": [{"model": "edge.obj", "translate": [3e38, 0, 0]}]})");
    const RunResult movedRun = render(moved);
    EXPECT_EQ(movedRun.status, 1) << movedRun.err;
    EXPECT_NE(movedRun.err.find("\"objects[0].translate\" moves the model"), std::string::npos)
        << movedRun.err;
}

// The cube scaled to 1e-30 units, seen from an eye and target 2.4e-30 apart: it is drawn.
// Catches: "the camera's eye and target are the same point" (a float length that underflows to 0).
TEST_F(CameraMessagesCli, CameraForATinyModelIsAccepted) {
    const std::string scene =
        file("tiny.json", R"({"objects": [{"model": ")" + kCube + R"(", "scale": 1e-30}]})");
    const RunResult run = render(scene + " --eye 0.5e-30,0.6e-30,2.6e-30 --target 0,0.1e-30,0");
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.err.find("nothing was drawn"), std::string::npos) << run.err;
    EXPECT_EQ(run.out.find(" 0 fragments shaded"), std::string::npos) << run.out;
}

// A triangle of 1e-40 units (subnormal float coordinates) is too small for the float transforms.
// Catches: a blank image, exit 0, with a warning that the triangle "lay outside the view".
TEST_F(CameraMessagesCli, SubnormalModelIsTooSmallToDraw) {
    const std::string model = file("tiny.obj", "v 0 0 0\nv 1e-40 0 0\nv 0 1e-40 0\nf 1 2 3\n");
    const RunResult run = render(model);
    EXPECT_EQ(run.status, 1) << run.err;
    EXPECT_NE(run.err.find("too small to draw"), std::string::npos) << run.err;
    EXPECT_EQ(run.err.find("outside the view"), std::string::npos) << run.err;
}

// A ground of ±1e6 units and the cube, the eye 5 units from the cube: the default near plane used to be
// a thousandth of the scene's size (1414), clipping away all the camera looked at.
// Catches: the default near plane of a huge scene drawing a blank image with only a warning.
TEST_F(CameraMessagesCli, HugeSceneSeenFromInsideIsDrawn) {
    file("ground.obj", "v -1e6 0 -1e6\nv 1e6 0 -1e6\nv 1e6 0 1e6\nv -1e6 0 1e6\nf 4 3 2 1\n");
    const std::string scene =
        file("huge.json", R"({"objects": [{"model": "ground.obj"}, {"model": ")" + kCube + R"("}]})");
    for (const std::string depth : {"float", "unorm16", "unorm24", "reversed-float"}) {
        const RunResult run = render(scene + " --eye 0,2,5 --target 0,0,0 --depth " + depth);
        EXPECT_EQ(run.status, 0) << depth << ": " << run.err;
        EXPECT_EQ(run.err.find("nothing was drawn"), std::string::npos) << depth << ": " << run.err;
    }
}

}  // namespace
}  // namespace facet
