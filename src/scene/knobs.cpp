#include "scene/knobs.h"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <type_traits>

#include "base/quote.h"
#include "pipeline/names.h"
#include "scene/json_reader.h"

namespace facet {

namespace {

// One name when every item of `items` gives the same value of E, else "" (the scene mixes them).
template <class E, class Items, class Get>
std::string commonName(const Items& items, Get get) {
    std::string common;
    for (const auto& item : items) {
        const std::string name(nameOf(static_cast<E>(get(item))));
        if (!common.empty() && common != name) return "";
        common = name;
    }
    return common;
}

// A knob's name, flag, help and scene file key (the rest set by the callers below).
SceneKnob named(std::string name, std::string flag, std::string help, std::string section = "",
                std::string key = "") {
    SceneKnob knob;
    knob.name = std::move(name);
    knob.flag = std::move(flag);
    knob.help = std::move(help);
    knob.section = std::move(section);
    knob.key = std::move(key);
    return knob;
}

// A knob whose value is one of E's names, in the field `field(scene)` returns (of a Scene or a const one).
template <class E, class Field>
SceneKnob choice(std::string name, std::string flag, std::string help, std::string section, std::string key,
                 Field field) {
    SceneKnob knob =
        named(std::move(name), std::move(flag), std::move(help), std::move(section), std::move(key));
    knob.kind = KnobKind::Names;
    knob.names = namesOf<E>();
    knob.tradeValues = {};
    knob.get = [field](const Scene& scene) { return std::string(nameOf<E>(field(scene))); };
    knob.set = [field](Scene& scene, const std::string& value) { field(scene) = *parseName<E>(value); };
    return knob;
}

// A knob whose value is a number of type T (int: whole) from `lowest` to `highest`.
template <class T, class Field>
SceneKnob number(std::string name, std::string flag, std::string help, std::string section, std::string key,
                 double lowest, double highest, std::string unit, Field field) {
    SceneKnob knob =
        named(std::move(name), std::move(flag), std::move(help), std::move(section), std::move(key));
    knob.kind = std::is_integral_v<T> ? KnobKind::WholeNumber : KnobKind::Number;
    knob.lowest = lowest;
    knob.highest = highest;
    knob.unit = std::move(unit);
    knob.get = [field](const Scene& scene) { return knobNumberText(static_cast<double>(field(scene))); };
    knob.set = [field](Scene& scene, const std::string& value) {
        field(scene) = static_cast<T>(std::strtod(value.c_str(), nullptr));
    };
    return knob;
}

// `knob` as the trade turns it: the values it tries, those of the fast and best presets, and the knob
// and value it acts under.
SceneKnob traded(SceneKnob knob, std::vector<std::string> values, std::string fast, std::string best,
                 std::string needsKnob = "", std::string needsValue = "") {
    knob.tradeValues = values.empty() ? knob.names : std::move(values);
    knob.fastValue = std::move(fast);
    knob.bestValue = std::move(best);
    knob.needsKnob = std::move(needsKnob);
    knob.needsValue = std::move(needsValue);
    return knob;
}

// `knob` as one that changes what the scene shows, whatever its value: no value of it is nearer the
// scene as the user wrote it than another, so the trade cannot rank it by accuracy.
SceneKnob changingContent(SceneKnob knob) {
    knob.changesContent = [](const Scene&, const std::string&) { return true; };
    return knob;
}

// --reflection and --shading choose for every object; the scene file's "lighting" keys are the
// scene's defaults, which an object's own "lighting" overrides (read after them).
SceneKnob reflectionKnob() {
    SceneKnob knob = choice<ReflectionModel>(
        "reflection", "--reflection", "Reflection model for every object", "lighting", "model",
        [](auto& s) -> auto& { return s.lighting.model; });
    knob.get = [](const Scene& scene) {
        return commonName<ReflectionModel>(scene.objects, [&](const ObjectSpec& object) {
            return object.reflection.value_or(scene.lighting.model);
        });
    };
    knob.set = [](Scene& scene, const std::string& value) {
        scene.lighting.model = *parseName<ReflectionModel>(value);
        for (ObjectSpec& object : scene.objects)
            object.reflection = scene.lighting.model;
    };
    return knob;
}

SceneKnob shadingKnob() {
    SceneKnob knob =
        named("shading", "--shading", "Shading frequency for every object: per face, per vertex or per pixel",
              "lighting", "shading");
    knob.names = namesOf<ShadingFrequency>();
    knob.get = [](const Scene& scene) {
        return commonName<ShadingFrequency>(scene.objects, [&](const ObjectSpec& object) {
            return object.shading.value_or(scene.lighting.shadingOrDefault());
        });
    };
    knob.set = [](Scene& scene, const std::string& value) {
        scene.lighting.shading = *parseName<ShadingFrequency>(value);
        for (ObjectSpec& object : scene.objects)
            object.shading = scene.lighting.shading;
    };
    return knob;
}

// --shadows sets every light's method; a scene file sets each light's own ("lights[i].shadows").
SceneKnob shadowsKnob() {
    SceneKnob knob = named("shadows", "--shadows",
                           "Shadows of every light: none, a ray to the light (exact), or a shadow map");
    knob.names = namesOf<ShadowMethod>();
    knob.defaultNote = "(default: each light's \"shadows\" in the scene file, else none)";
    knob.get = [](const Scene& scene) {
        if (scene.shadows) return std::string(nameOf(*scene.shadows));
        if (scene.lights.empty()) return std::string(nameOf(ShadowMethod::None));  // the default light's
        return commonName<ShadowMethod>(scene.lights, [](const LightSpec& light) { return light.shadows; });
    };
    knob.set = [](Scene& scene, const std::string& value) { scene.shadows = parseName<ShadowMethod>(value); };
    // Shadows where the scene has a light without them add what the scene does not show; among lights
    // that all cast shadows, the method (and none, the fast approximation) is a matter of accuracy.
    knob.changesContent = [](const Scene& baseline, const std::string& value) {
        if (value == nameOf(ShadowMethod::None)) return false;
        if (baseline.shadows) return *baseline.shadows == ShadowMethod::None;
        if (baseline.lights.empty()) return true;  // the default light casts no shadows
        for (const LightSpec& light : baseline.lights)
            if (light.shadows == ShadowMethod::None) return true;
        return false;
    };
    return knob;
}

// --shininess sets every object's material shininess, over its MTL's Ns and its scene file's
// "material.shininess" (the one value a lecture's exercise varies); the command line only.
SceneKnob shininessKnob() {
    SceneKnob knob =
        named("shininess", "--shininess", "Shininess (the specular exponent n) of every object's material");
    knob.kind = KnobKind::Number;
    knob.lowest = 0;
    knob.highest = 10000;
    knob.defaultNote = "(default: each object's material, its MTL's Ns or the scene's \"shininess\")";
    knob.get = [](const Scene& scene) {
        std::string common;
        for (const ObjectSpec& object : scene.objects) {
            if (!object.material.shininess) return std::string();
            const std::string value = knobNumberText(*object.material.shininess);
            if (!common.empty() && common != value) return std::string();
            common = value;
        }
        return common;
    };
    knob.set = [](Scene& scene, const std::string& value) {
        const float shininess = std::strtof(value.c_str(), nullptr);
        for (ObjectSpec& object : scene.objects)
            object.material.shininess = shininess;
    };
    return knob;
}

// Linear fog's start or end ("fog.start", "fog.end"), absent unless given: then from the scene's
// bounding sphere.
SceneKnob fogRangeKnob(std::string name, std::string flag, std::string help, std::string key,
                       std::optional<float> FogSpec::*field) {
    SceneKnob knob = named(std::move(name), std::move(flag), std::move(help), "fog", std::move(key));
    knob.kind = KnobKind::Number;
    knob.lowest = 0;
    knob.highest = 1e30;
    knob.defaultNote = "(default: from the scene's bounding sphere)";
    knob.get = [field](const Scene& scene) {
        const std::optional<float>& value = scene.fog.*field;
        return value ? knobNumberText(*value) : std::string();
    };
    knob.set = [field](Scene& scene, const std::string& value) {
        scene.fog.*field = std::strtof(value.c_str(), nullptr);
    };
    return knob;
}

// --ior and --f0 set every object's material key of that name ("ior", "f0" in an object's "material"),
// as exercises vary them; like those keys they make an object physically based (Cook-Torrance unless
// its "lighting" or --reflection says otherwise). --f0 takes one number for all three channels.
template <class Field>
SceneKnob materialNumberKnob(std::string name, std::string help, double lowest, double highest, Field field) {
    SceneKnob knob = named(name, "--" + name, std::move(help));
    knob.kind = KnobKind::Number;
    knob.lowest = lowest;
    knob.highest = highest;
    knob.defaultNote = "(default: each object's material \"" + name + "\", else its MTL file's)";
    knob.get = [field](const Scene& scene) {
        std::string common;
        for (const ObjectSpec& object : scene.objects) {
            const auto& value = field(object.material);
            std::string text;
            if (value) {
                if constexpr (std::is_same_v<std::decay_t<decltype(*value)>, glm::vec3>)
                    text = value->x == value->y && value->y == value->z ? knobNumberText(value->x) : "";
                else
                    text = knobNumberText(static_cast<double>(*value));
            }
            if (&object != &scene.objects.front() && text != common) return std::string();
            common = text;
        }
        return common;
    };
    knob.set = [field](Scene& scene, const std::string& value) {
        const float number = static_cast<float>(std::strtod(value.c_str(), nullptr));
        for (ObjectSpec& object : scene.objects)
            field(object.material) = std::decay_t<decltype(*field(object.material))>(number);
    };
    return knob;
}

// --area-samples ("lighting": {"area_samples"}) sets every area light's shadow samples; a scene file
// also sets each light's own ("lights[i].samples"), which this overrides.
SceneKnob areaSamplesKnob() {
    SceneKnob knob =
        named("area-samples", "--area-samples",
              "Area lights: shadow rays per point, a square (4, 16, 64, 256)", "lighting", "area_samples");
    knob.kind = KnobKind::WholeNumber;
    knob.lowest = 1;
    knob.highest = kMaxAreaSamples;
    knob.unit = " shadow rays per point";
    for (int m = 1; m * m <= kMaxAreaSamples; ++m)
        knob.only.push_back(m * m);
    knob.defaultNote = "(default: each area light's \"samples\" in the scene file, else 16)";
    knob.get = [](const Scene& scene) {
        if (scene.areaSamples) return knobNumberText(*scene.areaSamples);
        std::string common;
        for (const LightSpec& light : scene.lights) {
            if (!isAreaLight(light.type)) continue;
            const std::string text = knobNumberText(light.samples);
            if (!common.empty() && common != text) return std::string();
            common = text;
        }
        return common.empty() ? knobNumberText(kDefaultAreaSamples) : common;
    };
    knob.set = [](Scene& scene, const std::string& value) {
        scene.areaSamples = static_cast<int>(std::strtod(value.c_str(), nullptr));
    };
    return knob;
}

// `knob`, which the exact reference renderer replaces by `instead` (docs/reference.md).
SceneKnob rasterizerOnly(SceneKnob knob, std::string instead) {
    knob.referenceInstead = std::move(instead);
    return knob;
}

// The table. Notes on the trade's values:
//   shading: constant shading is unlit, another look rather than a cheaper approximation: not traded.
//   cull: front-face culling draws the wrong side, not a trade; culling back faces is the fast choice (the
//     same image for closed models); no best value, the reference culls as the scene does.
//   reflection: a choice of look more than of accuracy: no fast or best value, the reference keeps the
//     scene's; it changes what the scene shows (changingContent), as do the Blinn exponent, the textures
//     and the normals below: the trade lists them apart from the accuracy knobs.
//   the shadow map's bias and slope bias: tuning, neither faster nor slower: no fast or best value.
//   shadows: whether a light casts shadows is the scene's choice; the reference ray-casts the shadows
//     of the lights that cast them, so the best preset keeps the scene's (adding shadows to a scene
//     without any would move it away from its reference: a change of content); the fast preset drops
//     them (an approximation: the image without its shadows).
//   cull: an accuracy knob. Culling back faces is exact for closed models and its error where a model
//     is open (a face seen from behind vanishes) is the approximation's price, which the reference
//     (culling as the scene does) measures.
//   colour buffer: the narrower formats are emulated by rounding a float buffer (pipeline/blend.h), so
//     they cost time rather than save it: no fast value.
//   textures and normals: what the model looks like (its maps; how its smooth normals are made) rather
//     than how exactly it is drawn; the reference draws the scene's own: no fast or best value.
//   subpixel bits: no measurable speed difference (the edge functions are integers at any precision).
std::vector<SceneKnob> makeTable() {
    SceneKnob shadowFilter = number<int>(
        "shadow-filter", "--shadow-filter", "Shadow maps: depth comparisons averaged per point, 1, 4 or 16",
        "shadow_map", "filter", 1, 16, " depth comparisons per point",
        [](auto& s) -> auto& { return s.shadowMap.filterTaps; });
    shadowFilter.only = {1, 4, 16};
    return {
        choice<LightingPreset>(
            "lighting", "--lighting",
            "Conventions: linear light and sRGB output, OpenGL 1.x fixed function, or the lecture "
            "notes' formulas and 2.2 gamma (docs/lighting.md)",
            "lighting", "preset", [](auto& s) -> auto& { return s.lighting.preset; }),
        traded(shadingKnob(), {"flat", "gouraud", "phong"}, "flat", "phong"),
        rasterizerOnly(traded(choice<Interpolation>(
                                  "interpolation", "--interpolation",
                                  "Varyings across a triangle: perspective-correct, or affine in screen "
                                  "space (wrong, for teaching)",
                                  "pipeline", "interpolation",
                                  [](auto& s) -> auto& { return s.pipeline.interpolation; }),
                              {}, "affine", "perspective"),
                       "interpolates exactly, in double, at each ray's hit"),
        traded(shadowsKnob(), {}, "none", ""),
        rasterizerOnly(
            traded(number<int>(
                       "shadow-map-size", "--shadow-map-size",
                       "Shadow maps: texels per side (a point light draws six)", "shadow_map", "size", 16,
                       kMaxShadowMapSize, " texels", [](auto& s) -> auto& { return s.shadowMap.size; }),
                   {"256", "512", "1024", "2048", "4096"}, "512", "4096", "shadows", "map"),
            "ray-casts the shadows of every light that casts them"),
        rasterizerOnly(traded(shadowFilter, {"1", "4", "16"}, "1", "16", "shadows", "map"),
                       "ray-casts the shadows of every light that casts them"),
        traded(areaSamplesKnob(), {"4", "16", "64", "256"}, "4", std::to_string(kReferenceAreaSamples)),
        rasterizerOnly(
            traded(number<float>(
                       "shadow-bias", "--shadow-bias",
                       "Shadow maps: constant depth offset, in units of the map's depth resolution",
                       "shadow_map", "bias", 0, 1e6, "",
                       [](auto& s) -> auto& { return s.shadowMap.constantBias; }),
                   {"0.5", "1", "2", "4"}, "", "", "shadows", "map"),
            "ray-casts the shadows of every light that casts them"),
        rasterizerOnly(
            traded(number<float>(
                       "shadow-slope-bias", "--shadow-slope-bias",
                       "Shadow maps: depth offset per unit of the surface's depth slope across a texel",
                       "shadow_map", "slope_bias", 0, 1e6, "",
                       [](auto& s) -> auto& { return s.shadowMap.slopeBias; }),
                   {"0", "1.5", "4"}, "", "", "shadows", "map"),
            "ray-casts the shadows of every light that casts them"),
        rasterizerOnly(
            traded(choice<TransparencyMode>(
                       "transparency", "--transparency",
                       "Transparent triangles back to front, in file order, or in exact per-pixel lists",
                       "transparency", "mode", [](auto& s) -> auto& { return s.transparency.mode; }),
                   {}, "unsorted", "exact"),
            "composites every see-through surface along each ray in depth order"),
        // Used by "sorted" only, but accepted with every mode: switching the mode (in the file or with
        // --transparency) must not make the rest of the file wrong.
        rasterizerOnly(
            traded(choice<SortKey>(
                       "sort-key", "--sort-key",
                       "Depth that orders transparent triangles: the centroid's or the farthest "
                       "vertex's",
                       "transparency", "sort_key", [](auto& s) -> auto& { return s.transparency.key; }),
                   {}, "", "", "transparency", "sorted"),
            "composites every see-through surface along each ray in depth order"),
        traded(choice<CullMode>(
                   "cull", "--cull", "Which faces are not drawn", "pipeline", "cull",
                   [](auto& s) -> auto& { return s.pipeline.cull; }),
               {"back", "none"}, "back", ""),
        traded(changingContent(reflectionKnob()), {}, "", ""),
        // Changes the look (the highlight's size), not how exactly it is drawn: no fast or best value.
        traded(changingContent(choice<BlinnExponent>(
                   "blinn-exponent", "--blinn-exponent",
                   "Blinn-Phong's exponent: the material's shininess n, or 4n so that its "
                   "highlight matches Phong's",
                   "lighting", "blinn_exponent",
                   [](auto& s) -> auto& { return s.lighting.brdf.blinnExponent; })),
               {}, "", ""),
        rasterizerOnly(
            traded(
                choice<Antialiasing>(
                    "aa", "--aa",
                    "Anti-aliasing: supersampling (ssaaN) draws the frame once per sample (2, 4, 8 or 16, at "
                    "the standard sample positions) and averages them; multisampling (msaaN) draws it once, "
                    "testing coverage and depth per sample and shading once per pixel",
                    "pipeline", "antialiasing", [](auto& s) -> auto& { return s.pipeline.antialiasing; }),
                {}, "none", "ssaa16"),
            "averages N×N rays per pixel (--samples)"),
        rasterizerOnly(
            traded(number<int>(
                       "subpixel-bits", "--subpixel-bits",
                       "Rasterizer precision: vertices snapped to 1/2^N of a pixel, N from 0 to 8 (8 as "
                       "GPUs and Mesa)",
                       "pipeline", "subpixel_bits", 0, kMaxSubpixelBits, "",
                       [](auto& s) -> auto& { return s.pipeline.subpixelBits; }),
                   {"0", "2", "4", "8"}, "", "8"),
            "casts its rays through exact points, with no snapping"),
        rasterizerOnly(traded(choice<DepthBufferFormat>(
                                  "depth", "--depth",
                                  "Depth buffer format: 16- or 24-bit unorm, 32-bit float, or float "
                                  "with reversed Z (docs/trade.md)",
                                  "pipeline", "depth", [](auto& s) -> auto& { return s.pipeline.depth; }),
                              {}, "float", "reversed-float"),
                       "finds the nearest surface along each ray in double, with no depth buffer"),
        rasterizerOnly(
            traded(choice<ColorBufferFormat>(
                       "color-buffer", "--color-buffer",
                       "Colour buffer precision, rounded after every write: 8-bit linear, "
                       "half or float (docs/trade.md)",
                       "pipeline", "color_buffer", [](auto& s) -> auto& { return s.pipeline.colorBuffer; }),
                   {}, "", "float"),
            "keeps colours in double until the output is encoded"),
        traded(choice<TextureFilter>(
                   "texture-filter", "--texture-filter",
                   "Texture filtering: the nearest texel, bilinear, or trilinear over mipmaps "
                   "(docs/trade.md)",
                   "textures", "filter", [](auto& s) -> auto& { return s.textures.filter; }),
               {}, "nearest", "trilinear"),
        traded(changingContent(choice<TextureMaps>(
                   "textures", "--textures",
                   "The MTL's texture maps: used, or ignored so surfaces take their materials' colours",
                   "textures", "maps", [](auto& s) -> auto& { return s.textures.maps; })),
               {}, "", ""),
        number<float>(
            "crease-angle", "--crease-angle",
            "Computed normals: faces meeting at a sharper angle (degrees) keep a hard edge", "lighting",
            "crease_angle", 0, 180, " degrees",
            [](auto& s) -> auto& { return s.lighting.creaseAngleDegrees; }),
        traded(changingContent(choice<VertexNormals>(
                   "normals", "--normals",
                   "Computed normals: each face weighted by its triangles' areas, its "
                   "polygon's area, or its angle at the vertex (docs/trade.md)",
                   "lighting", "normals", [](auto& s) -> auto& { return s.lighting.normals; })),
               {}, "", ""),
        rasterizerOnly(traded(choice<MathPrecision>(
                                  "powers", "--powers",
                                  "pow and exp in lighting and fog: the C library's, or polynomials on the "
                                  "float's bits",
                                  "lighting", "powers", [](auto& s) -> auto& { return s.lighting.powers; }),
                              {}, "fast", "exact"),
                       "uses the C library's pow and exp"),
        rasterizerOnly(
            traded(choice<Normalization>(
                       "normalize", "--normalize",
                       "Unit vectors N, L, V, H: 1/sqrt, or the reciprocal square root estimate "
                       "and one Newton step",
                       "lighting", "normalize", [](auto& s) -> auto& { return s.lighting.normalize; }),
                   {}, "fast", "exact"),
            "normalises vectors exactly"),
        rasterizerOnly(
            traded(choice<FresnelModel>(
                       "fresnel", "--fresnel",
                       "Cook-Torrance's Fresnel term: Schlick's approximation or the exact dielectric one",
                       "lighting", "fresnel", [](auto& s) -> auto& { return s.lighting.brdf.fresnel; }),
                   {}, "schlick", "exact"),
            "uses the exact dielectric Fresnel term"),
        // The material's shininess and the fog: what a lecture's exercises vary. The fog's keys are read
        // by the scene file's "fog" section (scene_sections.cpp), which checks them against each other
        // (start and end for linear fog only); the command line accepts each with every mode, as
        // --sort-key with every transparency mode.
        shininessKnob(),
        choice<FogMode>(
            "fog", "--fog",
            "Fog: none, linear (from --fog-start to --fog-end), exp or exp2 (with --fog-density)", "fog",
            "mode", [](auto& s) -> auto& { return s.fog.mode; }),
        number<float>(
            "fog-density", "--fog-density", "Exponential fog's density, per unit of length", "fog", "density",
            0, 1e30, "", [](auto& s) -> auto& { return s.fog.density; }),
        fogRangeKnob("fog-start", "--fog-start", "Linear fog: the distance where it begins", "start",
                     &FogSpec::start),
        fogRangeKnob("fog-end", "--fog-end", "Linear fog: the distance where it is complete", "end",
                     &FogSpec::end),
        choice<NormalDistribution>(
            "distribution", "--distribution",
            "Cook-Torrance's microfacet distribution D: GGX, Beckmann or Torrance-Sparrow's Gaussian",
            "lighting", "distribution", [](auto& s) -> auto& { return s.lighting.brdf.distribution; }),
        materialNumberKnob(
            "ior", "Index of refraction η of every object (F0 = ((1 − η)/(1 + η))²)", 1, 10,
            [](auto& material) -> auto& { return material.ior; }),
        materialNumberKnob(
            "f0", "Reflectance at normal incidence F0 of every object (a dielectric's)", 0, 1,
            [](auto& material) -> auto& { return material.f0; }),
        // Cook-Torrance's other term: a scene file key only.
        choice<GeometryTerm>(
            "geometry", "", "", "lighting", "geometry",
            [](auto& s) -> auto& { return s.lighting.brdf.geometry; }),
    };
}

}  // namespace

std::string knobNumberText(double value) {
    std::ostringstream stream;
    stream << value;
    std::string text = stream.str();
    // 1e+06 → 1e6, 1e-05 → 1e-5: as a user writes it.
    const std::size_t e = text.find('e');
    if (e != std::string::npos) {
        std::size_t digits = e + 1;
        if (text[digits] == '+')
            text.erase(digits, 1);
        else if (text[digits] == '-')
            ++digits;
        while (digits + 1 < text.size() && text[digits] == '0')
            text.erase(digits, 1);
    }
    return text;
}

const std::vector<SceneKnob>& sceneKnobs() {
    static const std::vector<SceneKnob> table = makeTable();
    return table;
}

const SceneKnob* sceneKnobNamed(std::string_view name) {
    for (const SceneKnob& knob : sceneKnobs())
        if (knob.name == name) return &knob;
    return nullptr;
}

Scene defaultKnobScene() {
    Scene scene;
    scene.objects.emplace_back();
    return scene;
}

std::vector<std::string_view> knobKeysOf(std::string_view section) {
    std::vector<std::string_view> keys;
    for (const SceneKnob& knob : sceneKnobs())
        if (knob.section == section) keys.emplace_back(knob.key);
    return keys;
}

std::string SceneKnob::defaultValue() const {
    return defaultNote.empty() ? get(defaultKnobScene()) : "";
}

std::string SceneKnob::allowed() const {
    if (kind == KnobKind::Names) return scene_file::quotedList(names, " or ");
    if (!only.empty()) {
        std::string list;
        for (std::size_t i = 0; i < only.size(); ++i) {
            if (i > 0) list += i + 1 == only.size() ? " or " : ", ";
            list += std::to_string(only[i]);
        }
        return list + unit;
    }
    return "from " + knobNumberText(lowest) + " to " + knobNumberText(highest) + unit;
}

bool SceneKnob::allows(double value) const {
    // A number knob keeps a float, and a scene file's numbers are read as floats: compared as floats,
    // so that a documented bound is accepted at the bound (a scene file's 1e30 is the float
    // 1.0000000150e30, above the double 1e30).
    const bool inRange = kind == KnobKind::Number
                             ? float(value) >= float(lowest) && float(value) <= float(highest)
                             : value >= lowest && value <= highest;
    if (!inRange) return false;
    if (kind == KnobKind::WholeNumber && value != std::floor(value)) return false;
    if (only.empty()) return true;
    for (const int allowedValue : only)
        if (value == allowedValue) return true;
    return false;
}

std::optional<std::string> SceneKnob::commandLineProblem(const std::string& text) const {
    if (kind == KnobKind::Names || allows(std::strtod(text.c_str(), nullptr))) return std::nullopt;
    return flag + " must be " + allowed() + " (got " + text + ")";
}

}  // namespace facet
