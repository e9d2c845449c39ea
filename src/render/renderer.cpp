#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <unordered_map>

#include "base/errors.h"
#include "base/memory_limit.h"
#include "base/quote.h"
#include "pipeline/color.h"
#include "render/draw_geometry.h"
#include "render/shadow_maps.h"

#include <glm/gtc/matrix_transform.hpp>

namespace facet {

// The normal matrix of an object placed at viewFromObject: see renderer.h.
NormalMatrix normalMatrix(const glm::dmat4& viewFromObject) {
    NormalMatrix n;
    n.inverseTranspose = glm::transpose(glm::inverse(glm::dmat3(viewFromObject)));
    n.determinant = glm::determinant(n.inverseTranspose);
    n.scaled = n.inverseTranspose;
    if (n.determinant != 0.0 && std::isfinite(n.determinant)) n.scaled /= std::cbrt(std::abs(n.determinant));
    return n;
}

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

// OpenGL 1.x's initial material (glMaterial, OpenGL 2.1 Table 2.11): ambient 0.2, diffuse 0.8, specular
// 0, emission 0, shininess 0; what the gl preset lights faces with when the file gives them none.
Material glDefaultMaterial() {
    Material m;
    m.name = "OpenGL default";
    m.ambient = vec3(0.2f);
    m.diffuse = vec3(0.8f);
    m.specular = vec3(0.0f);
    m.emission = vec3(0.0f);
    m.shininess = 0.0f;
    m.fallback = true;
    return m;
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
// 2007, eq. 8 inverted), roughness = √α, and the index of refraction Ni when it is above 1 (F0 from
// it; exporters write Ni 1 for "none"). Then the preset, then the scene's explicit keys: f0 replaces
// the IOR's F0 and drops the IOR, ior replaces both.
template <class Decode>
PbrMaterial pbrMaterial(const Material& file, const PhongMaterial& phong, const MaterialOverride& override,
                        Decode decode, const std::filesystem::path& source) {
    PbrMaterial m;
    m.baseColor = phong.diffuse;
    m.metalness = 0.0f;
    m.roughness = std::sqrt(std::sqrt(2.0f / (std::max(phong.shininess, 0.0f) + 2.0f)));
    m.f0 = vec3(0.04f);
    if (file.ior > 1.0f) {
        m.ior = file.ior;
        m.f0 = vec3(f0FromEta(file.ior));
    }
    if (override.preset) {
        const std::optional<MaterialPreset> preset = findMaterialPreset(*override.preset);
        if (!preset)
            throw InputError(source.string() + ": unknown material preset \"" + *override.preset + "\"");
        if (preset->metal) {
            m.baseColor = preset->f0;  // linear already: measured reflectances
            m.metalness = 1.0f;
        } else {
            m.f0 = preset->f0;
            m.ior = 0.0f;
        }
    }
    if (override.baseColor) m.baseColor = decode(*override.baseColor);
    if (override.metalness) m.metalness = *override.metalness;
    if (override.roughness) m.roughness = *override.roughness;
    if (override.f0) {
        m.f0 = *override.f0;
        m.ior = 0.0f;
    }
    if (override.ior) {
        m.ior = *override.ior;
        m.f0 = vec3(f0FromEta(*override.ior));
    }
    if (override.anisotropy) m.anisotropy = *override.anisotropy;
    return m;
}

// The scene's fog for the shaders. Linear fog without start and end spans the bounding sphere: from
// its nearest point to the eye to its farthest.
template <class Decode>
FogParams fogParams(const Scene& scene, const Bounds& bounds, const Camera& camera, Decode decode) {
    FogParams fog;
    fog.mode = scene.fog.mode;
    fog.color = decode(scene.fog.color);
    fog.density = scene.fog.density;
    fog.distance = scene.fog.distance;
    // In double: the squared distances of a 1e30 model overflow float.
    const glm::dvec3 centre = 0.5 * (glm::dvec3(bounds.min) + glm::dvec3(bounds.max));
    const double radius = 0.5 * glm::length(glm::dvec3(bounds.max) - glm::dvec3(bounds.min));
    const double distance = glm::length(glm::dvec3(camera.eye) - centre);
    double start = scene.fog.start ? double(*scene.fog.start) : std::max(distance - radius, 0.0);
    double end = scene.fog.end ? double(*scene.fog.end) : distance + radius;
    // One end given, the other derived on its wrong side: keep the given one and a range of the
    // sphere's diameter.
    if (end <= start) {
        if (scene.fog.start)
            end = start + 2.0 * radius;
        else
            start = std::max(end - 2.0 * radius, 0.0);
    }
    // Eye space is world space times viewScale: distances scale with it, densities inversely.
    fog.start = float(start * camera.viewScale);
    fog.end = float(end * camera.viewScale);
    fog.density = float(fog.density / camera.viewScale);
    // Height fog: heights along the world's up, measured in eye-space units from the world's origin.
    const glm::dvec3 up = glm::normalize(glm::dvec3(scene.fog.up));
    fog.falloff = float(scene.fog.falloff / camera.viewScale);
    fog.baseHeight = float(scene.fog.baseHeight * camera.viewScale);
    fog.up = vec3(glm::normalize(glm::dmat3(camera.viewFromWorldExact) * up));
    fog.eyeHeight = float(glm::dot(glm::dvec3(camera.eye), up) * camera.viewScale);
    return fog;
}

// The environment map as the shaders read it: eye-space directions turned to world space (the view's
// rotation undone), then by the map's rotation about +y.
EnvironmentParams environmentParams(const Scene& scene, const SceneAssets& assets, const Camera& camera) {
    EnvironmentParams env;
    if (!scene.environment || !assets.environment) return env;
    env.map = assets.environment.get();
    env.intensity = scene.environment->intensity;
    const glm::dmat3 worldFromEye = glm::inverse(glm::dmat3(camera.viewFromWorldExact)) * camera.viewScale;
    const glm::dmat3 turn(glm::rotate(glm::dmat4(1.0),
                                      glm::radians(-double(scene.environment->rotationDegrees)),
                                      glm::dvec3(0.0, 1.0, 0.0)));
    env.mapFromEye = mat3(turn * worldFromEye);
    return env;
}

// The draw's matrices for an object placed by `worldFromObject`: composed in double with the camera's
// and rounded to float once, so that a model far from the origin or of extreme size (1e30, 1e-30)
// keeps its precision. The normal matrix is scaled to determinant 1: the shaders renormalise
// normals, and a matrix of a scaled view would otherwise shrink them to nothing.
void placeDraw(SurfaceUniforms& u, const Camera& camera, const glm::dmat4& worldFromObject) {
    const glm::dmat4 viewFromObject = camera.viewFromWorldExact * worldFromObject;
    u.viewFromObject = mat4(viewFromObject);
    u.clipFromObject = mat4(drawnClipFromView(camera) * viewFromObject);
    u.normalFromObject = mat3(normalMatrix(viewFromObject).scaled);
}

// One vertex per triangle corner, each with its face's normal: flat shading's input. The face normal
// is the cross product of two edges, turned to agree with the corners' own normals (so a model whose
// winding disagrees with its normals still lights the side its normals show).
void unweldWithFaceNormals(DrawTriangles& draw) {
    std::vector<MeshVertex> corners;
    corners.reserve(draw.indices.size());
    for (std::size_t t = 0; t + 2 < draw.indices.size(); t += 3) {
        const MeshVertex& a = draw.vertices[draw.indices[t]];
        const MeshVertex& b = draw.vertices[draw.indices[t + 1]];
        const MeshVertex& c = draw.vertices[draw.indices[t + 2]];
        const vec3 n = flatFaceNormal(a, b, c);
        for (const MeshVertex* v : {&a, &b, &c})
            corners.push_back({v->position, n, v->uv});
    }
    draw.vertices = std::move(corners);
    for (std::size_t k = 0; k < draw.indices.size(); ++k)
        draw.indices[k] = static_cast<std::uint32_t>(k);
}

// Splits one part of a mesh into its own vertex array, so its draw shades only the vertices it uses.
DrawTriangles extractPart(const Mesh& mesh, const MeshPart& part) {
    DrawTriangles draw;
    std::unordered_map<std::uint32_t, std::uint32_t> local;
    local.reserve(part.indexCount);
    draw.indices.reserve(part.indexCount);
    for (std::uint32_t k = part.firstIndex; k < part.firstIndex + part.indexCount; ++k) {
        const std::uint32_t global = mesh.indices[k];
        auto [it, inserted] = local.try_emplace(global, static_cast<std::uint32_t>(draw.vertices.size()));
        if (inserted) draw.vertices.push_back(mesh.vertices[global]);
        draw.indices.push_back(it->second);
    }
    return draw;
}

// The colours a user writes, as the lighting takes them: decoded from sRGB (Facet preset, unless the
// scene says not to) or as written.
struct ColourDecoding {
    bool decode = true;
    vec3 operator()(vec3 c) const { return decode ? decodeSrgb(c) : c; }
};

std::string numberText(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

// An object whose "scale" or "translate" takes its model beyond the largest float (a scale of 1e30 on
// a model of 1e20 units) has no position the pipeline can draw in: refused here, naming the key the
// user gave, before the framing meets an infinite box (and would speak of NaN near and far planes).
// In double, where 1e50 is still a number: the key to blame is the scale when the model's corners
// overflow before they are moved, else the translation.
void checkPlacementFits(const Scene& scene, std::size_t index, const Mesh& mesh) {
    const double largest = std::numeric_limits<float>::max();
    const glm::dmat4 m(scene.objects[index].worldFromObject);
    double modelReach = 0.0, scaledReach = 0.0, placedReach = 0.0;  // the largest |coordinate|
    const auto reach = [](glm::dvec3 p) { return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}); };
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p((corner & 1) ? mesh.boundsMax.x : mesh.boundsMin.x,
                           (corner & 2) ? mesh.boundsMax.y : mesh.boundsMin.y,
                           (corner & 4) ? mesh.boundsMax.z : mesh.boundsMin.z);
        const glm::dvec3 scaled = glm::dmat3(m) * p;
        modelReach = std::max(modelReach, reach(p));
        scaledReach = std::max(scaledReach, reach(scaled));
        placedReach = std::max(placedReach, reach(scaled + glm::dvec3(m[3])));
    }
    if (placedReach <= largest) return;
    const bool scaleOverflows = scaledReach > largest;
    const std::string key = scaleOverflows ? "scale" : "translate";
    throw InputError(scene.source.string() + ": " +
                     inQuotes("objects[" + std::to_string(index) + "]." + key) +
                     (scaleOverflows ? " scales the model " : " moves the model ") +
                     scene.objects[index].model.string() + " (coordinates up to " + numberText(modelReach) +
                     ") out to " + numberText(placedReach) + ", beyond the largest 32-bit float (" +
                     numberText(largest) + "): nothing could be drawn; give a smaller " + inQuotes(key));
}

