#include "renderer.h"

#include <algorithm>
#include <map>
#include <unordered_map>

#include "color.h"
#include "errors.h"
#include "obj_import.h"

namespace facet {

namespace {

vec3 decodeSrgb(vec3 encoded) {
    return {srgbToLinear(encoded.r), srgbToLinear(encoded.g), srgbToLinear(encoded.b)};
}

Bounds transformedBounds(const Mesh& mesh, const mat4& worldFromObject) {
    Bounds b{vec3(std::numeric_limits<float>::max()), vec3(std::numeric_limits<float>::lowest())};
    for (int corner = 0; corner < 8; ++corner) {
        const vec3 p((corner & 1) ? mesh.boundsMax.x : mesh.boundsMin.x,
                     (corner & 2) ? mesh.boundsMax.y : mesh.boundsMin.y,
                     (corner & 4) ? mesh.boundsMax.z : mesh.boundsMin.z);
        const vec3 world = vec3(worldFromObject * vec4(p, 1.0f));
        b.min = min(b.min, world);
        b.max = max(b.max, world);
    }
    return b;
}

ShaderMaterial shaderMaterial(const Material& file, const MaterialOverride& override) {
    ShaderMaterial m;
    m.ambient = decodeSrgb(override.ambient.value_or(file.ambient));
    m.diffuse = decodeSrgb(override.diffuse.value_or(file.diffuse));
    m.specular = decodeSrgb(override.specular.value_or(file.specular));
    m.emission = decodeSrgb(override.emission.value_or(file.emission));
    m.shininess = override.shininess.value_or(file.shininess);
    m.opacity = override.opacity.value_or(file.opacity);
    return m;
}

// Splits one part of a mesh into its own vertex array, so its draw shades only the vertices it uses.
void extractPart(const Mesh& mesh, const MeshPart& part, PreparedDraw& draw) {
    std::unordered_map<std::uint32_t, std::uint32_t> local;
    local.reserve(part.indexCount);
    draw.indices.reserve(part.indexCount);
    for (std::uint32_t k = part.firstIndex; k < part.firstIndex + part.indexCount; ++k) {
        const std::uint32_t global = mesh.indices[k];
        auto [it, inserted] = local.try_emplace(global, static_cast<std::uint32_t>(draw.vertices.size()));
        if (inserted) draw.vertices.push_back(mesh.vertices[global]);
        draw.indices.push_back(it->second);
    }
}

}  // namespace

PreparedScene prepareScene(const Scene& scene) {
    PreparedScene prepared;
    prepared.scene = scene;
    if (scene.width < 1 || scene.height < 1 || scene.width > kMaxImageSide || scene.height > kMaxImageSide)
        throw InputError(scene.source.string() + ": image size " + std::to_string(scene.width) + "x" +
                         std::to_string(scene.height) + " is outside 1.." + std::to_string(kMaxImageSide));
    if (scene.objects.empty())
        throw InputError(scene.source.string() + ": the scene has no objects to render");

    // Load each model once, even if several objects use it.
    std::map<std::filesystem::path, std::unique_ptr<Mesh>> meshes;
    std::map<std::filesystem::path, Texture*> textures;
    Bounds sceneBounds{vec3(std::numeric_limits<float>::max()), vec3(std::numeric_limits<float>::lowest())};
    for (const ObjectSpec& object : scene.objects) {
        auto& mesh = meshes[object.model];
        if (!mesh) {
            mesh = std::make_unique<Mesh>(loadObj(object.model));
            prepared.warnings.insert(prepared.warnings.end(), mesh->warnings.begin(), mesh->warnings.end());
            prepared.degenerateSkipped += mesh->stats.degenerateSkipped;
        }
        const Bounds b = transformedBounds(*mesh, object.worldFromObject);
        sceneBounds.min = min(sceneBounds.min, b.min);
        sceneBounds.max = max(sceneBounds.max, b.max);
    }

    // Camera.
    const float aspect = static_cast<float>(scene.width) / static_cast<float>(scene.height);
    prepared.camera = frameCamera(scene.camera, sceneBounds, aspect);
    const Camera& camera = prepared.camera;
    const mat4 worldFromView = inverse(camera.viewFromWorld);

    // Lights, in world space; without any, one white key light from the upper left, behind the viewer.
    std::vector<LightSpec> lights = scene.lights;
    if (lights.empty()) {
        LightSpec key;
        key.type = LightType::Directional;
        key.direction = vec3(0.45f, -0.55f, -1.0f);
        key.cameraRelative = true;
        lights.push_back(key);
    }
    if (lights.size() > static_cast<std::size_t>(kMaxLights))
        throw InputError(scene.source.string() + ": " + std::to_string(lights.size()) +
                         " lights given, at most " + std::to_string(kMaxLights) + " are supported");
    BlinnPhongShader::Uniforms common;
    common.eyeWorld = camera.eye;
    common.globalAmbient = decodeSrgb(scene.ambientLight);
    common.lightCount = static_cast<int>(lights.size());
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const LightSpec& l = lights[i];
        ShaderLight& out = common.lights[i];
        out.color = decodeSrgb(l.color) * l.intensity;
        if (l.type == LightType::Directional) {
            vec3 d = normalize(l.direction);
            if (l.cameraRelative) d = normalize(vec3(worldFromView * vec4(d, 0.0f)));
            out.positionOrDirection = vec4(d, 0.0f);
        } else {
            const vec3 p = l.cameraRelative ? vec3(worldFromView * vec4(l.position, 1.0f)) : l.position;
            out.positionOrDirection = vec4(p, 1.0f);
        }
    }

