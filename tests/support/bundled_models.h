// The models the tests load: those bundled in the source tree (models/) and the public ones beside the
// checkout (../shared/models).
#pragma once

#include <filesystem>
#include <string>

namespace facet::testing_support {

inline const std::filesystem::path kModels = std::filesystem::path(FACET_SOURCE_DIR) / "models";
// The smallest bundled model: a cube of 12 triangles.
inline const std::string kCube = FACET_SOURCE_DIR "/models/cube/cube.obj";
// Spot the cow, textured: 5,856 triangles.
inline const std::string kSpot = FACET_SOURCE_DIR "/models/spot/spot_triangulated.obj";
// The public test models beside the checkout (../shared/models).
inline const std::filesystem::path kSharedModels = FACET_SHARED_MODELS;

}  // namespace facet::testing_support
