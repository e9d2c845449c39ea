// A scene's assets: the model files its objects name, read into meshes, and the textures their materials
// name, read (with mip chains when the scene filters trilinearly). Loaded once and immutable after, so
// that every frame drawn from them (a turntable's frames, the step mode's variants, the trade's
// settings) shares them through a std::shared_ptr<const SceneAssets> instead of reading the files again.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "io/image_io.h"
#include "io/obj_import.h"
#include "pipeline/texture.h"
#include "scene/mesh.h"
#include "scene/scene.h"

namespace facet {

// Everything in a scene that decides what its assets hold: two scenes with equal options can draw from
// the same assets.
struct AssetOptions {
    std::vector<std::filesystem::path> objectModels;  // each object's model file, in the scene's order
    ObjOptions obj;                                   // how normals are computed where files give none
    bool textured = true;                             // the materials' texture maps are read at all
    bool decodeTextures = true;                       // 8- and 16-bit texels are sRGB codes, decoded
    bool mipChains = false;                           // trilinear filtering: each texture's mip chain built
    // The environment map ("environment", --environment): its file (empty: none), how its 8-bit codes
    // are read, and the key or flag that named it (for messages).
    std::filesystem::path environment;
    EnvironmentEncoding environmentEncoding = EnvironmentEncoding::Srgb;
    std::string environmentOrigin;
    TextureLimits limits;

    // Defaulted: an option added later is compared without anyone remembering to.
    bool operator==(const AssetOptions&) const = default;
};

// What `scene` needs loaded: its objects' models, its normals, and its textures' use. Colours are
// decoded under the Facet preset unless the scene says not to (docs/lighting.md); the GL preset takes
// them as written.
AssetOptions assetOptionsFor(const Scene& scene, const TextureLimits& limits = {});

struct LoadedTexture {
    std::unique_ptr<const Texture> texture;  // null: the file could not be read (a warning says why)
    bool translucent = false;                // an alpha below 1 somewhere: its parts are drawn transparent
};

struct SceneAssets {
    AssetOptions options;  // what they were loaded for
    // Each model file once, however many objects use it.
    std::map<std::filesystem::path, Mesh> models;
    // Each texture file once, however many materials name it; only those of parts that have triangles.
    std::map<std::filesystem::path, LoadedTexture> textures;
    // One line each: the importer's and coordinate precision's, per model in first use; then the
    // unreadable textures', in the order the parts name them.
    std::vector<std::string> modelWarnings, textureWarnings;
    std::size_t degenerateSkipped = 0;           // over every model file, each counted once
    std::size_t textureBytes = 0;                // every texture held, mip chains included
    std::unique_ptr<const Texture> environment;  // the environment map; null: none

    // The mesh of `file`, which options.objectModels names. Throws std::out_of_range otherwise.
    const Mesh& model(const std::filesystem::path& file) const { return models.at(file); }
    // The texture of `file`, or null when it could not be read or was not loaded.
    const LoadedTexture* texture(const std::filesystem::path& file) const;
};

// Reads every model and texture `options` names: the models in the order of the objects, then, when
// textured, each non-empty part's emission and diffuse maps in object and part order (the order in which
// the total of options.limits is spent), then the environment map. Throws InputError for a model that
// cannot be used or textures beyond the limits, and for an environment map that cannot be read; an
// unreadable material texture is a warning and is left out.
SceneAssets loadSceneAssets(const AssetOptions& options);

// The shared assets `scene` draws from.
std::shared_ptr<const SceneAssets> loadSharedAssets(const Scene& scene, const TextureLimits& limits = {});

// `assets` when they serve `scene` (loaded with the options it needs), else the scene's own, loaded now.
std::shared_ptr<const SceneAssets> assetsFor(const Scene& scene, std::shared_ptr<const SceneAssets> assets,
                                             const TextureLimits& limits = {});

}  // namespace facet
