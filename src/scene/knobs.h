// The knobs: every choice of how a scene is drawn that the command line, a scene file and the trade
// can set, each declared once. An entry holds everything about its knob: its name, its command-line
// flag and that flag's one help text, its scene file key, the values it takes and their check, its
// default (read from a default Scene, never written twice), its fast and exact values for the trade,
// the knob it needs, and how it reads and sets its field of a Scene. The command line (render, step,
// bench, trade, compare and step's --versus), the scene reader and the trade all read this table, so
// adding a knob is adding its entry here and using its field in the stage it changes.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene.h"

namespace facet {

// What a knob's values are.
enum class KnobKind : std::uint8_t {
    Names,        // one of the names of an enum's table (pipeline/names.h)
    WholeNumber,  // a whole number from `lowest` to `highest`, and one of `only` when that is given
    Number,       // a number from `lowest` to `highest`
};

struct SceneKnob {
    std::string name;  // what the trade's --knobs names: "aa"
    std::string flag;  // "--aa"; empty: a scene file key only
    std::string help;  // the flag's help text, which every command shows; the default is added to it
    // The scene file's key, "section.key": "pipeline.antialiasing"; empty: the command line only.
    std::string section, key;
    KnobKind kind = KnobKind::Names;
    std::vector<std::string> names;  // Names: every name, in its table's order
    double lowest = 0, highest = 0;  // numbers: both included
    std::vector<int> only;           // WholeNumber: when given, the only values allowed
    std::string unit;                // numbers: after the range in messages (" texels")
    // Instead of "(default X)" in the help, for a knob whose default is the scene's own (every light's
    // "shadows"); such a knob has no default value, and the trade's default preset leaves it alone.
    std::string defaultNote;
    // The trade (trade/knobs.h): the values it tries (empty: the knob is not traded), those of its
    // fast and best presets (empty: the preset leaves the knob as the scene has it), and the knob and
    // value this one acts under ({"shadows", "map"} for the shadow map's size).
    std::vector<std::string> tradeValues;
    std::string fastValue, bestValue;
    std::string needsKnob, needsValue;
    // Whether setting the knob to `value` changes what a scene `baseline` shows (its textures, its
    // reflection model, shadows it does not have) rather than how exactly the scene is drawn: the
    // trade lists such settings apart from the accuracy knobs and no preset sets them. Empty: never.
    std::function<bool(const Scene& baseline, const std::string& value)> changesContent;
    // What the exact reference renderer does in the knob's place, for messages ("averages N×N rays per
    // pixel (--samples)"); empty: the reference follows the knob. Such a knob is one of the rasterizer's
    // approximations, which `facet render --renderer reference` refuses on its command line rather than
    // ignore.
    std::string referenceInstead;
    // The knob's value in a scene, as the flag takes it; empty when its objects or lights disagree.
    std::function<std::string(const Scene&)> get;
    // Sets the knob's field of `scene` to `value`, which check() allows.
    std::function<void(Scene&, const std::string&)> set;

    // "pipeline.antialiasing".
    std::string scenePath() const { return section + "." + key; }
    // The value of a scene no file or option has changed; empty with a defaultNote.
    std::string defaultValue() const;
    // What a value must be, for messages: "from 16 to 8192 texels", "1, 4 or 16 depth comparisons per
    // point", "\"none\", \"ssaa2\" or …".
    std::string allowed() const;
    // Whether `value` is allowed (numbers: in the range and, when given, one of `only`).
    bool allows(double value) const;
    // The command line's check of `text` (as typed, already a number of the knob's kind): nothing when
    // allowed, else the one-line message "--shadow-filter must be 1, 4 or 16 … (got 3)".
    std::optional<std::string> commandLineProblem(const std::string& text) const;
};

// Every knob, in the order the trade runs them and the commands list their flags.
const std::vector<SceneKnob>& sceneKnobs();

// The entry named `name` (as --knobs names it); nullptr when there is none.
const SceneKnob* sceneKnobNamed(std::string_view name);

// The scene no file or option has changed: a default Scene with one default object, whose values are
// the knobs' defaults.
Scene defaultKnobScene();

// The keys of a scene file's section that are knobs ("pipeline" → "cull", "interpolation", …).
std::vector<std::string_view> knobKeysOf(std::string_view section);

// A number as the knobs' values are written: 1.5 → "1.5", 2048 → "2048", 1e6 → "1e6".
std::string knobNumberText(double value);

}  // namespace facet
