#include "io/scene_assets.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "base/errors.h"
#include "base/memory_limit.h"
#include "base/quote.h"

namespace facet {

namespace {

// Vertices are 32-bit floats: at coordinates of 1e7 they are 1 apart. A model far from the origin
// compared with its size lands on that coarse grid, and the vertex transform's float arithmetic
// loses as much again: a warning once the grid is coarser than 1/1000 of the model's size.
std::optional<std::string> coordinatePrecisionWarning(const Mesh& mesh, const std::filesystem::path& source) {
    const glm::dvec3 low(mesh.boundsMin), high(mesh.boundsMax);
    const double size = glm::length(high - low);
    const float reach = float(std::max({std::abs(low.x), std::abs(low.y), std::abs(low.z), std::abs(high.x),
                                        std::abs(high.y), std::abs(high.z)}));
    const double spacing = std::nextafter(reach, std::numeric_limits<float>::infinity()) - reach;
    if (!(size > 0.0) || spacing * 1000.0 <= size) return std::nullopt;
    std::ostringstream message;
    message << source.string() << ": coordinates reach " << reach << " while the model is only " << size
            << " across: 32-bit floats there are " << spacing
            << " apart, so its shape and position are coarse (move the model near the origin)";
    return message.str();
}

// Whether a texture is see-through anywhere (an alpha below 1).
bool hasTranslucentTexel(const Texture& texture) {
    if (!texture.codes.empty())
        return std::any_of(texture.codes.begin(), texture.codes.end(),
                           [](const Texture::Codes& c) { return alphaFromCode(c[3]) < 1.0f; });
    return std::any_of(texture.texels.begin(), texture.texels.end(),
                       [](const vec4& t) { return t.a < 1.0f; });
}

// Each model file once, in the order the objects first name them.
void loadModels(SceneAssets& assets) {
    for (const std::filesystem::path& file : assets.options.objectModels) {
        if (assets.models.count(file)) continue;
        const Mesh& mesh = assets.models.emplace(file, loadObj(file, assets.options.obj)).first->second;
        assets.modelWarnings.insert(assets.modelWarnings.end(), mesh.warnings.begin(), mesh.warnings.end());
        assets.degenerateSkipped += mesh.stats.degenerateSkipped;
        if (std::optional<std::string> warning = coordinatePrecisionWarning(mesh, file))
            assets.modelWarnings.push_back(*warning);
    }
}

// A texture file, read once; one that cannot be read is a warning and its parts go untextured.
void loadTexture(SceneAssets& assets, const std::filesystem::path& file, const std::string& material) {
    const auto [it, first] = assets.textures.try_emplace(file);
    if (!first) return;
    const AssetOptions& options = assets.options;
    TextureRead read = readTexture(file, options.decodeTextures, options.limits,
                                   options.limits.maxTotalBytes - assets.textureBytes);
    if (read.texture.empty()) {
        assets.textureWarnings.push_back(file.string() + ": " + read.problem + "; drawing material " +
                                         inQuotes(material, '\'') + " without this texture");
        return;
    }
    auto texture = std::make_unique<Texture>(std::move(read.texture));
    // Every draw filters as the scene says: trilinear needs the mip chain, built once here (a third
    // more memory), and no other filter builds it.
    if (options.mipChains) buildMipChain(*texture);
    assets.textureBytes += texture->bytes();
    it->second.translucent = hasTranslucentTexel(*texture);
    it->second.texture = std::move(texture);
}

// The maps of every part with triangles, in the order the draws are made: object by object, part by
// part, the emission map before the diffuse one; `visit(file, material name)`.
template <class Visit>
void forEachTexture(const SceneAssets& assets, Visit visit) {
    for (const std::filesystem::path& file : assets.options.objectModels) {
        const Mesh& mesh = assets.model(file);
        for (const MeshPart& part : mesh.parts) {
            if (part.indexCount == 0) continue;
            const Material& material = mesh.materials.at(part.material);
            if (!material.emissionTexture.empty()) visit(material.emissionTexture, material.name);
            if (!material.diffuseTexture.empty()) visit(material.diffuseTexture, material.name);
        }
    }
}

// Every texture file the render reads (each once) and the environment map, whose total is checked
// from their headers before any is decoded.
std::vector<std::filesystem::path> textureFiles(const SceneAssets& assets) {
    std::vector<std::filesystem::path> files;
    if (assets.options.textured)
        forEachTexture(assets, [&](const std::filesystem::path& file, const std::string&) {
            if (std::find(files.begin(), files.end(), file) == files.end()) files.push_back(file);
        });
    if (!assets.options.environment.empty()) files.push_back(assets.options.environment);
    return files;
}

void loadTextures(SceneAssets& assets) {
    forEachTexture(assets, [&](const std::filesystem::path& file, const std::string& material) {
        loadTexture(assets, file, material);
    });
}

// The environment map: a file that cannot be read is an error naming it and the key (or flag) that
// named it. "linear" 8-bit codes are code/255 as they are; float data is linear either way.
void loadEnvironment(SceneAssets& assets) {
    const AssetOptions& options = assets.options;
    TextureRead read = readTexture(options.environment, true, options.limits,
                                   options.limits.maxTotalBytes - assets.textureBytes);
    if (read.texture.empty())
        throw InputError(options.environment.string() + ": " + read.problem + " (the environment map, " +
                         options.environmentOrigin + ")");
    auto texture = std::make_unique<Texture>(std::move(read.texture));
    if (options.environmentEncoding == EnvironmentEncoding::Linear)
        for (int c = 0; c < 256; ++c)
            texture->colorFromCode[c] = static_cast<float>(c) * (1.0f / 255.0f);
    assets.textureBytes += texture->bytes();
    assets.environment = std::move(texture);
}

}  // namespace

AssetOptions assetOptionsFor(const Scene& scene, const TextureLimits& limits) {
    AssetOptions options;
    for (const ObjectSpec& object : scene.objects)
        options.objectModels.push_back(object.model);
    options.obj = {.creaseAngleDegrees = scene.lighting.creaseAngleDegrees,
                   .normals = scene.lighting.normals};
    options.textured = scene.textures.maps == TextureMaps::On;
    // Facet: colours are sRGB-encoded as written (unless "gamma": {"decode_inputs": false}); GL: taken
    // as given (OpenGL 1.x knows no gamma).
    options.decodeTextures = scene.lighting.preset != LightingPreset::GL && scene.gamma.decodeInputs;
    options.mipChains = scene.textures.filter == TextureFilter::Trilinear;
    if (scene.environment) {
        options.environment = scene.environment->image;
        options.environmentEncoding = scene.environment->encoding;
        options.environmentOrigin = scene.environment->origin;
    }
    options.limits = limits;
    return options;
}

const LoadedTexture* SceneAssets::texture(const std::filesystem::path& file) const {
    const auto it = textures.find(file);
    return it == textures.end() || !it->second.texture ? nullptr : &it->second;
}

SceneAssets loadSceneAssets(const AssetOptions& options) {
    SceneAssets assets;
    assets.options = options;
    loadModels(assets);
    checkTextureTotal(textureFiles(assets), options.limits);
    const MemoryUse use("loading textures");
    if (options.textured) loadTextures(assets);
    if (!options.environment.empty()) loadEnvironment(assets);
    return assets;
}

std::shared_ptr<const SceneAssets> loadSharedAssets(const Scene& scene, const TextureLimits& limits) {
    return std::make_shared<const SceneAssets>(loadSceneAssets(assetOptionsFor(scene, limits)));
}

std::shared_ptr<const SceneAssets> assetsFor(const Scene& scene, std::shared_ptr<const SceneAssets> assets,
                                             const TextureLimits& limits) {
    if (assets && assets->options == assetOptionsFor(scene, limits)) return assets;
    return loadSharedAssets(scene, limits);
}

}  // namespace facet
