#include "renderer.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
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

// The standard equation's material: the MTL values with the scene's overrides, decoded.
template <class Decode>
PhongMaterial phongMaterial(const Material& file, const MaterialOverride& override, Decode decode) {
    PhongMaterial m;
    m.ambient = decode(override.ambient.value_or(file.ambient));
    m.diffuse = decode(override.diffuse.value_or(file.diffuse));
    m.specular = decode(override.specular.value_or(file.specular));
    m.emission = decode(override.emission.value_or(file.emission));
    m.shininess = override.shininess.value_or(file.shininess);
    return m;
}

// Cook-Torrance's material. From the MTL: the diffuse colour as base colour, a dielectric (F0 = 0.04),
// and the roughness whose Beckmann lobe matches the Phong exponent Ns: α = √(2/(Ns + 2)) (Walter et al.
// 2007, eq. 8 inverted), roughness = √α. Then the preset, then the scene's explicit keys.
template <class Decode>
PbrMaterial pbrMaterial(const PhongMaterial& phong, const MaterialOverride& override, Decode decode,
                        const std::filesystem::path& source) {
    PbrMaterial m;
    m.baseColor = phong.diffuse;
    m.metalness = 0.0f;
    m.roughness = std::sqrt(std::sqrt(2.0f / (std::max(phong.shininess, 0.0f) + 2.0f)));
    m.f0 = vec3(0.04f);
    if (override.preset) {
        const std::optional<MaterialPreset> preset = findMaterialPreset(*override.preset);
        if (!preset)
            throw InputError(source.string() + ": unknown material preset \"" + *override.preset + "\"");
        if (preset->metal) {
            m.baseColor = preset->f0;  // linear already: measured reflectances
            m.metalness = 1.0f;
        } else {
            m.f0 = preset->f0;
        }
    }
    if (override.baseColor) m.baseColor = decode(*override.baseColor);
    if (override.metalness) m.metalness = *override.metalness;
    if (override.roughness) m.roughness = *override.roughness;
    if (override.f0) m.f0 = *override.f0;
    return m;
}