// The box around every object as placed.
Bounds sceneBounds(const Scene& scene, const SceneAssets& assets) {
    Bounds bounds{vec3(std::numeric_limits<float>::max()), vec3(std::numeric_limits<float>::lowest())};
    for (std::size_t i = 0; i < scene.objects.size(); ++i)
        checkPlacementFits(scene, i, assets.model(scene.objects[i].model));
    for (const ObjectSpec& object : scene.objects) {
        const Bounds b = transformedBounds(assets.model(object.model), object.worldFromObject);
        bounds.min = min(bounds.min, b.min);
        bounds.max = max(bounds.max, b.max);
    }
    return bounds;
}

// Every object copies its model's vertices into its draws: the total is bounded before they are made.
void checkTriangleLimit(const Scene& scene, const SceneAssets& assets) {
    std::size_t sceneTriangles = 0;
    for (const ObjectSpec& object : scene.objects)
        sceneTriangles += assets.model(object.model).stats.trianglesKept;
    if (sceneTriangles > kMaxSceneTriangles)
        throw InputError(scene.source.string() + ": the scene draws " + std::to_string(sceneTriangles) +
                         " triangles (each object counts its model's), more than the limit of " +
                         std::to_string(kMaxSceneTriangles) + "; use fewer objects or lighter models");
}