    // One draw per (object, material part).
    for (const ObjectSpec& object : scene.objects) {
        const Mesh& mesh = *meshes[object.model];
        BlinnPhongShader::Uniforms uniforms = common;
        uniforms.worldFromObject = object.worldFromObject;
        uniforms.clipFromObject = camera.clipFromView * camera.viewFromWorld * object.worldFromObject;
        uniforms.normalFromObject = transpose(inverse(mat3(object.worldFromObject)));
        for (const MeshPart& part : mesh.parts) {
            if (part.indexCount == 0) continue;
            PreparedDraw draw;
            draw.uniforms = uniforms;
            const Material& material = mesh.materials.at(part.material);
            draw.uniforms.material = shaderMaterial(material, object.material);
            if (!material.diffuseTexture.empty()) {
                Texture*& texture = textures[material.diffuseTexture];
                if (!texture) {
                    const LinearImage image = readImage(material.diffuseTexture);
                    auto owned = std::make_unique<Texture>();
                    owned->width = image.width;
                    owned->height = image.height;
                    owned->texels = image.pixels;
                    texture = owned.get();
                    prepared.textures.push_back(std::move(owned));
                }
                draw.uniforms.material.diffuseMap = texture;
            }
            extractPart(mesh, part, draw);
            prepared.triangleCount += draw.indices.size() / 3;
            prepared.draws.push_back(std::move(draw));
        }
    }

    // Pipeline state.
    DrawState& state = prepared.state;
    state.viewport = {0, 0, scene.width, scene.height};
    switch (scene.pipeline.cull) {
        case CullChoice::Back:
            state.raster.cull = CullMode::Back;
            break;
        case CullChoice::Front:
            state.raster.cull = CullMode::Front;
            break;
        case CullChoice::None:
            state.raster.cull = CullMode::None;
            break;
    }
    state.raster.subpixelBits = scene.pipeline.subpixelBits;
    state.interpolation = scene.pipeline.interpolation == InterpolationChoice::Affine
                              ? Interpolation::Affine
                              : Interpolation::PerspectiveCorrect;
    prepared.clearColor = vec4(decodeSrgb(vec3(scene.background)), scene.background.a);
    return prepared;
}

DrawStats renderFrame(const PreparedScene& prepared, Framebuffer& target, DrawContext& context) {
    target.clear(prepared.clearColor, 1.0f, context.pool);
    DrawStats total;
    for (const PreparedDraw& d : prepared.draws)
        total += draw<BlinnPhongShader>(prepared.state, d.uniforms, std::span<const MeshVertex>(d.vertices),
                                        std::span<const std::uint32_t>(d.indices), target, context);
    return total;
}

LinearImage toImage(const Framebuffer& framebuffer) {
    LinearImage image;
    image.width = framebuffer.width();
    image.height = framebuffer.height();
    image.pixels = framebuffer.colorPixels();
    return image;
}

}  // namespace facet