// One vertex per triangle corner, each with its face's normal: flat shading's input. The face normal
// is the cross product of two edges, turned to agree with the corners' own normals (so a model whose
// winding disagrees with its normals still lights the side its normals show).
void unweldWithFaceNormals(PreparedDraw& draw) {
    std::vector<MeshVertex> corners;
    corners.reserve(draw.indices.size());
    for (std::size_t t = 0; t + 2 < draw.indices.size(); t += 3) {
        const MeshVertex& a = draw.vertices[draw.indices[t]];
        const MeshVertex& b = draw.vertices[draw.indices[t + 1]];
        const MeshVertex& c = draw.vertices[draw.indices[t + 2]];
        vec3 n = cross(b.position - a.position, c.position - a.position);
        if (dot(n, a.normal + b.normal + c.normal) < 0.0f) n = -n;
        const float length = glm::length(n);
        n = length > 0.0f && std::isfinite(length) ? n / length : normalize(a.normal + b.normal + c.normal);
        for (const MeshVertex* v : {&a, &b, &c})
            corners.push_back({v->position, n, v->uv});
    }
    draw.vertices = std::move(corners);
    for (std::size_t k = 0; k < draw.indices.size(); ++k)
        draw.indices[k] = static_cast<std::uint32_t>(k);
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

    const bool glPreset = scene.lighting.preset == LightingPreset::GL;
    // Facet: colours are sRGB-encoded as written; GL: taken as given (OpenGL 1.x knows no gamma).
    const auto decode = [glPreset](vec3 c) { return glPreset ? c : decodeSrgb(c); };

    // Load each model once, even if several objects use it.
    std::map<std::filesystem::path, std::unique_ptr<Mesh>> meshes;
    std::map<std::filesystem::path, Texture*> textures;
    Bounds sceneBounds{vec3(std::numeric_limits<float>::max()), vec3(std::numeric_limits<float>::lowest())};
    for (const ObjectSpec& object : scene.objects) {
        auto& mesh = meshes[object.model];
        if (!mesh) {
            mesh =
                std::make_unique<Mesh>(loadObj(object.model, ObjOptions{scene.lighting.creaseAngleDegrees}));
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

    // Lights, in eye space; without any, one white key light from the upper left, behind the viewer.
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
    SurfaceUniforms common;
    common.globalAmbient = decode(scene.ambientLight);
    common.lightCount = static_cast<int>(lights.size());
    common.brdf = scene.lighting.brdf;
    common.twoSidedFlip = !glPreset;
    common.clampColor = glPreset;
    const mat4& viewFromWorld = camera.viewFromWorld;
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const LightSpec& l = lights[i];
        LightParams& out = common.lights[i];
        const auto toView = [&](vec3 v, float w) {
            return l.cameraRelative ? v : vec3(viewFromWorld * vec4(v, w));
        };
        out.kind = l.type == LightType::Directional ? LightKind::Directional
                   : l.type == LightType::Point     ? LightKind::Point
                                                    : LightKind::Spot;
        if (out.kind == LightKind::Directional) out.direction = normalize(toView(l.direction, 0.0f));
        if (out.kind == LightKind::Spot) out.spotDirection = normalize(toView(l.direction, 0.0f));
        if (out.kind != LightKind::Directional) out.position = toView(l.position, 1.0f);
        out.ambient = decode(l.ambient.value_or(vec3(0.0f))) * l.intensity;
        out.diffuse = decode(l.diffuse.value_or(l.color)) * l.intensity;
        out.specular = decode(l.specular.value_or(l.color)) * l.intensity;
        out.c0 = l.attenuation.x;
        out.c1 = l.attenuation.y;
        out.c2 = l.attenuation.z;
        out.spotCutoffDegrees = out.kind == LightKind::Spot ? l.spotCutoffDegrees : 180.0f;
        out.spotExponent = l.spotExponent;
        if (l.spotInnerDegrees && l.spotOuterDegrees) {
            out.spotProfile = SpotProfile::Smooth;
            out.spotInnerDegrees = *l.spotInnerDegrees;
            out.spotOuterDegrees = *l.spotOuterDegrees;
        }
    }

    // One draw per (object, material part).
    for (const ObjectSpec& object : scene.objects) {
        const Mesh& mesh = *meshes[object.model];
        SurfaceUniforms uniforms = common;
        uniforms.viewFromObject = viewFromWorld * object.worldFromObject;
        uniforms.clipFromObject = camera.clipFromView * uniforms.viewFromObject;
        uniforms.normalFromObject = transpose(inverse(mat3(uniforms.viewFromObject)));
        uniforms.reflection = object.reflection.value_or(
            object.material.physicallyBased() ? ReflectionModel::CookTorrance : scene.lighting.model);
        const ShadingFrequency frequency = object.shading.value_or(scene.lighting.shadingOrDefault());
        for (const MeshPart& part : mesh.parts) {
            if (part.indexCount == 0) continue;
            PreparedDraw draw;
            draw.uniforms = uniforms;
            draw.frequency = frequency;
            const Material& material = mesh.materials.at(part.material);
            draw.uniforms.material = phongMaterial(material, object.material, decode);
            draw.uniforms.pbr = pbrMaterial(draw.uniforms.material, object.material, decode, scene.source);
            draw.uniforms.opacity = object.material.opacity.value_or(material.opacity);
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
                draw.uniforms.diffuseMap = texture;
            }
            extractPart(mesh, part, draw);
            // Flat shading lights each face with its own normal; the GL preset keeps OpenGL's rule
            // instead: the provoking vertex's colour, lit with that vertex's normal.
            if (frequency == ShadingFrequency::Flat && !glPreset) unweldWithFaceNormals(draw);
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
    state.raster.provokingVertex = ProvokingVertex::Last;  // OpenGL's convention
    prepared.clearColor = vec4(decode(vec3(scene.background)), scene.background.a);
    prepared.encoding = glPreset ? kLinearEncoding : kSrgbEncoding;
    return prepared;
}

namespace {

template <ShadingFrequency kFrequency>
DrawStats drawSurface(const PreparedScene& prepared, const PreparedDraw& d, const SurfaceUniforms& uniforms,
                      Framebuffer& target, DrawContext& context) {
    return draw<SurfaceShader<kFrequency>>(prepared.state, uniforms, std::span<const MeshVertex>(d.vertices),
                                           std::span<const std::uint32_t>(d.indices), target, context);
}

}  // namespace

DrawStats renderFrame(const PreparedScene& prepared, Framebuffer& target, DrawContext& context,
                      std::uint8_t terms) {
    target.clear(prepared.clearColor, 1.0f, context.pool);
    DrawStats total;
    for (const PreparedDraw& d : prepared.draws) {
        const SurfaceUniforms* uniforms = &d.uniforms;
        SurfaceUniforms selected;
        if (terms != kAllTerms) {
            selected = d.uniforms;
            selected.terms = terms;
            uniforms = &selected;
        }
        switch (d.frequency) {
            case ShadingFrequency::Flat:
                total += drawSurface<ShadingFrequency::Flat>(prepared, d, *uniforms, target, context);
                break;
            case ShadingFrequency::Gouraud:
                total += drawSurface<ShadingFrequency::Gouraud>(prepared, d, *uniforms, target, context);
                break;
            case ShadingFrequency::Phong:
                total += drawSurface<ShadingFrequency::Phong>(prepared, d, *uniforms, target, context);
                break;
        }
    }
    return total;
}

GlScene toGlScene(const PreparedScene& prepared) {
    GlScene gl;
    gl.width = prepared.scene.width;
    gl.height = prepared.scene.height;
    gl.clearColor = prepared.clearColor;
    gl.clipFromView = prepared.camera.clipFromView;
    gl.cullBackFaces = prepared.state.raster.cull == CullMode::Back;
    if (prepared.state.raster.cull == CullMode::Front)
        throw std::invalid_argument("OpenGL comparison: front-face culling is not mirrored");
    const bool glPreset = prepared.scene.lighting.preset == LightingPreset::GL;
    if (!prepared.draws.empty()) {
        const SurfaceUniforms& u = prepared.draws.front().uniforms;
        gl.globalAmbient = u.globalAmbient;
        gl.lights.assign(u.lights.begin(), u.lights.begin() + u.lightCount);
        gl.brdf = u.brdf;
        gl.twoSidedFlip = u.twoSidedFlip;
    }
    const bool smoothSpot = std::any_of(gl.lights.begin(), gl.lights.end(), [](const LightParams& l) {
        return l.kind == LightKind::Spot && l.spotProfile == SpotProfile::Smooth;
    });
    for (const PreparedDraw& d : prepared.draws) {
        GlDraw out;
        out.vertices = d.vertices;
        out.indices = d.indices;
        out.viewFromObject = d.uniforms.viewFromObject;
        out.normalFromObject = d.uniforms.normalFromObject;
        out.reflection = d.uniforms.reflection;
        out.frequency = d.frequency;
        out.material = d.uniforms.material;
        out.pbr = d.uniforms.pbr;
        out.diffuseMap = d.uniforms.diffuseMap;
        out.clampColor = d.uniforms.clampColor;
        // OpenGL 1.x itself where it can say the same: the GL preset's per-vertex Blinn-Phong.
        const bool fixedFunction = glPreset && d.frequency != ShadingFrequency::Phong &&
                                   d.uniforms.reflection == ReflectionModel::BlinnPhong && !smoothSpot &&
                                   d.uniforms.material.shininess <= 128.0f;
        out.program = fixedFunction                            ? GlProgram::FixedFunction
                      : d.frequency == ShadingFrequency::Phong ? GlProgram::PerPixel
                                                               : GlProgram::PerVertex;
        gl.draws.push_back(std::move(out));
    }
    return gl;
}

LinearImage toImage(const Framebuffer& framebuffer) {
    LinearImage image;
    image.width = framebuffer.width();
    image.height = framebuffer.height();
    image.pixels = framebuffer.colorPixels();
    return image;
}

}  // namespace facet
