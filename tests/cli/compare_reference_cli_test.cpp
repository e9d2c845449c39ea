// facet compare --reference as a user runs it: the largest differences named, --diff written.
#include <filesystem>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "cli/run_facet.h"
#include "io/image_io.h"
#include "support/bundled_models.h"

namespace facet {
namespace {

using testing_support::runFacet;
using testing_support::TempFolder;

using testing_support::kModels;

// Catches: --diff refused or ignored with --reference, or written at another size than the error
// image of a scene-sized pair (the image, plus the legend strip below from 200 px wide); the largest
// differences' section missing from the report.
TEST(CompareReferenceCli, DiffImageIsWrittenAtTheImageSize) {
    const TempFolder dir;
    for (const auto& [width, height, legend] : {std::tuple{64, 48, 0}, std::tuple{200, 150, 24}}) {
        const std::filesystem::path diff = dir.path() / ("diff-" + std::to_string(width) + ".png");
        const auto run =
            runFacet("compare '" + (kModels / "shadows.json").string() +
                         "' --reference --shadow-map-sizes 0 --width " + std::to_string(width) +
                         " --height " + std::to_string(height) + " --diff '" + diff.string() + "'",
                     dir);
        ASSERT_TRUE(run.status == 0 || run.status == 3) << run.err;
        const LinearImage image = readImage(diff);
        EXPECT_EQ(image.width, width);
        EXPECT_EQ(image.height, height + legend);
        // At 200×150 the shadows' boundaries hold pixels more than 1/255 apart (33 measured).
        if (width == 200) {
            EXPECT_NE(run.out.find("Largest differences"), std::string::npos) << run.out;
        }
    }
}

}  // namespace
}  // namespace facet