Camera sceneCamera(const Scene& scene, const Bounds& bounds) {
    const float aspect = static_cast<float>(scene.width) / static_cast<float>(scene.height);
    try {
        return frameCamera(scene.camera, bounds, aspect, scene.pipeline.depth);
    } catch (const InputError& e) {
        throw InputError(scene.source.string() + ": " + e.what());
    }
}

// The scene's lights; without any, one white key light from the upper left, behind the viewer.
std::vector<LightSpec> sceneLights(const Scene& scene) {
    std::vector<LightSpec> lights = scene.lights;
    if (lights.empty()) {
        LightSpec key;
        key.type = LightKind::Directional;
        key.direction = vec3(0.45f, -0.55f, -1.0f);
        key.cameraRelative = true;
        lights.push_back(key);
    }
    if (lights.size() > static_cast<std::size_t>(kMaxLights))
        throw InputError(scene.source.string() + ": " + std::to_string(lights.size()) +
                         " lights given, at most " + std::to_string(kMaxLights) + " are supported");
    return lights;
}

// A light as the shaders take it: in eye space, its colours decoded and scaled by its intensity.
LightParams eyeSpaceLight(const LightSpec& l, const Camera& camera, ColourDecoding decode) {
    const double s = camera.viewScale;
    // Camera-relative lights are given in world units: eye space is scaled by viewScale.
    const auto toViewExact = [&](glm::dvec3 v, double w) {
        return l.cameraRelative ? v * s : glm::dvec3(camera.viewFromWorldExact * glm::dvec4(v, w));
    };
    const auto toView = [&](vec3 v, float w) { return vec3(toViewExact(glm::dvec3(v), double(w))); };
    // A direction is made unit length in double after the view's scale (2^-100 for a 1e30 model):
    // normalising the scaled vector in float would square components of 1e-30 to 0, or of 1e30 to +inf,
    // and give NaN (an unlit model).
    const auto directionToView = [&](const glm::dvec3& d) {
        return vec3(glm::normalize(toViewExact(d, 0.0)));
    };
    LightParams out;
    out.kind = l.type;
    // Made unit length in double first: in float, the squared length of [0, -1e-30, 0] underflows
    // to 0 and that of [-3e38, 0, 0] overflows, and normalize would give NaN (a black image).
    const glm::dvec3 direction = glm::normalize(glm::dvec3(l.direction));
    if (out.kind == LightKind::Directional) out.direction = directionToView(direction);
    if (out.kind == LightKind::Spot) out.spotDirection = directionToView(direction);
    if (out.kind != LightKind::Directional) out.position = toView(l.position, 1.0f);
    out.ambient = decode(l.ambient.value_or(vec3(0.0f))) * l.intensity;
    out.diffuse = decode(l.diffuse.value_or(l.color)) * l.intensity;
    out.specular = decode(l.specular.value_or(l.color)) * l.intensity;
    // att = 1/(c0 + c1·d + c2·d²) with d in world units, d = d_eye / viewScale.
    out.c0 = l.attenuation.x;
    out.c1 = float(l.attenuation.y / s);
    out.c2 = float(l.attenuation.z / (s * s));
    out.attenuationGiven = l.attenuationGiven;
    // The range in eye units, as d is measured there.
    if (l.range) {
        out.range = float(double(*l.range) * s);
        out.window = l.window;
    }
    if (isAreaLight(out.kind)) {
        // The emitter's frame in world units: n the way it faces, v̂ along `up` in its plane, û across.
        const glm::dvec3 n = glm::normalize(glm::dvec3(l.direction));
        const glm::dvec3 up = glm::dvec3(l.up.value_or(areaUp(l.direction)));
        const glm::dvec3 v = glm::normalize(up - n * glm::dot(up, n));
        const glm::dvec3 u = glm::cross(v, n);
        const double halfU = out.kind == LightKind::Rect ? 0.5 * l.width : l.radius;
        const double halfV = out.kind == LightKind::Rect ? 0.5 * l.height : l.radius;
        out.areaNormal = directionToView(n);
        out.areaU = toView(vec3(u * halfU), 0.0f);
        out.areaV = toView(vec3(v * halfV), 0.0f);
        out.areaSamples = l.samples;
    }
    out.spotCutoffDegrees = out.kind == LightKind::Spot ? l.spotCutoffDegrees : 180.0f;
    out.spotExponent = l.spotExponent;
    if (l.spotInnerDegrees && l.spotOuterDegrees) {
        out.spotProfile = SpotProfile::Smooth;
        out.spotInnerDegrees = *l.spotInnerDegrees;
        out.spotOuterDegrees = *l.spotOuterDegrees;
    }
    return out;
}

// The uniforms every draw shares: lights, fog, the lighting's options.
SurfaceUniforms commonUniforms(const Scene& scene, std::span<const LightSpec> lights, const Bounds& bounds,
                               const Camera& camera, ColourDecoding decode) {
    const bool glPreset = scene.lighting.preset == LightingPreset::GL;
    SurfaceUniforms common;
    common.globalAmbient = decode(scene.ambientLight);
    common.lightCount = static_cast<int>(lights.size());
    common.brdf = scene.lighting.brdf;
    common.precision = scene.lighting.powers;
    common.normalization = scene.lighting.normalize;
    common.twoSidedFlip = !glPreset;
    common.clampColor = glPreset;
    if (scene.lighting.preset == LightingPreset::Lecture) {
        // The lecture notes' conventions (docs/lighting.md, "Facet's form and the notes'").
        common.twoSidedFlip = false;
        common.clampNdotV = true;
        common.clampColor = true;
        common.brdf.fresnelCosine = FresnelCosine::NdotL;
        common.brdf.denominator = MicrofacetDenominator::Pi;
        common.brdf.metal = MetalBlend::TintedLobe;
    }
    common.fog = fogParams(scene, bounds, camera, decode);
    common.textureFilter = scene.textures.filter;
    if (!isMultisampled(scene.pipeline.antialiasing))  // ssaaN: each pass samples 1/N of the pixel
        common.textureFootprint =
            1.0f / std::sqrt(static_cast<float>(samplesPerPixel(scene.pipeline.antialiasing)));
    for (std::size_t i = 0; i < lights.size(); ++i) {
        common.lights[i] = eyeSpaceLight(lights[i], camera, decode);
        if (scene.areaSamples && isAreaLight(lights[i].type))
            common.lights[i].areaSamples = *scene.areaSamples;
    }
    // A pixel's size in eye space (per unit of depth under perspective), for anisotropic draws' tangents.
    const glm::dmat4& projection = camera.clipFromViewExact;
    common.perspective = projection[3][3] == 0.0;
    common.pixelSpread =
        vec2(float(2.0 / (projection[0][0] * scene.width)), float(2.0 / (projection[1][1] * scene.height)));
    return common;
}

