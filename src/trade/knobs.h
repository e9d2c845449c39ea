// The accuracy knobs `facet trade` turns, one row each, made from the knobs' table (scene/knobs.h): the
// command-line flag of `facet render` that selects it, the values it takes, and which of them the
// default, fast and best presets use. A knob setting is the words a user would type (`--shading flat`),
// so every label of the trade is a flag a user can copy and every setting goes through the render
// command's own parser.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace facet {

struct Knob {
    std::string name;                 // what --knobs selects: "shading"
    std::string flag;                 // "--shading"
    std::vector<std::string> values;  // every value the trade tries, as the flag takes them
    // The value with the flag absent from a plain model; empty: the scene's own (the default preset
    // leaves the knob alone).
    std::string defaultValue;
    // The presets' values; empty: that preset leaves the knob as the scene has it (a knob that changes
    // what is drawn rather than how exactly, like the reflection model, has no best value).
    std::string fastValue, bestValue;
    // The knob acts only under this other knob's value ({"shadows", "map"} for the shadow map's size):
    // its settings carry those words first, and a preset sets it only when the preset's own value of
    // that knob is the one needed. Empty: always.
    std::string needsKnob, needsValue;
    // The knob's value in a scene; empty when its objects or lights disagree. A setting whose value the
    // baseline already has is skipped.
    std::function<std::string(const Scene&)> valueIn;
    // Whether the value changes what the scene `baseline` shows rather than how exactly it is drawn
    // (scene/knobs.h); empty: never.
    std::function<bool(const Scene& baseline, const std::string& value)> changesContent;
};

// Every knob of scene/knobs.h with values to try, in that table's order (the order the trade runs them).
const std::vector<Knob>& knobTable();

// The row named `name`; throws InputError listing the valid names when there is none.
const Knob& knobNamed(const std::string& name);

// "shading,shadows" → those rows, in the table's order; empty text: every row. Throws InputError for
// an unknown name (the message lists the valid ones) or an empty item.
std::vector<const Knob*> selectKnobs(const std::string& list);

// One run of the trade: the baseline, one knob at one value, or a preset.
struct TradeSetting {
    std::string knob;                // the knob's name; "baseline"; "preset"
    std::string value;               // the knob's value; "" for the baseline; the preset's name
    std::vector<std::string> words;  // the command-line words that select it, on top of the user's
    std::string label() const;       // the words joined by spaces; "baseline" without words
};

// The knob at `value`: its prerequisite's words, then its own.
TradeSetting knobSetting(const Knob& knob, const std::string& value);

// Preset `name` ("fast", "default", "best"): each knob of the table at its value for that preset, a
// knob whose prerequisite the preset does not set left out, and so are the knobs named in
// `leftAsTheScene` (with the knobs that need them) and the knobs whose value would change what the
// scene shows (changesContent: the default preset leaves the textures and the reflection model alone).
TradeSetting presetSetting(const std::string& name, const std::vector<std::string>& leftAsTheScene = {});
inline const std::vector<std::string> kPresetNames = {"fast", "default", "best"};

// Whether `scene` already has every value `setting` sets (by the knobs' valueIn): rendering it would
// repeat the baseline.
bool sceneHasSetting(const Scene& scene, const TradeSetting& setting);

// Whether `setting` changes what `baseline` shows (some knob it sets, its prerequisite's included, at a
// value other than the baseline's own whose changesContent holds): `--textures off`, `--reflection phong`,
// `--shadows map
// --shadow-map-size 512` on a scene without shadows. Such a setting is not an approximation of the
// reference (the scene as written), so the trade ranks it apart: never on the Pareto front.
bool settingChangesContent(const Scene& baseline, const TradeSetting& setting);

}  // namespace facet
