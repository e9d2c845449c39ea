#include "step/user_shader_view.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "render/user_shaders.h"
#include "step/views.h"

namespace facet::step {

namespace {

// Where the uniform `name` was set: the last --uniform that names it, else a scene file's "shader".
std::string originOf(const Scene* scene, std::string_view name) {
    if (!scene) return "the scene";
    std::string origin;
    const auto look = [&](const std::vector<UniformValue>& values) {
        for (const UniformValue& v : values)
            if (v.name == name) origin = v.origin.empty() ? "the scene" : v.origin;
    };
    if (scene->shader) look(scene->shader->uniforms);
    for (const ObjectSpec& object : scene->objects)
        if (object.shader) look(object.shader->uniforms);
    look(scene->uniforms);  // --uniform wins
    return origin.empty() ? "the scene" : origin;
}

bool finite(const float* v, int count) {
    for (int k = 0; k < count; ++k)
        if (!std::isfinite(v[k])) return false;
    return true;
}

bool hasNaN(const float* v, int count) {
    for (int k = 0; k < count; ++k)
        if (std::isnan(v[k])) return true;
    return false;
}

std::string valuesText(const float* v, int count) {
    if (count == 1) return number(v[0]);
    std::string text = "(";
    for (int k = 0; k < count; ++k)
        text += number(v[k]) + (k + 1 < count ? ", " : ")");
    return text;
}

// The marker after a value that is not a finite number.
const char* kNaNMark = "  <- NaN!";
const char* kInfMark = "  <- infinite!";

struct NonFiniteSeen {
    bool nan = false, inf = false;
    std::string mark(const float* v, int count) {
        if (finite(v, count)) return "";
        if (hasNaN(v, count)) {
            nan = true;
            return kNaNMark;
        }
        inf = true;
        return kInfMark;
    }
    void explain(std::ostream& out) const {
        if (nan)
            out << "NaN (not a number) comes from 0/0, 0·∞, ∞ − ∞ or the square root of a negative:\n"
                   "  normalize of a zero vector? A NaN spreads into every value computed from it.\n";
        if (inf) out << "Infinite: a division by zero (or a number too large for a float)?\n";
    }
};

nlohmann::json jsonNumber(float v) {
    if (std::isnan(v)) return "NaN";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    return v;
}

nlohmann::json jsonValues(const float* v, int count) {
    if (count == 1) return jsonNumber(v[0]);
    nlohmann::json a = nlohmann::json::array();
    for (int k = 0; k < count; ++k)
        a.push_back(jsonNumber(v[k]));
    return a;
}

bool sameBits(const vec4& a, const vec4& b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

}  // namespace

UserShaderTrace traceUserShader(const PreparedDraw& draw, const SurfaceUniforms& uniforms,
                                const DrawState& state, const FragmentEvent& f, const Scene* scene) {
    const ShaderModule& module = *draw.userShader.module;
    UserShaderTrace trace;
    trace.name = std::string(module.name);
    trace.file = draw.userShader.label;
    trace.x = f.x;
    trace.y = f.y;
    trace.triangle = f.triangle;
    trace.fate = f.fate;
    for (std::uint32_t k = 0; k < module.uniforms.size(); ++k) {
        const UniformInfo& info = module.uniforms[k];
        UserUniformShown shown{std::string(info.name), info.type,     std::string(info.help),
                               info.defaults,          info.defaults, {}};
        for (const UniformSetting& setting :
             draw.userUniforms)  // later settings win, as uniformsOf sets them
            if (setting.index == k) {
                shown.value = setting.value;
                shown.setBy = originOf(scene, info.name);
            }
        trace.uniforms.push_back(std::move(shown));
    }
    trace.varyingNames.assign(module.varyingNames.begin(), module.varyingNames.end());
    trace.varyings.assign(f.varyings.begin(), f.varyings.begin() + f.varyingCount);
    trace.barycentrics = f.barycentrics;
    trace.invW = f.invW;
    trace.uvDerivatives = f.uvDerivatives;
    trace.pipelineOutput = f.shaded;
    trace.shaderRan = f.fate != FragmentFate::DepthFailed;
    if (!trace.shaderRan) return trace;
    const ShaderCall call{&state, &uniforms, draw.userUniforms, draw.vertices, draw.indices};
    FragmentInput in;
    in.varyings = f.varyings.data();
    in.uvDerivatives = {vec2(f.uvDerivatives[0], f.uvDerivatives[1]),
                        vec2(f.uvDerivatives[2], f.uvDerivatives[3])};
    in.barycentric = f.barycentrics;
    ShaderTrace recorded;
    vec4 color(0.0f);
    trace.discarded = !module.shadeFragment(in, call, color, &recorded);
    trace.output = color;
    for (const RecordedValue& v : recorded.values)
        trace.recorded.push_back({std::string(v.name), v.count, v.values});
    trace.matchesPipeline = !trace.discarded && sameBits(trace.output, trace.pipelineOutput);
    return trace;
}

int nonFiniteCount(const UserShaderTrace& t) {
    int count = 0;
    for (const UserRecordedValue& v : t.recorded)
        count += !finite(v.values.data(), v.count);
    if (t.shaderRan && !t.discarded) count += !finite(&t.output.x, 4);
    for (float v : t.varyings)
        count += !std::isfinite(v);
    return count;
}

std::vector<Screen> userShaderScreens(const UserShaderTrace& t) {
    std::vector<Screen> screens;
    // The file's name in titles (one line), the file as given in the text.
    const std::string named = t.name + " (" + std::filesystem::path(t.file).filename().string() + ")";
    {
        std::ostringstream out;
        out << wrapText("This fragment is shaded by a shader of your own: " + t.name + " (" + t.file + ")" +
                            ", compiled into a module that the pipeline calls instead of the built-in "
                            "lighting.",
                        80, 0);
        out << "\nIts uniforms are the scene's (matrices, lights, material, fog: SceneUniforms)\n"
               "and those it declares (kUniforms). Their values for this draw:\n\n";
        if (t.uniforms.empty()) out << "  (it declares none)\n";
        for (const UserUniformShown& u : t.uniforms) {
            const int n = componentCount(u.type);
            std::string line = (u.setBy.empty() ? "  " : "* ") + u.name + " (" + std::string(nameOf(u.type)) +
                               ") = " + uniformValueText(u.type, u.value);
            if (u.setBy.empty())
                line += ", the default";
            else
                line += ", set by " + u.setBy + " (default " + uniformValueText(u.type, u.defaults) + ")";
            if (!finite(u.value.data(), n)) line += kNaNMark;
            out << wrapText(line, 80, 4);
            if (!u.help.empty()) out << wrapText("    " + u.help, 80, 4);
        }
        if (!t.uniforms.empty())
            out << "\n* set by the scene or --uniform; the others keep their defaults.\n";
        screens.push_back({"uniforms", "Your shader: " + named + " and its uniforms", out.str()});
    }
    {
        std::ostringstream out;
        NonFiniteSeen seen;
        out << wrapText("The fragment part of " + t.name +
                            " ran once more on this fragment alone, on the varyings the pipeline "
                            "interpolated for it: the same code the frame ran eight fragments at a time.",
                        80, 0)
            << "Its input, at λ = " << vectorText(t.barycentrics) << ", 1/w = " << number(t.invW) << ":\n";
        std::string line;
        for (std::size_t k = 0; k < t.varyings.size(); ++k) {
            std::string item = "  ";
            item += k < t.varyingNames.size() ? t.varyingNames[k] : "varying " + std::to_string(k);
            item += " = ";
            item += number(t.varyings[k]);
            item += seen.mark(&t.varyings[k], 1);
            if (!line.empty() && line.size() + item.size() > 78) {
                out << line << "\n";
                line.clear();
            }
            line += item;
        }
        if (!line.empty()) out << line << "\n";
        if (t.uvDerivatives != std::array<float, 4>{})
            out << "  ∂(u,v)/∂x = " << vectorText(vec2(t.uvDerivatives[0], t.uvDerivatives[1]))
                << ", ∂(u,v)/∂y = " << vectorText(vec2(t.uvDerivatives[2], t.uvDerivatives[3])) << "\n";
        std::string title;
        if (!t.shaderRan) {
            out << "\nThe depth test failed before the fragment part ran (early depth test): it\n"
                   "did not run for this fragment, and recorded nothing.\n";
            title = "Your shader: not run (the depth test failed first)";
        } else {
            out << "\n";
            if (t.recorded.empty())
                out << "It recorded nothing: gl.record(\"name\", value) in its fragment() shows a\n"
                       "value here.\n";
            else
                out << "What it recorded (gl.record), in order:\n";
            for (const UserRecordedValue& v : t.recorded)
                out << wrapText("  " + v.name + " = " + valuesText(v.values.data(), v.count) +
                                    seen.mark(v.values.data(), v.count),
                                80, 6);
            if (t.discarded) {
                out << "\nIts output: discarded (it returned FragmentOut with discard true): no\n"
                       "depth and no colour are written for this fragment.\n";
                title = "Your shader: " + t.name + " discarded the fragment";
            } else {
                out << "\nIts output: colour " << vectorText(t.output) << seen.mark(&t.output.x, 4) << "\n";
                if (t.matchesPipeline)
                    out << "The frame's output for this fragment is the same, bit for bit.\n";
                else
                    out << "The frame computed " << vectorText(t.pipelineOutput)
                        << " (eight lanes at once; one lane may round differently).\n";
                title = "Your shader: " + t.name + "'s fragment part and its output";
            }
        }
        if (seen.nan || seen.inf) out << "\n";
        seen.explain(out);
        screens.push_back({"shader", title, out.str()});
    }
    return screens;
}

nlohmann::json toJson(const UserShaderTrace& t) {
    nlohmann::json uniforms = nlohmann::json::array();
    for (const UserUniformShown& u : t.uniforms) {
        const int n = componentCount(u.type);
        nlohmann::json j = {{"name", u.name},
                            {"type", nameOf(u.type)},
                            {"value", jsonValues(u.value.data(), n)},
                            {"default", jsonValues(u.defaults.data(), n)},
                            {"set", !u.setBy.empty()}};
        if (!u.setBy.empty()) j["setBy"] = u.setBy;
        if (!u.help.empty()) j["help"] = u.help;
        uniforms.push_back(std::move(j));
    }
    nlohmann::json varyings = nlohmann::json::object();
    for (std::size_t k = 0; k < t.varyings.size(); ++k)
        varyings[k < t.varyingNames.size() ? t.varyingNames[k] : "varying " + std::to_string(k)] =
            jsonNumber(t.varyings[k]);
    nlohmann::json recorded = nlohmann::json::array();
    for (const UserRecordedValue& v : t.recorded)
        recorded.push_back({{"name", v.name},
                            {"value", jsonValues(v.values.data(), v.count)},
                            {"finite", finite(v.values.data(), v.count)}});
    nlohmann::json j = {{"name", t.name},
                        {"file", t.file},
                        {"pixel", {t.x, t.y}},
                        {"fate", nameOf(t.fate)},
                        {"uniforms", std::move(uniforms)},
                        {"varyings", std::move(varyings)},
                        {"barycentrics", {t.barycentrics.x, t.barycentrics.y, t.barycentrics.z}},
                        {"invW", jsonNumber(t.invW)},
                        {"uvDerivatives", jsonValues(t.uvDerivatives.data(), 4)},
                        {"shaderRan", t.shaderRan},
                        {"recorded", std::move(recorded)},
                        {"nonFinite", nonFiniteCount(t)}};
    if (t.shaderRan) {
        j["discarded"] = t.discarded;
        if (!t.discarded) {
            j["output"] = jsonValues(&t.output.x, 4);
            j["matchesPipeline"] = t.matchesPipeline;
        }
    }
    return j;
}

}  // namespace facet::step
