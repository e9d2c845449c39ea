#include "trade/knobs.h"

#include <algorithm>
#include <sstream>

#include "base/errors.h"
#include "base/quote.h"
#include "scene/knobs.h"

namespace facet {

namespace {

// The knobs of the table (scene/knobs.h) that the trade turns: those with values to try.
std::vector<Knob> makeKnobTable() {
    std::vector<Knob> table;
    for (const SceneKnob& knob : sceneKnobs())
        if (!knob.tradeValues.empty())
            table.push_back({knob.name, knob.flag, knob.tradeValues, knob.defaultValue(), knob.fastValue,
                             knob.bestValue, knob.needsKnob, knob.needsValue, knob.get, knob.changesContent});
    return table;
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
        // A preset draws the scene itself, faster or more exactly: a knob whose preset value changes what
        // a scene shows (the default preset's textures or reflection model where the scene has others)
        // is left as the scene has it. The default scene stands for any: only the shadows knob's rule
        // reads the scene, and its one preset value, none, adds nothing to any scene.
        if (knob.changesContent && knob.changesContent(defaultKnobScene(), value)) continue;
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

bool settingChangesContent(const Scene& baseline, const TradeSetting& setting) {
    for (std::size_t w = 0; w + 1 < setting.words.size(); w += 2)
        for (const Knob& knob : knobTable())
            if (knob.flag == setting.words[w] && knob.changesContent &&
                knob.valueIn(baseline) != setting.words[w + 1] &&  // the baseline's own changes nothing
                knob.changesContent(baseline, setting.words[w + 1]))
                return true;
    return false;
}

}  // namespace facet