// The texture of `file` in the assets, or null (none, or unreadable).
const Texture* textureOf(const SceneAssets& assets, const std::filesystem::path& file) {
    if (file.empty()) return nullptr;
    const LoadedTexture* loaded = assets.texture(file);
    return loaded ? loaded->texture.get() : nullptr;
}

// One object's draws, made one per part alike.
struct ObjectDraws {
    const Scene& scene;
    const SceneAssets& assets;
    const ObjectSpec& object;
    SurfaceUniforms uniforms;  // the common ones, placed for the object, its reflection model chosen
    ShadingFrequency frequency;
    BlendMode blend;
    bool glPreset;
    ColourDecoding decode;
};

// The draw of one part of an object's mesh; its triangles go to `triangles`.
PreparedDraw partDraw(const ObjectDraws& o, const Camera& camera, const Mesh& mesh, const MeshPart& part,
                      DrawTriangles& triangles) {
    PreparedDraw draw;
    draw.uniforms = o.uniforms;
    draw.frequency = o.frequency;
    draw.worldFromObject = o.object.worldFromObject;
    draw.viewFromObjectExact = camera.viewFromWorldExact * glm::dmat4(o.object.worldFromObject);
    Material material = mesh.materials.at(part.material);
    draw.uniforms.emissionMap = textureOf(o.assets, material.emissionTexture);
    // map_Ke without Ke (or with Ke 0) means the texture is the emission, as exporters write it.
    if (draw.uniforms.emissionMap && material.emission == vec3(0.0f)) material.emission = vec3(1.0f);
    // The gl preset: faces without a material get OpenGL 1.x's default glMaterial, and the
    // shininess is clamped to GL_SHININESS's range [0, 128].
    if (o.glPreset && material.fallback) material = glDefaultMaterial();
    draw.uniforms.material = phongMaterial(material, o.object.material, o.decode);
    if (o.glPreset) draw.uniforms.material.shininess = std::min(draw.uniforms.material.shininess, 128.0f);
    draw.uniforms.pbr =
        pbrMaterial(material, draw.uniforms.material, o.object.material, o.decode, o.scene.source);
    draw.uniforms.opacity = o.object.material.opacity.value_or(material.opacity);
    const LoadedTexture* diffuse =
        material.diffuseTexture.empty() ? nullptr : o.assets.texture(material.diffuseTexture);
    draw.uniforms.diffuseMap = diffuse ? diffuse->texture.get() : nullptr;
    // Transparent: see through it (opacity, a texture's alpha) or blended other than over.
    const bool textureAlpha = diffuse && diffuse->translucent;
    draw.transparent = draw.uniforms.opacity < 1.0f || textureAlpha || o.blend != BlendMode::Over;
    // The gl preset blends over as glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA) does,
    // alpha included; Facet's keeps Porter–Duff's α.
    draw.uniforms.blend = !draw.transparent                          ? BlendMode::Replace
                          : o.glPreset && o.blend == BlendMode::Over ? BlendMode::OverGL
                                                                     : o.blend;
    triangles = extractPart(mesh, part);
    // Flat shading lights each face with its own normal; the GL preset keeps OpenGL's rule
    // instead: the provoking vertex's colour, lit with that vertex's normal.
    if (o.frequency == ShadingFrequency::Flat && !o.glPreset) unweldWithFaceNormals(triangles);
    return draw;
}

DrawState pipelineState(const Scene& scene);

// The shader of one's own an object is drawn with (its own, else the scene's) and its uniforms' values:
// the scene file's for it, then --uniform's where it declares them. Nothing for the built-in shaders.
// Its module is compiled for the back-end walk this draw takes in the scene (planFrame: the scene's
// depth format and samples; the fragment lists for a transparent draw under exact transparency).
void chooseUserShader(const Scene& scene, const ObjectSpec& object, PreparedDraw& draw) {
    const std::optional<ShaderSpec>& spec = object.shader ? object.shader : scene.shader;
    if (!spec) return;
    DrawPlan plan = planDraw(pipelineState(scene));
    if (draw.transparent && scene.transparency.mode == TransparencyMode::Exact)
        plan.output = FragmentOutput::AppendToLists;
    draw.userShader = loadUserShader(spec->source, backEndWalkOf(plan, false));
    draw.userUniforms = uniformSettings(draw.userShader, spec->uniforms);
    const std::vector<UniformSetting> given = uniformSettings(draw.userShader, scene.uniforms, true);
    draw.userUniforms.insert(draw.userUniforms.end(), given.begin(), given.end());
}

// Every --uniform must reach a shader: one no shader of the scene declares is a mistake (a misspelt name).
void checkUniformsUsed(const PreparedScene& frame) {
    for (const UniformValue& value : frame.scene.uniforms) {
        bool declared = false;
        const UserShader* any = nullptr;
        for (const PreparedDraw& draw : frame.draws) {
            if (!draw.userShader.module) continue;
            any = &draw.userShader;
            declared = declared || declaresUniform(draw.userShader, value.name);
        }
        if (!any)
            throw InputError(value.origin +
                             ": the scene uses no shader of one's own to give it to (--shader FILE)");
        if (!declared)
            throw InputError(value.origin + ": " + any->label + " declares no uniform " +
                             inQuotes(value.name) + " (it has: " + describeUniforms(*any->module) + ")");
    }
}

