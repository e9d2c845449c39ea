#include "trade/knobs.h"

#include <algorithm>
#include <sstream>

#include "base/errors.h"
#include "base/quote.h"
#include "pipeline/names.h"

namespace facet {

namespace {

// Every name of E's table, in the table's order: the values an enum knob tries.
template <class E>
std::vector<std::string> allNames() {
    std::vector<std::string> names;
    for (const auto& entry : enumNames(E{}))
        names.emplace_back(entry.name);
    return names;
}

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

std::string numberText(double value) {  // 1.5 → "1.5", 2048 → "2048": as the knob's values are written
    std::ostringstream text;
    text << value;
    return text.str();
}

std::string shadowsIn(const Scene& scene) {
    if (scene.shadows) return std::string(nameOf(*scene.shadows));
    if (scene.lights.empty()) return std::string(nameOf(ShadowMethod::None));  // the default light's
    return commonName<ShadowMethod>(scene.lights, [](const LightSpec& light) { return light.shadows; });
}

template <class E>
std::string nameText(E value) {
    return std::string(nameOf(value));
}

std::string shadingIn(const Scene& scene) {
    return commonName<ShadingFrequency>(scene.objects, [&](const ObjectSpec& object) {
        return object.shading.value_or(scene.lighting.shadingOrDefault());
    });
}

std::string reflectionIn(const Scene& scene) {
    return commonName<ReflectionModel>(scene.objects, [&](const ObjectSpec& object) {
        return object.reflection.value_or(scene.lighting.model);
    });
}

// The table. Notes on rows:
//   cull: front-face culling draws the wrong side, not a trade; culling back faces is the fast choice (the
//     same image for closed models); no best value, the reference culls as the scene does.
//   reflection: a choice of look more than of accuracy: no fast or best value, the reference keeps the
//     scene's.
//   the shadow map's bias and slope bias: tuning, neither faster nor slower: no fast or best value.
//   shadows: whether a light casts shadows is the scene's choice; the reference ray-casts the shadows
//     of the lights that cast them, so the best preset keeps the scene's (adding shadows to a scene
//     without any would move it away from its reference); the fast preset drops them.
//   colour buffer: the narrower formats are emulated by rounding a float buffer (pipeline/blend.h), so
//     they cost time rather than save it: no fast value.
//   textures and normals: what the model looks like (its maps; how its smooth normals are made) rather
//     than how exactly it is drawn; the reference draws the scene's own: no fast or best value.
//   subpixel bits: no measurable speed difference (the edge functions are integers at any precision).
std::vector<Knob> makeKnobTable() {
    using S = const Scene&;
    // One row per knob, its value in a scene on the line below.
    // clang-format off
    return {
        // name               flag                   values                                  default        fast        best           needs
        {"shading",           "--shading",           allNames<ShadingFrequency>(),           "phong",       "flat",     "phong",       "", "",
         shadingIn},
        {"interpolation",     "--interpolation",     allNames<Interpolation>(),              "perspective", "affine",   "perspective", "", "",
         [](S s) { return nameText(s.pipeline.interpolation); }},
        {"shadows",           "--shadows",           allNames<ShadowMethod>(),               "",            "none",     "",            "", "",
         shadowsIn},
        {"shadow-map-size",   "--shadow-map-size",   {"256", "512", "1024", "2048", "4096"}, "2048",        "512",      "4096",        "shadows", "map",
         [](S s) { return numberText(s.shadowMap.size); }},
        {"shadow-filter",     "--shadow-filter",     {"1", "4", "16"},                       "4",           "1",        "16",          "shadows", "map",
         [](S s) { return numberText(s.shadowMap.filterTaps); }},
        {"shadow-bias",       "--shadow-bias",       {"0.5", "1", "2", "4"},                 "1",           "",         "",            "shadows", "map",
         [](S s) { return numberText(s.shadowMap.constantBias); }},
        {"shadow-slope-bias", "--shadow-slope-bias", {"0", "1.5", "4"},                      "1.5",         "",         "",            "shadows", "map",
         [](S s) { return numberText(s.shadowMap.slopeBias); }},
        {"transparency",      "--transparency",      allNames<TransparencyMode>(),           "sorted",      "unsorted", "exact",       "", "",
         [](S s) { return nameText(s.transparency.mode); }},
        {"sort-key",          "--sort-key",          allNames<SortKey>(),                    "centroid",    "",         "",            "transparency", "sorted",
         [](S s) { return nameText(s.transparency.key); }},
        {"cull",              "--cull",              {"back", "none"},                       "back",        "back",     "",            "", "",
         [](S s) { return nameText(s.pipeline.cull); }},
        {"reflection",        "--reflection",        allNames<ReflectionModel>(),            "blinn-phong", "",         "",            "", "",
         reflectionIn},
        {"aa",                "--aa",                allNames<Antialiasing>(),               "none",        "none",     "ssaa16",      "", "",
         [](S s) { return nameText(s.pipeline.antialiasing); }},
        {"subpixel-bits",     "--subpixel-bits",     {"0", "2", "4", "8"},                   "8",           "",         "8",           "", "",
         [](S s) { return numberText(s.pipeline.subpixelBits); }},
        {"depth",             "--depth",             allNames<DepthBufferFormat>(),          "float",       "float",    "reversed-float", "", "",
         [](S s) { return nameText(s.pipeline.depth); }},
        {"color-buffer",      "--color-buffer",      allNames<ColorBufferFormat>(),          "float",       "",         "float",       "", "",
         [](S s) { return nameText(s.pipeline.colorBuffer); }},
        {"texture-filter",    "--texture-filter",    allNames<TextureFilter>(),              "bilinear",    "nearest",  "trilinear",   "", "",
         [](S s) { return nameText(s.textures.filter); }},
        {"textures",          "--textures",          allNames<TextureMaps>(),                "on",          "",         "",            "", "",
         [](S s) { return nameText(s.textures.maps); }},
        {"normals",           "--normals",           allNames<VertexNormals>(),              "polygon-area", "",        "",            "", "",
         [](S s) { return nameText(s.lighting.normals); }},
        {"powers",            "--powers",            allNames<MathPrecision>(),              "fast",        "fast",     "exact",       "", "",
         [](S s) { return nameText(s.lighting.powers); }},
        {"normalize",         "--normalize",         allNames<Normalization>(),              "exact",       "fast",     "exact",       "", "",
         [](S s) { return nameText(s.lighting.normalize); }},
        {"fresnel",           "--fresnel",           allNames<FresnelModel>(),               "schlick",     "schlick",  "exact",       "", "",
         [](S s) { return nameText(s.lighting.brdf.fresnel); }},
    };
    // clang-format on
}

std::string validNames() {
    std::string names;
    for (const Knob& knob : knobTable()) {
        if (!names.empty()) names += ", ";
        names += knob.name;
    }
    return names;
}

}  // namespace

const std::vector<Knob>& knobTable() {
    static const std::vector<Knob> table = makeKnobTable();
    return table;
}

const Knob& knobNamed(const std::string& name) {
    for (const Knob& knob : knobTable())
        if (knob.name == name) return knob;
    std::string message = "--knobs: unknown knob ";
    message += inQuotes(name);
    message += " (valid: ";
    message += validNames();
    message += ")";
    throw InputError(message);
}

std::vector<const Knob*> selectKnobs(const std::string& list) {
    std::vector<const Knob*> selected;
    if (list.empty()) {
        for (const Knob& knob : knobTable())
            selected.push_back(&knob);
        return selected;
    }
    std::vector<bool> chosen(knobTable().size(), false);
    std::size_t start = 0;
    while (start <= list.size()) {  // every item between commas, a trailing empty one included
        const std::size_t comma = std::min(list.find(',', start), list.size());
        const std::string name = list.substr(start, comma - start);
        if (name.empty()) {
            std::string message = "--knobs expects knob names separated by commas (got ";
            message += inQuotes(list);
            message += "; valid: ";
            message += validNames();
            message += ")";
            throw InputError(message);
        }
        chosen[static_cast<std::size_t>(&knobNamed(name) - knobTable().data())] = true;
        start = comma + 1;
    }
    for (std::size_t k = 0; k < chosen.size(); ++k)
        if (chosen[k]) selected.push_back(&knobTable()[k]);
    return selected;
}

std::string TradeSetting::label() const {
    if (words.empty()) return knob == "baseline" ? "baseline" : knob + " " + value + " (no change)";
    std::string text;
    for (const std::string& word : words) {
        if (!text.empty()) text += " ";
        text += word;
    }
    return text;
}

TradeSetting knobSetting(const Knob& knob, const std::string& value) {
    TradeSetting setting{knob.name, value, {}};
    if (!knob.needsKnob.empty()) setting.words = {knobNamed(knob.needsKnob).flag, knob.needsValue};
    setting.words.push_back(knob.flag);
    setting.words.push_back(value);
    return setting;
}

TradeSetting presetSetting(const std::string& name, const std::vector<std::string>& leftAsTheScene) {
    TradeSetting setting{"preset", name, {}};
    static const std::string kScenesOwn;
    auto valueFor = [&](const Knob& knob) -> const std::string& {
        if (std::find(leftAsTheScene.begin(), leftAsTheScene.end(), knob.name) != leftAsTheScene.end())
            return kScenesOwn;
        return name == "fast" ? knob.fastValue : name == "best" ? knob.bestValue : knob.defaultValue;
    };
    for (const Knob& knob : knobTable()) {
        const std::string& value = valueFor(knob);
        if (value.empty()) continue;
        if (!knob.needsKnob.empty() && valueFor(knobNamed(knob.needsKnob)) != knob.needsValue) continue;
        setting.words.push_back(knob.flag);
        setting.words.push_back(value);
    }
    return setting;
}

bool sceneHasSetting(const Scene& scene, const TradeSetting& setting) {
    for (std::size_t w = 0; w + 1 < setting.words.size(); w += 2) {
        const Knob* knob = nullptr;
        for (const Knob& row : knobTable())
            if (row.flag == setting.words[w]) knob = &row;
        if (!knob || knob->valueIn(scene) != setting.words[w + 1]) return false;
    }
    return true;
}

}  // namespace facet