// One draw per (object, material part) into frame.draws, their triangles into `triangles`.
void addDraws(PreparedScene& frame, const SceneAssets& assets, const SurfaceUniforms& common,
              ColourDecoding decode, std::vector<DrawTriangles>& triangles) {
    const Scene& scene = frame.scene;
    for (const ObjectSpec& object : scene.objects) {
        const Mesh& mesh = assets.model(object.model);
        ObjectDraws o{scene,
                      assets,
                      object,
                      common,
                      object.shading.value_or(scene.lighting.shadingOrDefault()),
                      object.blend.value_or(BlendMode::Over),
                      scene.lighting.preset == LightingPreset::GL,
                      decode};
        placeDraw(o.uniforms, frame.camera, glm::dmat4(object.worldFromObject));
        o.uniforms.reflection = object.reflection.value_or(
            object.material.physicallyBased() ? ReflectionModel::CookTorrance : scene.lighting.model);
        o.uniforms.unlit = o.frequency == ShadingFrequency::Constant;
        for (const MeshPart& part : mesh.parts) {
            if (part.indexCount == 0) continue;
            frame.draws.push_back(partDraw(o, frame.camera, mesh, part, triangles.emplace_back()));
            chooseUserShader(scene, object, frame.draws.back());
        }
    }
    checkUniformsUsed(frame);
}

DrawState pipelineState(const Scene& scene) {
    DrawState state;
    state.viewport = {0, 0, scene.width, scene.height};
    state.raster.cull = scene.pipeline.cull;
    state.raster.subpixelBits = scene.pipeline.subpixelBits;
    state.interpolation = scene.pipeline.interpolation;
    state.depth.format = scene.pipeline.depth;
    state.depth.compare = nearerPasses(state.depth.format, CompareOp::Less);
    state.colorBuffer = scene.pipeline.colorBuffer;
    if (isMultisampled(scene.pipeline.antialiasing))
        state.samples = samplesPerPixel(scene.pipeline.antialiasing);
    state.raster.provokingVertex = ProvokingVertex::Last;  // OpenGL's convention
    return state;
}

// The eye-space distance to the far side of the bounding sphere.
float sceneExtent(const Bounds& bounds, const Camera& camera) {
    const glm::dvec3 centre = 0.5 * (glm::dvec3(bounds.min) + glm::dvec3(bounds.max));
    const double radius = 0.5 * glm::length(glm::dvec3(bounds.max) - glm::dvec3(bounds.min));
    return float((glm::length(glm::dvec3(camera.eye) - centre) + radius) * camera.viewScale);
}

// The importer's warnings, then the camera's, then the unreadable textures'.
std::vector<std::string> frameWarnings(const SceneAssets& assets, const Camera& camera) {
    std::vector<std::string> warnings = assets.modelWarnings;
    warnings.insert(warnings.end(), camera.warnings.begin(), camera.warnings.end());
    warnings.insert(warnings.end(), assets.textureWarnings.begin(), assets.textureWarnings.end());
    return warnings;
}

}  // namespace

void checkFrameSettings(const Scene& scene) {
    if (scene.width < 1 || scene.height < 1 || scene.width > kMaxImageSide || scene.height > kMaxImageSide)
        throw InputError(scene.source.string() + ": image size " + std::to_string(scene.width) + "x" +
                         std::to_string(scene.height) + " is outside 1.." + std::to_string(kMaxImageSide));
    if (scene.objects.empty())
        throw InputError(scene.source.string() + ": the scene has no objects to render");
    // Exact transparency keeps one fragment list per pixel, not per sample.
    if (scene.transparency.mode == TransparencyMode::Exact && isMultisampled(scene.pipeline.antialiasing)) {
        std::string message = scene.source.string();
        message += ": exact transparency (--transparency exact) cannot be multisampled (--aa ";
        message += nameOf(scene.pipeline.antialiasing);
        message += "): its fragment lists are per pixel; use --aa ssaa";
        message += std::to_string(samplesPerPixel(scene.pipeline.antialiasing));
        message += " or --transparency sorted";
        throw InputError(message);
    }
    checkFrameMemory(scene);  // before any file is read
}

PreparedScene prepareFrame(const Scene& scene, std::shared_ptr<const SceneAssets> assets) {
    checkFrameSettings(scene);
    if (!assets || !(assets->options == assetOptionsFor(scene, assets->options.limits)))
        throw std::invalid_argument("prepareFrame: the assets were loaded for another scene");
    PreparedScene frame;
    frame.scene = scene;
    frame.assets = assets;
    frame.degenerateSkipped = assets->degenerateSkipped;
    const Bounds bounds = sceneBounds(scene, *assets);
    checkTriangleLimit(scene, *assets);
    frame.turntableCentre = 0.5f * (bounds.min + bounds.max);
    frame.camera = sceneCamera(scene, bounds);
    frame.warnings = frameWarnings(*assets, frame.camera);

    const bool glPreset = scene.lighting.preset == LightingPreset::GL;
    const ColourDecoding decode{!glPreset && scene.gamma.decodeInputs};
    const std::vector<LightSpec> lights = sceneLights(scene);
    std::vector<DrawTriangles> triangles;
    SurfaceUniforms common = commonUniforms(scene, lights, bounds, frame.camera, decode);
    common.environment = environmentParams(scene, *assets, frame.camera);
    frame.environment = common.environment;
    frame.environmentBackground = common.environment.map && scene.environment->background;
    addDraws(frame, *assets, common, decode, triangles);
    setTriangles(frame, std::move(triangles));

    frame.state = pipelineState(scene);
    // The clipper's new vertices take their depth from their w by the camera's projection (state.h,
    // DepthFromW); a supersampling pass's projection shifts x and y only, so the relation holds there too.
    frame.state.depth.fromW = clipDepthFromW(drawnClipFromView(frame.camera));
    frame.clearColor = vec4(decode(vec3(scene.background)), scene.background.a);
    frame.encoding = glPreset ? kGlEncoding
                     : scene.lighting.preset == LightingPreset::Lecture
                         ? kLectureEncoding
                         : ColorEncoding{scene.gamma.encode, scene.gamma.exponent};
    // Shadows: each light's method (the command line's for all of them, when given).
    for (std::size_t i = 0; i < lights.size(); ++i) {
        frame.shadowMethods[i] = scene.shadows.value_or(lights[i].shadows);
        // An area light's soft shadows are ray-cast: a shadow map (--shadows map) falls back to rays.
        if (isAreaLight(lights[i].type) && frame.shadowMethods[i] == ShadowMethod::Map) {
            frame.shadowMethods[i] = ShadowMethod::Ray;
            frame.warnings.push_back("light " + std::to_string(i) + " is an area light (\"" +
                                     std::string(nameOf(lights[i].type)) +
                                     "\"): its shadows are ray-cast, not from a shadow map");
        }
    }
    frame.shadowMapOptions = scene.shadowMap;
    frame.sceneExtent = sceneExtent(bounds, frame.camera);
    prepareShadows(frame);
    return frame;
}

PreparedScene prepareScene(const Scene& scene, const TextureLimits& limits) {
    checkFrameSettings(scene);  // before any file is read
    return prepareFrame(scene, loadSharedAssets(scene, limits));
}

PreparedScene prepareScene(const Scene& scene, std::shared_ptr<const SceneAssets> assets,
                           const TextureLimits& limits) {
    checkFrameSettings(scene);
    return prepareFrame(scene, assetsFor(scene, std::move(assets), limits));
}

void setTriangles(PreparedScene& frame, std::vector<DrawTriangles> triangles) {
    if (triangles.size() != frame.draws.size())
        throw std::invalid_argument("setTriangles: one DrawTriangles per draw");
    auto geometry = std::make_shared<FrameGeometry>();
    geometry->draws = std::move(triangles);
    frame.triangleCount = 0;
    for (std::size_t k = 0; k < frame.draws.size(); ++k) {
        const DrawTriangles& t = geometry->draws[k];
        PreparedDraw& draw = frame.draws[k];
        draw.vertices = t.vertices;
        draw.indices = t.indices;
        const auto count = static_cast<std::uint32_t>(t.indices.size() / 3);
        frame.triangleCount += count;
        if (!draw.transparent) continue;
        for (std::uint32_t i = 0; i < count; ++i)
            geometry->transparentTriangles.push_back({static_cast<std::uint32_t>(k), i});
    }
    frame.transparentTriangles = geometry->transparentTriangles;
    frame.geometry = std::move(geometry);
}

std::vector<RayMesh> rayMeshes(const PreparedScene& prepared, std::vector<std::vector<vec3>>& positions) {
    positions.assign(prepared.draws.size(), {});
    std::vector<RayMesh> meshes;
    meshes.reserve(prepared.draws.size());
    for (std::size_t k = 0; k < prepared.draws.size(); ++k) {
        const PreparedDraw& d = prepared.draws[k];
        positions[k].reserve(d.vertices.size());
        for (const glm::dvec3& p : eyePositions(prepared, d))
            positions[k].push_back(vec3(p));
        meshes.push_back({positions[k], d.indices, !d.transparent});
    }
    return meshes;
}

void prepareShadows(PreparedScene& prepared) {
    prepared.shadows.reset();
    for (PreparedDraw& d : prepared.draws)
        d.uniforms.shadows = nullptr;
    const auto casts = [&](ShadowMethod method) {
        return std::find(prepared.shadowMethods.begin(), prepared.shadowMethods.end(), method) !=
               prepared.shadowMethods.end();
    };
    if (!casts(ShadowMethod::Ray) && !casts(ShadowMethod::Map)) return;  // no BVH, no map, no cost
    auto shadows = std::make_shared<FrameShadows>();
    SceneShadows& forShaders = shadows->forShaders;
    forShaders.rayOffset = kShadowRayOffset * prepared.sceneExtent;
    if (casts(ShadowMethod::Ray)) {
        std::vector<std::vector<vec3>> positions;
        const std::vector<RayMesh> meshes = rayMeshes(prepared, positions);
        shadows->rays = std::make_unique<RayScene>(meshes);
        forShaders.rays = shadows->rays.get();
    }
    checkShadowMapMemory(prepared);  // before the first map is drawn
    const MemoryUse use("drawing the shadow maps (--shadow-map-size)");
    for (std::size_t i = 0; i < kMaxLights; ++i) {
        forShaders.lights[i].method = prepared.shadowMethods[i];
        if (prepared.shadowMethods[i] == ShadowMethod::Map) {
            shadows->maps.push_back(drawShadowMap(prepared, static_cast<int>(i)));
            forShaders.lights[i].map = shadows->maps.back().get();
        }
    }
    for (PreparedDraw& d : prepared.draws)
        d.uniforms.shadows = &forShaders;
    prepared.shadows = std::move(shadows);
}

void setTurntable(PreparedScene& prepared, float degrees) {
    const glm::dvec3 c(prepared.turntableCentre);
    // turn(p) = c + Ry(θ)(p − c): about the vertical axis through the centre.
    const glm::dmat4 turn = glm::translate(glm::dmat4(1.0), c) *
                            glm::rotate(glm::dmat4(1.0), glm::radians(double(degrees)), glm::dvec3(0, 1, 0)) *
                            glm::translate(glm::dmat4(1.0), -c);
    for (PreparedDraw& d : prepared.draws) {
        placeDraw(d.uniforms, prepared.camera, turn * glm::dmat4(d.worldFromObject));
        d.viewFromObjectExact = prepared.camera.viewFromWorldExact * turn * glm::dmat4(d.worldFromObject);
    }
    prepareShadows(prepared);  // the shadows move with the objects
}

PreparedScene turned(const PreparedScene& prepared, float degrees) {
    PreparedScene variant = prepared;
    setTurntable(variant, degrees);
    return variant;
}

namespace {

// The sort keys of the transparent triangles: the distance along the view direction (−z_eye) of each
// triangle's centroid or of its farthest corner; larger is farther. The triangles of one draw are
// consecutive, so each draw's vertex depths are computed once, then shared by its triangles.
void depthKeys(const PreparedScene& prepared, SortKey key, FrameMemory& memory) {
    const std::span<const TransparentTriangle> triangles = prepared.transparentTriangles;
    memory.keys.resize(triangles.size());
    std::uint32_t current = std::numeric_limits<std::uint32_t>::max();
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        const PreparedDraw& d = prepared.draws[triangles[t].draw];
        if (triangles[t].draw != current) {
            current = triangles[t].draw;
            const mat4 m = d.uniforms.viewFromObject;  // a copy: the stores below cannot alias it
            memory.vertexDepths.resize(d.vertices.size());
            for (std::size_t v = 0; v < d.vertices.size(); ++v)
                memory.vertexDepths[v] = eyeDepthOf(m, d.vertices[v].position);
        }
        const std::uint32_t* corner = &d.indices[3 * triangles[t].triangle];
        memory.keys[t] = sortKeyOf(key, memory.vertexDepths[corner[0]], memory.vertexDepths[corner[1]],
                                   memory.vertexDepths[corner[2]]);
    }
}

// Cuts the sorted transparent triangles into runs of consecutive triangles of one draw (memory.runs).
// A run with all of its draw's triangles uses the draw's vertex array (every vertex of it is used:
// extractPart); any other run gets a compact array of the vertices it uses, each once, and its
// indices are renumbered into it. The vertex stage then shades, over all runs, at most three
// vertices per transparent triangle, instead of the whole draw once per run. The image is the same:
// a vertex is shaded alike wherever it sits in the array.
void buildTransparentRuns(const PreparedScene& prepared, std::span<const std::uint32_t> order,
                          FrameMemory& memory) {
    const std::span<const TransparentTriangle> triangles = prepared.transparentTriangles;
    memory.runIndices.resize(3 * triangles.size());
    memory.runTriangles.resize(triangles.size());
    memory.runVertices.clear();
    memory.runVertices.reserve(3 * triangles.size());  // at most three vertices a triangle: no regrowth
    memory.runs.clear();
    std::size_t written = 0;
    // In sorted order the triangles, their indices and their vertices are read at random places (a
    // cache miss each, most of the plan's time): each loop below asks for what it reads kAhead steps
    // later.
    constexpr std::size_t kAhead = 16;
    for (std::size_t i = 0; i < order.size();) {
        const std::uint32_t k = triangles[order[i]].draw;
        const PreparedDraw& d = prepared.draws[k];
        const std::size_t first = written;
        for (; i < order.size() && triangles[order[i]].draw == k; ++i) {
            if (i + kAhead < order.size()) {
                const TransparentTriangle& ahead = triangles[order[i + kAhead]];
                __builtin_prefetch(&prepared.draws[ahead.draw].indices[3 * std::size_t{ahead.triangle}]);
            }
            if (i + 2 * kAhead < order.size()) __builtin_prefetch(&triangles[order[i + 2 * kAhead]]);
            const std::uint32_t t = triangles[order[i]].triangle;
            memory.runTriangles[written / 3] = t;
            for (int c = 0; c < 3; ++c)
                memory.runIndices[written++] = d.indices[3 * t + c];
        }
        const std::span<std::uint32_t> run = std::span(memory.runIndices).subspan(first, written - first);
        const std::size_t start = memory.runVertices.size();
        if (run.size() < d.indices.size()) {
            if (memory.runVertexOf.size() < d.vertices.size())
                memory.runVertexOf.resize(d.vertices.size(), FrameMemory::kNotInRun);
            memory.runVertexSources.clear();
            for (std::size_t j = 0; j < run.size(); ++j) {
                if (j + kAhead < run.size()) {
                    __builtin_prefetch(&memory.runVertexOf[run[j + kAhead]]);
                    __builtin_prefetch(&d.vertices[run[j + kAhead]]);
                }
                std::uint32_t& index = run[j];
                std::uint32_t& local = memory.runVertexOf[index];
                if (local == FrameMemory::kNotInRun) {
                    local = static_cast<std::uint32_t>(memory.runVertexSources.size());
                    memory.runVertexSources.push_back(index);
                    memory.runVertices.push_back(d.vertices[index]);
                }
                index = local;
            }
            for (const std::uint32_t source : memory.runVertexSources)
                memory.runVertexOf[source] = FrameMemory::kNotInRun;
        }
        memory.runs.push_back({k, first, run.size(), start, memory.runVertices.size() - start});
    }
}

// Whether memory's runs were cut for the frame's triangles (the same FrameGeometry, not merely one at
// the same address).
bool runsCutFor(const FrameMemory& memory, const PreparedScene& prepared) {
    return prepared.geometry && !memory.runsGeometry.owner_before(prepared.geometry) &&
           !prepared.geometry.owner_before(memory.runsGeometry);
}

// The draw call of a transparent run: its compact vertices (or its draw's own) and indices in `memory`.
PlannedDraw runCall(const PreparedScene& prepared, const FrameMemory& memory,
                    const FrameMemory::TransparentRun& run, const DrawState& state) {
    const std::span<const MeshVertex> vertices =
        run.vertexCount == 0
            ? prepared.draws[run.draw].vertices
            : std::span<const MeshVertex>(memory.runVertices).subspan(run.firstVertex, run.vertexCount);
    return {
        run.draw, vertices,
        std::span<const std::uint32_t>(memory.runIndices).subspan(run.firstIndex, run.indexCount), state,
        std::span<const std::uint32_t>(memory.runTriangles).subspan(run.firstIndex / 3, run.indexCount / 3)};
}

}  // namespace

std::vector<PlannedDraw> planFrame(const PreparedScene& prepared, TransparencyMode mode, FrameMemory& memory,
                                   FrameStats& stats) {
    std::vector<PlannedDraw> plan;
    // A user's vertex shader need not place its vertices by the camera's projection: its clipped
    // vertices keep interpolated depths (state.h, DepthFromW).
    const auto drawState = [&](std::uint32_t k) {
        DrawState state = prepared.state;
        if (prepared.draws[k].userShader.module) state.depth.fromW = {};
        return state;
    };
    // Opaque draws, with depth writes, in file order.
    for (std::uint32_t k = 0; k < prepared.draws.size(); ++k) {
        const PreparedDraw& d = prepared.draws[k];
        if (!d.transparent) plan.push_back({k, d.vertices, d.indices, drawState(k), {}});
    }
    const std::span<const TransparentTriangle> triangles = prepared.transparentTriangles;
    if (triangles.empty()) return plan;

    // The transparent pass: depth test on, depth writes off, each draw's own blend.
    const TransparencyOptions& options = prepared.scene.transparency;
    const auto transparentState = [&](std::uint32_t k) {
        DrawState state = drawState(k);
        state.depth.writeEnabled = false;
        state.blend = prepared.draws[k].uniforms.blend;
        if (mode == TransparencyMode::Exact) state.output = FragmentOutput::AppendToLists;
        return state;
    };
    if (mode != TransparencyMode::Sorted) {
        for (std::uint32_t k = 0; k < prepared.draws.size(); ++k)
            if (prepared.draws[k].transparent) {
                plan.push_back(
                    {k, prepared.draws[k].vertices, prepared.draws[k].indices, transparentState(k), {}});
                ++stats.transparentRuns;
            }
        return plan;
    }

    // Sorted back to front, then cut into runs of consecutive triangles of one draw.
    const auto start = std::chrono::steady_clock::now();
    depthKeys(prepared, options.key, memory);
    const std::span<const std::uint32_t> order =
        memory.sorter.sort(memory.keys, SortAlgorithm::InsertionWithMemory, stats.sort);
    stats.sortMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

    // The runs depend on the order and the frame's triangles alone: when the sort moved no triangle
    // since the last frame this memory planned for these triangles (a still camera over still objects,
    // or another variant of the same frame), that frame's runs, index lists and compact vertex arrays
    // are this frame's too. Only the calls are made again below, with the states the frame has now.
    stats.runsReused = runsCutFor(memory, prepared) && !stats.sort.fromScratch && stats.sort.moves == 0;
    if (!stats.runsReused) {
        buildTransparentRuns(prepared, order, memory);
        memory.runsGeometry = prepared.geometry;
    }
    plan.reserve(plan.size() + memory.runs.size());
    for (const FrameMemory::TransparentRun& run : memory.runs) {
        plan.push_back(runCall(prepared, memory, run, transparentState(run.draw)));
        ++stats.transparentRuns;
    }
    return plan;
}

DrawStats renderFrame(const PreparedScene& prepared, Framebuffer& target, DrawContext& context,
                      std::uint8_t terms) {
    FrameMemory memory;
    return renderFrame(prepared, target, context, memory, terms).draw;
}

glm::dmat4 clipFromViewAtSample(const Camera& camera, SampleOffset offset, int width, int height) {
    const double unit = kSampleOffsetUnitsPerPixel;
    const glm::dvec3 shift(-2.0 * offset.x / (unit * width), 2.0 * offset.y / (unit * height), 0.0);
    // After the projection the frame draws with (reversed Z remaps its depth), so a pass differs
    // from the frame only by where its pixels sample.
    return glm::translate(glm::dmat4(1.0), shift) * drawnClipFromView(camera);
}

glm::dvec3 environmentViewRay(const glm::dmat4& viewFromClip, glm::dvec2 window, int width, int height) {
    const double ndcX = 2.0 * window.x / width - 1.0, ndcY = 1.0 - 2.0 * window.y / height;
    const glm::dvec4 p = viewFromClip * glm::dvec4(ndcX, ndcY, 0.5, 1.0);
    return glm::dvec3(p) / p.w;
}

namespace detail {

void fillEnvironmentBackground(const PreparedScene& prepared, Framebuffer& target,
                               const glm::dmat4* clipFromView, ThreadPool& pool) {
    const glm::dmat4 viewFromClip =
        glm::inverse(clipFromView ? *clipFromView : drawnClipFromView(prepared.camera));
    const int width = target.width(), height = target.height();
    const std::size_t samples = static_cast<std::size_t>(target.samples());
    // Taken here, once, on the calling thread (they settle the clear): the rows are then written apart.
    vec4* const colors = target.colorSpanToWrite().data();
    vec4* const sampleColors = samples > 1 ? target.sampleColors(0, 0) : nullptr;
    const float alpha = prepared.clearColor.a;
    const ColorBufferFormat format = prepared.state.colorBuffer;
    pool.parallelFor(static_cast<std::size_t>(height), [&](std::size_t row, int) {
        for (int x = 0; x < width; ++x) {
            const glm::dvec3 ray =
                environmentViewRay(viewFromClip, glm::dvec2(x + 0.5, double(row) + 0.5), width, height);
            const vec4 c =
                roundToColorBuffer(format, vec4(environmentColor(prepared.environment, ray), alpha));
            const std::size_t i = row * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
            colors[i] = c;
            if (sampleColors)
                for (std::size_t s = 0; s < samples; ++s)
                    sampleColors[i * samples + s] = c;
        }
    });
}

void accumulateSamplePass(Framebuffer& target, std::vector<vec4>& sum, std::size_t pass, std::size_t passes,
                          ColorBufferFormat format, ThreadPool& pool) {
    const int width = target.width();
    const std::size_t pixels = static_cast<std::size_t>(width) * target.height();
    if (sum.size() != pixels) sum.resize(pixels);  // allocated by the first frame, reused after
    const float weight = 1.0f / static_cast<float>(passes);
    const bool first = pass == 0, last = pass + 1 == passes;
    // Taken here, not per pixel through target.color(x, y): that call also marks the framebuffer's
    // cleared cells unknown, a write every thread would make at once.
    const std::span<vec4> colors = target.colorSpanToWrite();
    pool.parallelFor(static_cast<std::size_t>(target.height()), [&](std::size_t row, int) {
        vec4* rowColor = colors.data() + row * width;
        vec4* rowSum = sum.data() + row * width;
        for (int x = 0; x < width; ++x) {
            vec4& c = rowColor[x];
            rowSum[x] = first ? c : rowSum[x] + c;
            // The resolve writes into the colour buffer, rounded as its format stores a value.
            if (last) c = roundToColorBuffer(format, rowSum[x] * weight);
        }
    });
}

}  // namespace detail

LinearImage toImage(const Framebuffer& framebuffer) {
    LinearImage image;
    image.width = framebuffer.width();
    image.height = framebuffer.height();
    image.pixels = framebuffer.colorPixels();
    return image;
}

}  // namespace facet
