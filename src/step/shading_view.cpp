#include "step/shading_view.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <string>
#include <string_view>

namespace facet::step {

// ---- Recomputing the shading with the records on ---------------------------------------------------

namespace {

using PerVertex = PerVertexSurface<ShadingFrequency::Gouraud>;  // flat shading runs the same functions

// The vertex lighting at one corner, as the vertex shader ran it.
CornerShading shadeCorner(const SurfaceUniforms& u, const std::array<MeshVertex, 3>& corners, int corner) {
    CornerShading shading;
    shading.corner = corner;
    shading.vertex = corners[static_cast<std::size_t>(corner)];
    const VertexOut<PerVertex::VertexInputsT<float>> inputs = PerVertex::vertexInputs(shading.vertex, u);
    shading.invW = 1.0f / inputs.position.w;
    const PerVertex::VaryingsT<float> out =
        PerVertex::lightVertex<float>(inputs.varyings, u, &shading.lighting);
    shading.lighting.modulated = out.modulated;
    shading.lighting.added = out.added;
    return shading;
}

// The fragment's texture-coordinate derivatives as the shader takes them.
TexCoordDerivativesT<float> uvDerivativesOf(const FragmentEvent& f) {
    const auto& d = f.uvDerivatives;
    return {vec2(d[0], d[1]), vec2(d[2], d[3])};
}

// The fragment's varyings in the layout of the shader's VaryingsT<float>.
template <class Varyings>
Varyings varyingsOf(const FragmentEvent& f) {
    Varyings in;
    std::memcpy(&in, f.varyings.data(), sizeof in);
    return in;
}

}  // namespace

ShadingTrace traceShading(const SurfaceUniforms& u, ShadingFrequency frequency, const FragmentEvent& f,
                          const std::array<MeshVertex, 3>& corners, int provokingCorner) {
    ShadingTrace trace;
    trace.frequency = frequency;
    trace.x = f.x;
    trace.y = f.y;
    trace.triangle = f.triangle;
    trace.fate = f.fate;
    trace.barycentrics = f.barycentrics;
    trace.invW = f.invW;
    trace.provokingCorner = provokingCorner;
    trace.pipelineOutput = f.shaded;
    trace.shaderRan = f.fate != FragmentFate::DepthFailed && f.fate != FragmentFate::Discarded;
    if (const Texture* map = u.diffuseMap ? u.diffuseMap : u.emissionMap) {
        const TexCoordDerivativesT<float> d = uvDerivativesOf(f);
        const float lod = textureLod(*map, d.dx, d.dy);  // lod = log2 ρ, so ρ = 2^lod
        trace.texture = {.mapped = true,
                         .filter = u.textureFilter,
                         .width = map->width,
                         .height = map->height,
                         .levels = map->levelCount(),
                         .uvDx = d.dx,
                         .uvDy = d.dy,
                         .rho = std::exp2(lod),
                         .lod = lod};
    }

    if (frequency == ShadingFrequency::Phong) {
        using Shader = PerPixelSurface;
        trace.fragment.result = Shader::shade<float>(varyingsOf<Shader::VaryingsT<float>>(f), u, 1u,
                                                     uvDerivativesOf(f), &trace.fragment);
    } else {
        if (frequency == ShadingFrequency::Gouraud) {
            for (int corner = 0; corner < 3; ++corner)
                trace.corners.push_back(shadeCorner(u, corners, corner));
            // Perspective-correct interpolation (OpenGL 2.1 §3.5.1): each corner's value weighted by
            // λi·(1/wi), divided by their sum, the pixel's 1/w.
            float sum = 0.0f;
            for (int i = 0; i < 3; ++i)
                sum += f.barycentrics[i] * trace.corners[static_cast<std::size_t>(i)].invW;
            trace.weightsMatchCorners = std::abs(sum - f.invW) <= 1e-3f * std::abs(f.invW);
            for (int i = 0; i < 3; ++i) {
                const CornerShading& c = trace.corners[static_cast<std::size_t>(i)];
                const float mu = f.barycentrics[i] * c.invW / f.invW;
                trace.perspectiveWeights[i] = mu;
                trace.mixedModulated += mu * c.lighting.modulated;
                trace.mixedAdded += mu * c.lighting.added;
            }
        } else {
            trace.corners.push_back(shadeCorner(u, corners, provokingCorner));
        }
        // Flat and Gouraud run the same fragment function; only which varyings are flat differs.
        using Shader = PerVertexSurface<ShadingFrequency::Gouraud>;
        trace.fragment.result = Shader::shade<float>(varyingsOf<Shader::VaryingsT<float>>(f), u, 1u,
                                                     uvDerivativesOf(f), &trace.fragment);
    }
    trace.matchesPipeline = std::memcmp(&trace.fragment.result, &f.shaded, sizeof f.shaded) == 0;
    trace.uniforms = u;
    trace.uniforms.diffuseMap = nullptr;
    trace.uniforms.emissionMap = nullptr;
    return trace;
}

// ---- Text --------------------------------------------------------------------------------------------

namespace {

constexpr std::size_t kColumns = 80;

// Floats to 4 significant digits, enough to check each step by hand.
std::string num(float v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.4g", static_cast<double>(v));
    return buffer;
}
std::string vec(const vec3& v) {
    // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on "(" + std::string.
    std::string text(1, '(');
    text.append(num(v.x)).append(", ").append(num(v.y)).append(", ").append(num(v.z)).append(")");
    return text;
}
std::string rgb(const vec3& c) {
    return "RGB" + vec(c);
}
std::string rgba(const vec4& c) {
    return "RGBA(" + num(c.r) + ", " + num(c.g) + ", " + num(c.b) + ", " + num(c.a) + ")";
}
std::string uvText(const vec2& uv) {
    std::string text = "(";  // appended, not a chain of +: GCC 12 warns falsely (-Wrestrict) on that
    text += num(uv.x);
    text += ", ";
    text += num(uv.y);
    text += ")";
    return text;
}

// Columns a UTF-8 line takes: one per code point.
std::size_t columns(std::string_view s) {
    std::size_t n = 0;
    for (const char c : s)
        n += (static_cast<unsigned char>(c) & 0xc0) != 0x80;
    return n;
}

// A screen's lines, each wrapped to 80 columns at a space (outside parentheses when it can), the
// continuation indented four more than the line.
class Lines {
  public:
    void add(std::string line) {
        const std::size_t indent = std::min<std::size_t>(line.find_first_not_of(' '), 40);
        const std::string continuation(indent + 4, ' ');
        while (columns(line) > kColumns) {
            std::size_t at = breakBefore(line, continuation.size(), true);
            if (at == std::string::npos) at = breakBefore(line, continuation.size(), false);
            if (at == std::string::npos) break;
            text_ += line.substr(0, at) + "\n";
            line = continuation + line.substr(at + 1);
        }
        text_ += line + "\n";
    }
    void blank() { text_ += "\n"; }
    const std::string& text() const { return text_; }

  private:
    // The last space within the first 80 columns, past the indentation (and outside parentheses).
    static std::size_t breakBefore(const std::string& line, std::size_t from, bool outsideParentheses) {
        std::size_t at = std::string::npos, column = 0;
        int depth = 0;
        for (std::size_t i = 0; i < line.size(); ++i) {
            const char c = line[i];
            column += (static_cast<unsigned char>(c) & 0xc0) != 0x80;
            if (column > kColumns) break;
            if (c == '(') ++depth;
            if (c == ')') --depth;
            if (c == ' ' && i > from && (depth == 0 || !outsideParentheses)) at = i;
        }
        return at;
    }
    std::string text_;
};

// A paragraph, wrapped to 80 columns, its lines indented as its first.
void addWrapped(Lines& out, const std::string& paragraph) {
    const std::string text = wrapText(paragraph, kColumns, paragraph.find_first_not_of(' '));
    for (std::size_t at = 0; at < text.size();) {
        const std::size_t end = text.find('\n', at);
        out.add(text.substr(at, end == std::string::npos ? std::string::npos : end - at));
        at = end == std::string::npos ? text.size() : end + 1;
    }
}

std::string_view modelName(const LightingRecord& r) {
    if (r.physicallyBased) return "Cook-Torrance";
    return r.specularModel == SpecularModel::Phong ? "Phong" : "Blinn-Phong";
}

std::string_view distributionName(NormalDistribution d) {
    return d == NormalDistribution::GGX ? "GGX (Trowbridge-Reitz)" : "Beckmann";
}

// The microfacet lobe's denominator and Fresnel's cosine in symbols (BrdfModel's choices).
std::string denominatorText(MicrofacetDenominator d) {
    return d == MicrofacetDenominator::Four ? "4(N·L)(N·V)" : "π(N·V)(N·L)";
}
std::string fresnelCosineText(FresnelCosine c) {
    return c == FresnelCosine::VdotH ? "V·H" : "N·L";
}

// The equation in symbols, once per screen.
void writeEquation(Lines& out, const LightingRecord& r) {
    if (r.physicallyBased) {
        out.add("Physically based lighting: Lambert diffuse + Cook-Torrance specular");
        out.add("(Cook & Torrance 1982; Karis 2013):");
        out.add("  c = m_emission + a_global ⊗ c_base");
        out.add("      + Σ f_r ⊗ π·c_light·falloff·spot·max(N·L,0)");
        const std::string spec = "D·F·G/(" + denominatorText(r.brdf.denominator) + ")";
        if (r.brdf.metal == MetalBlend::TintedLobe) {
            // lighting-deck-C.txt's "putting it together", term by term.
            out.add("  f_r = metalness·" + spec + "·c_base");
            out.add("        + (1 − metalness)·(" + spec + " + (1 − F)·c_base/π)");
            out.add("  F0 = F0_dielectric (the metal lobe is tinted by c_base instead)");
        } else {
            out.add("  f_r = (1 − F)(1 − metalness)·c_base/π + " + spec);
        }
        out.add("  falloff = 1/d² (point and spot lights), 1 (directional)");
        out.add("  H = normalize(L + V); D: " + std::string(distributionName(r.brdf.distribution)) +
                " distribution; F: " +
                (r.brdf.fresnel == FresnelModel::Schlick ? "Schlick's Fresnel" : "exact Fresnel") + " at " +
                fresnelCosineText(r.brdf.fresnelCosine) + "; G: " +
                (r.brdf.geometry == GeometryTerm::SmithGGX ? "Smith GGX" : "Cook-Torrance") + " shadowing.");
    } else {
        const bool phong = r.specularModel == SpecularModel::Phong;
        out.add(std::string("The standard lighting equation (OpenGL 2.1 §2.14.1), ") +
                (phong ? "Phong" : "Blinn-Phong") + " specular:");
        out.add("  c = m_emission + a_global ⊗ m_a");
        out.add(std::string("      + Σ att·spot·(l_a⊗m_a + max(N·L,0)·l_d⊗m_d + ") +
                (phong ? "max(R·V,0)^e" : "max(N·H,0)^e") + "·l_s⊗m_s)");
        out.add(std::string("  ") + (phong ? "R = 2(N·L)N − L" : "H = normalize(L + V)") +
                "; att = 1/(c0 + c1·d + c2·d²)");
        out.add("  The specular term is 0 where N·L ≤ " + num(kGrazingCosine) +
                ": the light grazes the surface or is behind it.");
    }
    out.add("  ⊗ multiplies colours channel by channel; colours are linear RGB.");
}

// The point: P, N (and its flip), V.
void writePoint(Lines& out, const SurfaceTermsRecord& s) {
    const LightingRecord& r = s.lighting;
    out.add("  P = " + vec(s.position) + " (eye space: the eye at the origin)");
    out.add("  N = " + vec(s.normal) + " as it comes, length " + num(glm::length(s.normal)));
    if (s.flipped)
        out.add("  N·V < 0: the surface is seen from behind, so the two-sided flip turns N round: N = −N");
    if (s.underside)
        out.add(
            "  N·V < 0: the viewer sees the underside; N·V is clamped to 0, so the lights' diffuse and "
            "specular terms are 0");
    out.add("  N = normalize(N) = " + vec(r.N));
    out.add("  V = normalize(eye − P) = " + vec(r.V));
}

void writeMaterial(Lines& out, const LightingRecord& r) {
    if (r.physicallyBased) {
        out.add("  c_base = " + rgb(r.materialDiffuse) + ", metalness = " + num(r.pbr.metalness) +
                ", roughness = " + num(r.pbr.roughness));
        if (r.pbr.ior > 0.0f) {
            out.add("  η = n2/n1 = " + num(r.pbr.ior) + " (n1 = 1, air)");
            out.add("  F0_dielectric = ((n1 − n2)/(n1 + n2))² = ((1 − " + num(r.pbr.ior) + ")/(1 + " +
                    num(r.pbr.ior) + "))² = " + num(r.pbr.f0.x));
        } else {
            out.add("  F0_dielectric = " + rgb(r.pbr.f0));
        }
    } else {
        out.add("  m_a (ambient)  = " + rgb(r.materialAmbient));
        out.add("  m_d (diffuse)  = " + rgb(r.materialDiffuse));
        out.add("  m_s (specular) = " + rgb(r.materialSpecular) + ", e = " + num(r.shininess));
    }
    const std::string symbols = std::string("a_global ⊗ ") + (r.physicallyBased ? "c_base" : "m_a");
    out.add("  " + symbols + " = " + rgb(r.globalAmbient) + " ⊗ " + rgb(r.materialAmbient));
    out.add("  " + std::string(columns(symbols), ' ') + " = " + rgb(r.globalAmbientTerm));
}

std::string lightTitle(int index, const LightParams& light) {
    const std::string number = "Light " + std::to_string(index + 1) + ": ";
    switch (light.kind) {
        case LightKind::Directional:
            return number + "directional, shining along " + vec(light.direction);
        case LightKind::Point:
            return number + "point light at " + vec(light.position);
        case LightKind::Spot:
            return number + "spot light at " + vec(light.position) + ", axis " + vec(light.spotDirection);
        case LightKind::Rect:
            return number + "rectangle light centred at " + vec(light.position);
        case LightKind::Disk:
            return number + "disk light centred at " + vec(light.position);
    }
    return number;
}

// An area light's shape: its facing, size and shadow samples.
void writeAreaShape(Lines& out, const LightParams& light) {
    if (!isAreaLight(light.kind)) return;
    out.add("  facing n_light = " + vec(light.areaNormal));
    if (light.kind == LightKind::Rect)
        out.add("  " + num(2.0f * length(light.areaU)) + " × " + num(2.0f * length(light.areaV)) +
                " (eye units), " + std::to_string(light.areaSamples) + " shadow samples");
    else
        out.add("  radius " + num(length(light.areaU)) + " (eye units), " +
                std::to_string(light.areaSamples) + " shadow samples");
    out.add("  lit as from its centre, times the emitter's cosine and the visible fraction v");
}

// The range's window (lighting.h's rangeWindow), in symbols and with the numbers.
void writeWindow(Lines& out, const LightRecord& r) {
    const LightParams& light = r.light;
    if (light.kind == LightKind::Directional || !(light.range > 0.0f)) return;
    const bool ue4 = light.window == RangeWindow::Ue4;
    const std::string power = ue4 ? "⁴" : "²";
    out.add("  f_win = (1 − (d/r_max)" + power + ")²₊   (" + (ue4 ? "Karis 2013, UE4" : "Just Cause 2") +
            "; 0 from d = r_max on)");
    out.add("        = (1 − (" + num(r.distance) + "/" + num(light.range) + ")" + power +
            ")²₊ = " + num(r.window));
}

void writeSpot(Lines& out, const LightRecord& r) {
    const LightParams& light = r.light;
    if (r.spot.emitter) {
        out.add("  spot = max(−L·n_light, 0) = max(" + num(r.spot.cosAngle) + ", 0) = " + num(r.spot.factor) +
                " (one-sided emitter)");
        return;
    }
    if (!r.spot.cone) {
        out.add(light.kind == LightKind::Spot ? "  spot = 1 (a cutoff of 180°: no cone)"
                                              : "  spot = 1 (not a spot light)");
        return;
    }
    out.add("  cos angle = −L·s = " + num(r.spot.cosAngle) + " (s: the spot's axis)");
    if (light.spotProfile == SpotProfile::Smooth) {
        out.add("  smooth cone, inner " + num(light.spotInnerDegrees) + "°, outer " +
                num(light.spotOuterDegrees) + "°:");
        out.add("  spot = smoothstep(cos outer, cos inner, −L·s) = smoothstep(" + num(r.spot.cosOuter) +
                ", " + num(r.spot.cosInner) + ", " + num(r.spot.cosAngle) + ") = " + num(r.spot.factor));
        return;
    }
    out.add("  cutoff " + num(light.spotCutoffDegrees) + "°: cos cutoff = " + num(r.spot.cosCutoff));
    if (r.spot.cosAngle >= r.spot.cosCutoff)
        out.add("  inside the cone: spot = max(−L·s, 0)^e = max(" + num(r.spot.cosAngle) + ", 0)^" +
                num(light.spotExponent) + " = " + num(r.spot.factor));
    else
        out.add("  outside the cone (cos angle < cos cutoff): spot = 0");
}

void writeLightPosition(Lines& out, const LightRecord& r) {
    if (r.light.kind == LightKind::Directional) {
        out.add("  L = normalize(−direction) = " + vec(r.L) + "; no distance");
        return;
    }
    out.add("  L = normalize(p_light − P) = " + vec(r.L));
    out.add("  d = |p_light − P| = " + num(r.distance));
}

// Three lines: a term in symbols, with the numbers, and its value.
void writeTerm(Lines& out, const std::string& name, const std::string& symbols, const std::string& numbers,
               const vec3& value) {
    const std::string pad(columns(name), ' ');
    out.add("  " + name + " = " + symbols);
    out.add("  " + pad + " = " + numbers);
    out.add("  " + pad + " = " + rgb(value));
}

// The shadow test's verdict for one light (shaders/shadowing.h): a ray from the point towards the light,
// or a shadow map's share of lit taps.
void writeShadow(Lines& out, const LightRecord& r, const ShadowBlocker* blocker) {
    if (isAreaLight(r.light.kind)) {
        const int n = std::max(r.light.areaSamples, 1);
        const int visible = static_cast<int>(std::lround(r.visibility * float(n)));
        out.add("  shadow: " + std::to_string(visible) + " of the " + std::to_string(n) + " samples of the " +
                (r.light.kind == LightKind::Rect ? "rectangle" : "disk") + " reach P:");
        out.add("  v = " + std::to_string(visible) + "/" + std::to_string(n) + " = " + num(r.visibility));
        return;
    }
    if (r.visibility == 1.0f)
        out.add("  shadow: nothing blocks the light from P (or it casts none): v = 1");
    else if (r.visibility == 0.0f)
        out.add("  shadow: another surface blocks the light from P: v = 0, no diffuse or specular from it");
    else
        out.add("  shadow: the shadow map's filter finds " + num(r.visibility) +
                " of its taps lit: v = " + num(r.visibility));
    if (r.visibility == 1.0f || !blocker) return;
    if (!blocker->found) {
        if (!blocker->byMap) return;
        out.add("  (the shadow map decided; a ray from P towards the light meets no triangle)");
        return;
    }
    const std::string what = "triangle " + std::to_string(blocker->triangle) + " of " + blocker->object;
    if (blocker->byMap) {
        out.add("  the shadow map decided; a ray from P towards the light only names a blocker:");
        out.add("  " + what + ", at distance " + num(blocker->distance) + " along the ray");
    } else {
        out.add("  the nearest blocker on the shadow ray from P + ε·N towards the light:");
        out.add("  " + what + ", at distance " + num(blocker->distance));
    }
}

void writeStandardLight(Lines& out, const LightingRecord& lighting, const LightRecord& r,
                        const ShadowBlocker* blocker) {
    const LightParams& light = r.light;
    writeAreaShape(out, light);
    writeLightPosition(out, r);
    if (light.kind == LightKind::Directional)
        out.add("  att = 1 (a directional light is not attenuated)");
    else
        out.add("  att = 1/(c0 + c1·d + c2·d²) = 1/(" + num(light.c0) + " + " + num(light.c1) + "·" +
                num(r.distance) + " + " + num(light.c2) + "·" + num(r.distance) +
                "²) = " + num(r.attenuation));
    writeWindow(out, r);
    writeSpot(out, r);
    out.add("  N·L = " + num(r.NdotL));
    const bool phong = lighting.specularModel == SpecularModel::Phong;
    if (phong) {
        out.add("  R = 2(N·L)N − L = " + vec(r.reflected));
        out.add("  R·V = " + num(r.cosine));
    } else {
        out.add("  H = normalize(L + V) = " + vec(r.reflected));
        out.add("  N·H = " + num(r.cosine));
    }
    if (r.grazing)
        out.add("  N·L ≤ " + num(kGrazingCosine) +
                ": the light grazes the surface or is behind it: spec = 0");
    else if (lighting.specularExponent != lighting.shininess)  // Blinn-Phong's exponent matched to Phong's
        out.add("  spec = max(N·H, 0)^e′, e′ = 4e = " + num(lighting.specularExponent) + ": max(" +
                num(r.cosine) + ", 0)^" + num(lighting.specularExponent) + " = " + num(r.spec));
    else
        out.add(std::string("  spec = max(") + (phong ? "R·V" : "N·H") + ", 0)^e = max(" + num(r.cosine) +
                ", 0)^" + num(lighting.shininess) + " = " + num(r.spec));
    // With a range, its window f_win multiplies att.
    const bool windowed = light.kind != LightKind::Directional && light.range > 0.0f;
    const std::string att = windowed ? "att·f_win" : "att";
    const std::string reach =
        num(r.attenuation) + (windowed ? "·" + num(r.window) : std::string()) + "·" + num(r.spot.factor);
    writeTerm(out, "ambient", att + "·spot·l_a⊗m_a",
              reach + "·" + rgb(light.ambient) + "⊗" + rgb(lighting.materialAmbient), r.ambient);
    // With shadows, v (the share of the light that reaches P) scales the diffuse and specular terms.
    const std::string v = r.shadowTested ? "·v" : "";
    const std::string lit = r.shadowTested ? reach + "·" + num(r.visibility) : reach;
    if (r.shadowTested) writeShadow(out, r, blocker);
    writeTerm(
        out, "diffuse", att + "·spot" + v + "·max(N·L,0)·l_d⊗m_d",
        lit + "·max(" + num(r.NdotL) + ", 0)·" + rgb(light.diffuse) + "⊗" + rgb(lighting.materialDiffuse),
        r.diffuse);
    writeTerm(out, "specular", att + "·spot" + v + "·spec·l_s⊗m_s",
              lit + "·" + num(r.spec) + "·" + rgb(light.specular) + "⊗" + rgb(lighting.materialSpecular),
              r.specular);
}

void writeBrdf(Lines& out, const LightingRecord& lighting, const BrdfRecord& b) {
    out.add("  H = normalize(L + V) = " + vec(b.H));
    out.add("  N·H = " + num(b.NdotH) + ", N·V = " + num(b.NdotV) + ", V·H = " + num(b.VdotH) +
            " (N·L, N·V at least 0.0001)");
    out.add("  α_r = roughness² = " + num(lighting.pbr.roughness) + "² = " + num(b.alpha) +
            " (at least 0.001)");
    if (b.anisotropic) {
        // Anisotropic GGX (tangent.h, lighting.h): the frame, the two roughnesses, then D.
        out.add("  T = ∂P/∂u made ⊥ N, unit = " + vec(b.T));
        out.add("  B = N × T = " + vec(b.B));
        const float a = lighting.pbr.anisotropy;
        out.add("  a = " + num(a) + ": α_x = α_r(1 + a) = " + num(b.alphaX) +
                ", α_y = α_r(1 − a) = " + num(b.alphaY));
        out.add("  H·T = " + num(b.HdotT) + ", H·B = " + num(b.HdotB) + ", N·H = " + num(b.NdotH));
        out.add("  D = 1/(π α_x α_y ((H·T/α_x)² + (H·B/α_y)² + (N·H)²)²)   (anisotropic GGX)");
        out.add("    = 1/(π·" + num(b.alphaX) + "·" + num(b.alphaY) + "·((" + num(b.HdotT) + "/" +
                num(b.alphaX) + ")² + (" + num(b.HdotB) + "/" + num(b.alphaY) + ")² + " + num(b.NdotH) +
                "²)²)");
        out.add("    = " + num(b.D));
    } else if (b.model.distribution == NormalDistribution::GGX) {
        out.add("  D = α_r²/(π((N·H)²(α_r² − 1) + 1)²)   (GGX)");
        out.add("    = " + num(b.alpha) + "²/(π(" + num(b.NdotH) + "²(" + num(b.alpha) +
                "² − 1) + 1)²) = " + num(b.D));
    } else if (b.model.distribution == NormalDistribution::Beckmann) {
        out.add("  D = exp(((N·H)² − 1)/(α_r²(N·H)²))/(π·α_r²·(N·H)⁴)   (Beckmann)");
        const std::string nh = num(b.NdotH), a = num(b.alpha);
        out.add("    = exp((" + nh + "² − 1)/(" + a + "²·" + nh + "²))/(π·" + a + "²·" + nh +
                "⁴) = " + num(b.D));
    } else {
        out.add("  D = c·exp(−(θ_h/m)²), θ_h = acos(N·H), m = α_r   (Gaussian)");
        out.add("    c = 1/(2π∫exp(−(θ/m)²)cosθ sinθ dθ) = " + num(b.gaussianC) + " (∫D(N·H)dω = 1)");
        out.add("    = " + num(b.gaussianC) + "·exp(−(" + num(b.thetaH) + "/" + num(b.alpha) +
                ")²) = " + num(b.D));
    }
    if (b.model.metal == MetalBlend::F0)
        out.add("  F0 = mix(F0_dielectric, c_base, metalness) = " + rgb(b.f0));
    else
        out.add("  F0 = F0_dielectric = " + rgb(b.f0));
    const std::string cosine = fresnelCosineText(b.model.fresnelCosine);
    if (b.model.fresnel == FresnelModel::Schlick) {
        out.add("  F = F0 + (1 − F0)(1 − " + cosine + ")^5   (Schlick)");
        out.add("    = " + rgb(b.f0) + " + (1 − F0)(1 − " + num(b.fresnelCosine) + ")^5");
    } else {
        out.add("  F = (R_s + R_p)/2, the exact Fresnel reflectance at cos θ_i = " + cosine + " = " +
                num(b.fresnelCosine));
        if (lighting.pbr.ior > 0.0f && lighting.pbr.metalness == 0.0f)
            out.add("    η = n2/n1 = " + num(lighting.pbr.ior) + " (the material's index of refraction)");
        else
            out.add("    η = (1 + √F0)/(1 − √F0) = " + vec(b.eta) + " per channel");
        out.add("    sin θ_t = sin θ_i/η;  R_s = ((cos θ_i − η cos θ_t)/(cos θ_i + η cos θ_t))²");
        out.add("                          R_p = ((cos θ_t − η cos θ_i)/(cos θ_t + η cos θ_i))²");
        out.add("    R_s = " + vec(b.Rs) + ", R_p = " + vec(b.Rp));
    }
    out.add("    = " + rgb(b.F));
    if (b.model.geometry == GeometryTerm::SmithGGX && b.anisotropic) {
        out.add("  G = G1(L)·G1(V), G1(ω) = 2/(1 + √(1 + (α_x²(ω·T)² + α_y²(ω·B)²)/(N·ω)²))");
        out.add("    (Smith, anisotropic GGX) with N·L = " + num(b.NdotL) + ", N·V = " + num(b.NdotV) +
                ": G = " + num(b.G));
    } else if (b.model.geometry == GeometryTerm::SmithGGX) {
        out.add("  G = G1(N·L)·G1(N·V), G1(x) = 2x/(x + √(α_r² + (1 − α_r²)x²))   (Smith GGX)");
        out.add("    with N·L = " + num(b.NdotL) + ", N·V = " + num(b.NdotV) + ": G = " + num(b.G));
    } else {
        out.add("  G = min(1, 2(N·H)(N·V)/(V·H), 2(N·H)(N·L)/(V·H))   (Cook-Torrance)");
        out.add("    = min(1, 2·" + num(b.NdotH) + "·" + num(b.NdotV) + "/" + num(b.VdotH) + ", 2·" +
                num(b.NdotH) + "·" + num(b.NdotL) + "/" + num(b.VdotH) + ") = " + num(b.G));
    }
    if (b.grazing) {
        out.add("  N·L ≤ " + num(kGrazingCosine) +
                ": the light grazes the surface or is behind it: both lobes are 0");
        return;
    }
    const std::string denominator = denominatorText(b.model.denominator);
    if (b.model.denominator == MicrofacetDenominator::Four)
        out.add("  D·G/(" + denominator + ") = " + num(b.D) + "·" + num(b.G) + "/(4·" + num(b.NdotL) + "·" +
                num(b.NdotV) + ") = " + num(b.specularScale));
    else
        out.add("  D·G/(" + denominator + ") = " + num(b.D) + "·" + num(b.G) + "/(π·" + num(b.NdotV) + "·" +
                num(b.NdotL) + ") = " + num(b.specularScale));
    if (b.model.metal == MetalBlend::TintedLobe) {
        out.add("  tint = mix(1, c_base, metalness) = " + rgb(b.metalTint));
        writeTerm(out, "specular lobe", "D·F·G/(" + denominator + ")·tint",
                  num(b.specularScale) + "·" + rgb(b.F) + "⊗" + rgb(b.metalTint), b.lobes.specular);
    } else {
        writeTerm(out, "specular lobe", "D·F·G/(" + denominator + ")", num(b.specularScale) + "·" + rgb(b.F),
                  b.lobes.specular);
    }
    writeTerm(out, "diffuse lobe", "(1 − F)(1 − metalness)·c_base/π",
              "(1 − " + rgb(b.F) + ")·" + rgb(lighting.materialDiffuse) + "·" + num(b.diffuseScale),
              b.lobes.diffuse);
}

void writePhysicallyBasedLight(Lines& out, const LightingRecord& lighting, const LightRecord& r,
                               const ShadowBlocker* blocker) {
    const LightParams& light = r.light;
    writeAreaShape(out, light);
    writeLightPosition(out, r);
    if (light.kind == LightKind::Directional)
        out.add("  falloff = 1 (a directional light)");
    else if (light.attenuationGiven)
        out.add("  falloff = 1/(c0 + c1·d + c2·d²) = 1/(" + num(light.c0) + " + " + num(light.c1) + "·" +
                num(r.distance) + " + " + num(light.c2) + "·" + num(r.distance) +
                "²) = " + num(r.attenuation) + " (the light's attenuation)");
    else
        out.add("  falloff = 1/d² = 1/" + num(r.distance) + "² = " + num(r.attenuation));
    writeWindow(out, r);
    writeSpot(out, r);
    out.add("  N·L = " + num(r.NdotL));
    const bool windowed = light.kind != LightKind::Directional && light.range > 0.0f;
    const std::string falloff = windowed ? "falloff·f_win" : "falloff";
    const std::string falloffValue = num(r.attenuation) + (windowed ? "·" + num(r.window) : std::string());
    if (r.shadowTested && windowed) {
        writeShadow(out, r, blocker);
        out.add("  irradiance factor = " + falloff + "·spot·max(N·L,0)·v");
        out.add("    = " + falloffValue + "·" + num(r.spot.factor) + "·max(" + num(r.NdotL) + ", 0)·" +
                num(r.visibility) + " = " + num(r.reach));
    } else if (r.shadowTested) {
        writeShadow(out, r, blocker);
        out.add("  irradiance factor = falloff·spot·max(N·L,0)·v = " + num(r.attenuation) + "·" +
                num(r.spot.factor) + "·max(" + num(r.NdotL) + ", 0)·" + num(r.visibility) + " = " +
                num(r.reach));
    } else {
        out.add("  irradiance factor = " + falloff + "·spot·max(N·L,0) = " + falloffValue + "·" +
                num(r.spot.factor) + "·max(" + num(r.NdotL) + ", 0) = " + num(r.reach));
    }
    writeBrdf(out, lighting, r.brdf);
    writeTerm(out, "incoming", "π·c_light·irradiance factor", "π·" + rgb(light.diffuse) + "·" + num(r.reach),
              r.incoming);
    writeTerm(out, "diffuse", "diffuse lobe ⊗ incoming", rgb(r.brdf.lobes.diffuse) + "⊗" + rgb(r.incoming),
              r.diffuse);
    writeTerm(out, "specular", "specular lobe ⊗ incoming", rgb(r.brdf.lobes.specular) + "⊗" + rgb(r.incoming),
              r.specular);
}

void writeLights(Lines& out, const LightingRecord& lighting, const ShadowBlockers* blockers) {
    if (lighting.lightCount == 0) out.add("  No lights: only emission and ambient light.");
    for (int k = 0; k < lighting.lightCount; ++k) {
        const LightRecord& r = lighting.lights[static_cast<std::size_t>(k)];
        out.blank();
        out.add(lightTitle(k, r.light) + " (eye space)");
        const ShadowBlocker* blocker = blockers ? &(*blockers)[static_cast<std::size_t>(k)] : nullptr;
        if (lighting.physicallyBased)
            writePhysicallyBasedLight(out, lighting, r, blocker);
        else
            writeStandardLight(out, lighting, r, blocker);
    }
}

// The terms summed over the lights, and the selection of terms drawn.
void writeSum(Lines& out, const SurfaceTermsRecord& s, const vec3& emission) {
    const LightingTerms<vec3>& t = s.terms;
    out.add("The sum:");
    if (s.selectedTerms != kAllTerms) {
        std::string drawn;
        for (const EnumName<LightingTerm>& term : kLightingTermNames)
            if (s.selectedTerms & term.value) drawn += (drawn.empty() ? "" : ", ") + std::string(term.name);
        out.add("  Only " + (drawn.empty() ? std::string("no term") : drawn) +
                " drawn (a component image): the other terms are 0.");
    }
    out.add("  emission = " + rgb(emission));
    out.add("  ambient  = " + rgb(t.ambient) + " (global + each light's)");
    out.add("  diffuse  = " + rgb(t.diffuse));
    out.add("  specular = " + rgb(t.specular));
}

// The environment map's mirror reflection (shading/environment.h), with every number.
void writeEnvironment(Lines& out, const EnvironmentRecord& e) {
    if (!e.used) return;
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on long chains of string +.
    const auto line = [&out](std::initializer_list<std::string_view> pieces) {
        std::string text;
        for (const std::string_view piece : pieces)
            text += piece;
        out.add(std::move(text));
    };
    out.add("The environment map's mirror reflection (equirectangular, RTR4 §10.4.1):");
    line({"  R = 2(N·V)N − V, N = ", vec(e.N), ", V = ", vec(e.V)});
    line({"    = ", vec(e.R), " (eye space)"});
    line({"  R in the map's frame (eye to world, the map's turn) = ", vec(e.direction)});
    line({"  u = ½ + atan2(x, −z)/(2π), v = ½ + asin(y)/π: uv = ", uvText(e.uv)});
    line({"  texel (", std::to_string(e.texel.x), ", ", std::to_string(e.texel.y),
          ") from the top left, bilinear × intensity:"});
    line({"  E(R) = ", rgb(e.color)});
    if (e.fresnel) {
        line({"  F = F0 + (1 − F0)(1 − N·V)^5 (Schlick), F0 = ", rgb(e.f0), ", N·V = ", num(e.NdotV)});
        line({"    = ", rgb(e.weight)});
        line({"  reflection = F ⊗ E(R) = ", rgb(e.term)});
    } else {
        line({"  weight w = m_s = ", rgb(e.weight)});
        line({"  reflection = w ⊗ E(R) = ", rgb(e.term)});
    }
}

void writeLighting(Lines& out, const SurfaceTermsRecord& s, const ShadowBlockers* blockers) {
    writePoint(out, s);
    writeMaterial(out, s.lighting);
    writeLights(out, s.lighting, blockers);
    out.blank();
}

std::string frequencyTitle(const ShadingTrace& t) {
    switch (t.frequency) {
        case ShadingFrequency::Phong:
            return "per pixel (Phong shading)";
        case ShadingFrequency::Gouraud:
            return "per vertex (Gouraud shading)";
        case ShadingFrequency::Flat:
            return "once per triangle (flat shading)";
        case ShadingFrequency::Constant:
            return "never (constant shading)";
    }
    return "";
}

void writeCorner(Lines& out, const CornerShading& c, const std::array<int, 3>& vertexOfCorner) {
    const VertexLightingRecord& v = c.lighting;
    out.add("---- v" + std::to_string(vertexOfCorner[static_cast<std::size_t>(c.corner) % 3]) +
            ": the vertex at " + vec(c.vertex.position) + " (object space) ----");
    writeLighting(out, v.lighting, &c.blockers);
    writeSum(out, v.lighting, v.lighting.terms.emission);
    if (v.environment.used) {
        writeEnvironment(out, v.environment);
        out.add("  (the reflection is part of the specular term above)");
    }
    if (v.emissionDeferred)
        out.add("  The emission is left out here: the pixel adds it with its emission texture.");
    if (v.clamped) {
        out.add("  c = emission + ambient + diffuse + specular = " + rgb(v.sum));
        out.add("  clamped to [0, 1] (OpenGL 1.x; the notes), all of it tinted by a diffuse map:");
        out.add("  modulated = clamp(c, 0, 1) = " + rgb(v.modulated) + ", added = " + rgb(v.added));
    } else {
        out.add("  The vertex hands on two colours, so that a diffuse map tints the diffuse light only:");
        out.add("  modulated = diffuse = " + rgb(v.modulated));
        out.add("  added = emission + ambient + specular = " + rgb(v.added));
    }
    out.blank();
}

// Gouraud after clipping: the piece's corners' colours, each new vertex mixed from its edge's ends.
void writeClippedCorners(Lines& out, const ShadingTrace::PieceCorners& p) {
    const std::string names = p.names[0] + ", " + p.names[1] + ", " + p.names[2];
    addWrapped(out, "  Clipping cut this triangle: the pixel lies in fan piece " + std::to_string(p.piece) +
                        ", corners " + names +
                        " of the clipped polygon (see clipping), and λ are theirs. A new vertex's "
                        "colours mix its edge's ends with t: c = (1 − t)·c_in + t·c_out.");
    for (const ShadingTrace::ClipMix& m : p.mixes) {
        const std::string a = num(1.0f - m.t), b = num(m.t);
        out.add("  " + m.made + ": made by " + m.plane + " on " + m.from + "→" + m.to + ", t = " + num(m.t));
        out.add("    modulated = " + a + "·" + rgb(m.modulated[0]) + " + " + b + "·" + rgb(m.modulated[1]));
        out.add("              = " + rgb(m.modulated[2]));
        out.add("    added = " + a + "·" + rgb(m.added[0]) + " + " + b + "·" + rgb(m.added[1]));
        out.add("          = " + rgb(m.added[2]));
    }
    for (int i = 0; i < 3; ++i) {
        const std::size_t k = static_cast<std::size_t>(i);
        out.add("  c" + std::to_string(i) + " (" + p.names[k] +
                (p.sources[k] != p.names[k] ? ", that is " + p.sources[k] : std::string()) + "):");
        out.add("    modulated " + rgb(p.modulated[k]) + ", added " + rgb(p.added[k]));
    }
    out.add("  λ′_i = (λ_i/w_i)/(1/w) for " + names + ": λ′ = " + vec(p.weights));
    out.add("  modulated = λ′0·c0 + λ′1·c1 + λ′2·c2 = " + rgb(p.mixedModulated));
    out.add("  added = λ′0·c0 + λ′1·c1 + λ′2·c2 = " + rgb(p.mixedAdded));
}

void writeInterpolation(Lines& out, const ShadingTrace& t) {
    const FragmentRecord& f = t.fragment;
    // The weights of v0, v1, v2 as drawn: the setup's corner c is vertex vertexOfCorner[c].
    const auto drawn = [&t](const vec3& setupOrder) {
        vec3 byVertex(0.0f);
        for (int c = 0; c < 3; ++c)
            byVertex[t.vertexOfCorner[static_cast<std::size_t>(c)] % 3] = setupOrder[c];
        return byVertex;
    };
    out.add("Interpolation to the pixel (perspective-correct, OpenGL 2.1 §3.5.1):");
    out.add("  λ = (λ0, λ1, λ2) = " + vec(drawn(t.barycentrics)) + " from the edge functions");
    out.add("  1/w at the pixel = λ0/w0 + λ1/w1 + λ2/w2 = " + num(t.invW));
    if (t.weightsMatchCorners) {
        const vec3 invW(t.corners[0].invW, t.corners[1].invW, t.corners[2].invW);
        out.add("  1/w0, 1/w1, 1/w2 = " + vec(drawn(invW)));
        out.add("  λ′_i = (λ_i/w_i)/(1/w): λ′ = " + vec(drawn(t.perspectiveWeights)));
        out.add("  modulated = λ′0·c0 + λ′1·c1 + λ′2·c2 = " + rgb(t.mixedModulated));
        out.add("  added = λ′0·c0 + λ′1·c1 + λ′2·c2 = " + rgb(t.mixedAdded));
    } else if (t.piece.present) {
        writeClippedCorners(out, t.piece);
    } else {
        out.add("  Clipping cut this triangle: the λ are those of the piece the pixel lies in, whose");
        out.add("  corners are themselves mixes of the corners above.");
    }
    out.add("  The interpolator gives (what the fragment shader reads):");
    out.add("  modulated = " + rgb(f.modulatedIn));
    out.add("  added = " + rgb(f.addedIn));
}

// How the maps were read at this pixel: the filter, and under trilinear the level of detail from the
// texture coordinates' screen-space derivatives (OpenGL 4.6 §8.14.1–2).
void writeTextureFilter(Lines& out, const ShadingTrace& t) {
    const ShadingTrace::TextureFootprint& m = t.texture;
    if (!m.mapped) return;
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on long chains of string +.
    const auto line = [&out](std::initializer_list<std::string_view> pieces) {
        std::string text;
        for (const std::string_view piece : pieces)
            text += piece;
        out.add(std::move(text));
    };
    const std::string size = std::to_string(m.width) + "×" + std::to_string(m.height);
    switch (m.filter) {
        case TextureFilter::Nearest:
            line({"  Filter: nearest, the one texel of the ", size, " map that holds uv."});
            return;
        case TextureFilter::Bilinear:
            line({"  Filter: bilinear, the four texels of the ", size,
                  " map around uv, weighted by uv's distance to each."});
            return;
        case TextureFilter::Trilinear:
            break;
    }
    line({"  Filter: trilinear over the map's ", std::to_string(m.levels), " mip levels (level 0 is ", size,
          "). The pixel's footprint:"});
    line({"    ∂uv/∂x = ", uvText(m.uvDx), ", ∂uv/∂y = ", uvText(m.uvDy),
          " (how uv changes to the next pixel)"});
    line(
        {"    ρ = max(|∂uv/∂x ⊗ (w, h)|, |∂uv/∂y ⊗ (w, h)|) = ", num(m.rho), " texels of level 0 per pixel"});
    const int last = m.levels - 1;
    const std::string lod = num(m.lod);
    if (!(m.lod > 0.0f)) {
        line({"    lod = log2 ρ = ", lod, " ≤ 0: magnified, level 0 read bilinearly"});
    } else if (m.lod >= static_cast<float>(last)) {
        line({"    lod = log2 ρ = ", lod, " ≥ ", std::to_string(last), ", the last level: level ",
              std::to_string(last), " read bilinearly"});
    } else {
        const int fine = static_cast<int>(m.lod);
        const std::string a = std::to_string(fine), b = std::to_string(fine + 1);
        line({"    lod = log2 ρ = ", lod, ": levels ", a, " and ", b, " read bilinearly, mixed as (1 − t)·c",
              a, " + t·c", b, ", t = lod − ⌊lod⌋ = ", num(m.lod - static_cast<float>(fine))});
    }
}

// The fragment shader's own part: textures, emission, clamp.
void writeFragmentPart(Lines& out, const ShadingTrace& t) {
    const FragmentRecord& f = t.fragment;
    out.add("The fragment shader at pixel (" + std::to_string(t.x) + ", " + std::to_string(t.y) + "):");
    if (f.perPixel) {
        if (f.environment.used)
            out.add("  c = emission + ambient + diffuse + specular + reflection = " + rgb(f.sum));
        else
            out.add("  c = emission + ambient + diffuse + specular = " + rgb(f.sum));
        if (f.clamped) out.add("  clamped to [0, 1] (OpenGL 1.x; the lecture notes): c = " + rgb(f.color));
    } else {
        if (f.diffuseMapped)
            out.add("  modulated = " + rgb(f.modulatedIn) + " ⊗ " + rgb(vec3(f.diffuseTexel)) + " = " +
                    rgb(f.modulated) + " (the diffuse map's texel at uv " + uvText(f.uv) + ")");
        if (f.emissionMapped)
            out.add("  added = " + rgb(f.addedIn) + " + m_emission ⊗ texel = " + rgb(f.addedIn) + " + " +
                    rgb(f.emission) + " = " + rgb(f.added) + " (the emission map at uv " + uvText(f.uv) +
                    ")");
        out.add("  c = modulated + added = " + rgb(f.modulated) + " + " + rgb(f.added) + " = " +
                rgb(f.color));
        writeTextureFilter(out, t);
    }
    if (f.diffuseMapped)
        out.add("  α = opacity·texel α = " + num(f.opacity) + "·" + num(f.diffuseTexel.a) + " = " +
                num(f.alpha));
    else
        out.add("  α = opacity = " + num(f.alpha));
}

// Flat shading's normal: the face normal of v0, v1, v2 as drawn, from two edges (renderer.h's
// flatFaceNormal, in object space, whose record the trace holds).
void writeFaceNormal(Lines& out, const ShadingTrace& t) {
    const FaceNormalRecord& r = t.faceNormalRecord;
    const std::array<vec3, 3>& v = t.facePositions;
    out.add("Its normal is the face normal, the same at every corner, from two edges of");
    out.add("the triangle (object space, the positions v0, v1, v2 the pipeline used):");
    for (int k = 0; k < 3; ++k)
        out.add("  v" + std::to_string(k) + " = " + vec(v[static_cast<std::size_t>(k)]));
    out.add("  v1 − v0 = " + vec(v[1] - v[0]) + ", v2 − v0 = " + vec(v[2] - v[0]));
    out.add("  (v1 − v0) × (v2 − v0) = " + vec(r.cross));
    if (r.turned)
        out.add("  it points against the model's vertex normals, so it is turned: " + vec(-r.cross));
    if (r.fallback) {
        out.add("  it has no length: the corners' normals' sum, normalised, instead:");
        out.add("  n = " + vec(r.normal));
    } else {
        out.add("  n = normalize(" + std::string(r.turned ? "−" : "") + "(v1 − v0) × (v2 − v0)) = " +
                vec(r.cross * (r.turned ? -1.0f : 1.0f)) + " / " + num(r.length));
        out.add("    = " + vec(r.normal) + ", the face normal (object space)");
    }
    out.add("The vertex shader turns it into eye space, n_eye = N·n with the normal");
    out.add("matrix N (see the vertex shader screen): the lighting's N below is n_eye.");
}

Screen lightingScreen(const ShadingTrace& t) {
    Lines out;
    const FragmentRecord& f = t.fragment;
    const LightingRecord& model =
        t.corners.empty() ? f.lighting.lighting : t.corners[0].lighting.lighting.lighting;
    if (t.frequency == ShadingFrequency::Constant) {
        // No lighting equation: the colour the flat shader's vertex stage hands on (surfaceTerms, unlit).
        const SurfaceUniforms& u = t.uniforms;
        const bool pbr = u.reflection == ReflectionModel::CookTorrance;
        out.add("Constant shading: no lighting equation runs (no light, no normal). Every pixel");
        out.add("of the object takes one unlit colour (lighting-deck-A.txt):");
        out.add(std::string("  c = ") + (pbr ? "c_base" : "m_d") + " ⊗ texel + m_emission");
        out.blank();
        out.add(std::string("  ") + (pbr ? "c_base" : "m_d") + " = " + rgb(u.albedo()) +
                (u.terms & kDiffuseTerm ? "" : " (not selected: 0)"));
        out.add("  m_emission = " + rgb(u.material.emission) +
                (u.terms & kEmissionTerm ? "" : " (not selected: 0)"));
        if (f.diffuseMapped)
            out.add("  texel = " + rgb(vec3(f.diffuseTexel)) + " (the diffuse map at uv " + uvText(f.uv) +
                    ")");
        if (f.emissionMapped)
            out.add("  m_emission ⊗ emission texel " + rgb(vec3(f.emissionTexel)) + " = " + rgb(f.emission));
        out.add("  c = " + rgb(f.modulated) + " + " + rgb(f.added) + " = " + rgb(f.color));
        out.blank();
        writeFragmentPart(out, t);
        return {"lighting", "Lighting " + frequencyTitle(t) + ": the unlit colour", out.text()};
    }
    std::string title = "Lighting " + frequencyTitle(t) + ": " + std::string(modelName(model));
    switch (t.frequency) {
        case ShadingFrequency::Constant:  // above
            break;
        case ShadingFrequency::Phong:
            out.add("Phong shading: the lighting equation runs at this pixel, on the position and the");
            out.add("normal interpolated from the triangle's corners.");
            break;
        case ShadingFrequency::Gouraud:
            out.add("Gouraud shading: the lighting equation runs at the triangle's three corners");
            out.add("(in the vertex shader); their colours are interpolated across the triangle.");
            break;
        case ShadingFrequency::Flat: {
            const int v = t.vertexOfCorner[static_cast<std::size_t>(t.provokingCorner) % 3];
            const std::string name = "v" + std::to_string(v);
            addWrapped(out, "Flat shading: the lighting equation runs once, at " + name +
                                ", the provoking vertex (" + (v == 2 ? "the last, as OpenGL" : "the first") +
                                "); its colour fills the whole triangle.");
            if (t.faceNormal)
                writeFaceNormal(out, t);
            else
                addWrapped(out, "Its normal is " + name + "'s own (the gl preset: no face normal).");
            break;
        }
    }
    out.blank();
    writeEquation(out, model);
    out.blank();
    if (t.frequency == ShadingFrequency::Phong) {
        out.add("The point:");
        if (f.diffuseMapped)
            out.add("  " + std::string(model.physicallyBased ? "c_base" : "m_d") + " = " +
                    rgb(f.materialAlbedo) + " ⊗ " + rgb(vec3(f.diffuseTexel)) + " = " + rgb(f.albedo) +
                    " (the diffuse map's texel at uv " + uvText(f.uv) + ")");
        writeTextureFilter(out, t);
        writeLighting(out, f.lighting, &t.blockers);
        writeSum(out, f.lighting, f.emission);
        writeEnvironment(out, f.environment);
        if (f.emissionMapped)
            out.add("  (emission = m_emission ⊗ the emission map's texel " + rgb(vec3(f.emissionTexel)) +
                    " at uv " + uvText(f.uv) + ")");
        out.blank();
    } else {
        // The corners as v0, v1, v2 of the triangle as drawn (the setup may have exchanged two).
        for (int v = 0; v < 3; ++v)
            for (const CornerShading& c : t.corners)
                if (t.vertexOfCorner[static_cast<std::size_t>(c.corner) % 3] == v)
                    writeCorner(out, c, t.vertexOfCorner);
        if (t.frequency == ShadingFrequency::Gouraud) {
            writeInterpolation(out, t);
        } else {
            out.add("Every pixel of the triangle takes the provoking corner's colours:");
            out.add("  modulated = " + rgb(f.modulatedIn) + ", added = " + rgb(f.addedIn));
        }
        out.blank();
    }
    writeFragmentPart(out, t);
    return {"lighting", title, out.text()};
}

// Height fog's screen: the closed form, then the numbers.
Screen heightFogScreen(const FogRecord& r) {
    const FogParams& fog = r.fog;
    Lines out;
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on long chains of string +.
    const auto line = [&out](std::initializer_list<std::string_view> pieces) {
        std::string text;
        for (const std::string_view piece : pieces)
            text += piece;
        out.add(std::move(text));
    };
    out.add("Height fog: the density falls exponentially with the height h above h0,");
    out.add("  density(h) = a·e^(−b·(h − h0)), integrated along the ray from eye to point:");
    out.add("  τ = a·e^(−b·(y_e − h0))·d·g(b·Δy),  g(x) = (1 − e^(−x))/x,  g(0) = 1");
    out.add("  (d: the distance to the point, Δy: its height above the eye's)");
    out.add("  f = e^(−τ), c_p = f·c_s + (1 − f)·c_fog");
    out.blank();
    line({"  a = ", num(fog.density), ", b = ", num(fog.falloff), ", h0 = ", num(fog.baseHeight),
          " (eye-space units)"});
    line({"  y_e = ", num(fog.eyeHeight), " (the eye's height), up (eye space) = ", vec(fog.up)});
    line({"  d = |P_eye| = |", vec(r.eyePosition), "| = ", num(r.z)});
    line({"  Δy = P_eye·up = ", num(r.rise)});
    line({"  τ = ", num(fog.density), "·e^(−", num(fog.falloff), "·(", num(fog.eyeHeight), " − ",
          num(fog.baseHeight), "))·", num(r.z), "·g(", num(fog.falloff * r.rise), ")"});
    line({"    = ", num(r.tau)});
    line({"  f = e^(−τ) = ", num(r.f)});
    line({"  c_fog = ", rgb(fog.color)});
    line({"  c_p = f·c_s + (1 − f)·c_fog = ", num(r.f), "·", rgb(r.color), " + ", num(1.0f - r.f), "·",
          rgb(fog.color)});
    line({"      = ", rgb(r.fogged)});
    std::string title = "Fog: height, f = ";
    title += num(r.f);
    return {"fog", std::move(title), out.text()};
}

Screen fogScreen(const ShadingTrace& t) {
    Lines out;
    const FogRecord& r = t.fragment.output.fog;
    const FogParams& fog = r.fog;
    if (fog.mode == FogMode::None) {
        out.add("Fog is off: the lit colour passes unchanged, c_p = c_s = " + rgb(r.color) + ".");
        return {"fog", "Fog: off", out.text()};
    }
    if (fog.mode == FogMode::Height) return heightFogScreen(r);
    out.add("Fog (OpenGL 2.1 §3.10) blends the colour towards the fog colour with distance:");
    out.add("  c_p = f·c_s + (1 − f)·c_fog, f clamped to [0, 1] (1: no fog, 0: only fog)");
    out.blank();
    if (fog.distance == FogDistance::Radial)
        out.add("  z = |P_eye| (radial distance) = |" + vec(r.eyePosition) + "| = " + num(r.z));
    else
        out.add("  z = |z_eye| (the eye-space depth) = |" + num(r.eyePosition.z) + "| = " + num(r.z));
    switch (fog.mode) {
        case FogMode::None:
        case FogMode::Height:
            break;
        case FogMode::Linear:
            out.add("  linear fog from start " + num(fog.start) + " to end " + num(fog.end) + ":");
            out.add("  f = (end − z)/(end − start) = (" + num(fog.end) + " − " + num(r.z) + ")/(" +
                    num(fog.end) + " − " + num(fog.start) + ") = " + num(r.f));
            break;
        case FogMode::Exponential:
            out.add("  exponential fog, density " + num(fog.density) + ":");
            out.add("  f = e^(−density·z) = e^(−" + num(fog.density) + "·" + num(r.z) + ") = " + num(r.f));
            break;
        case FogMode::ExponentialSquared:
            out.add("  exponential-squared fog, density " + num(fog.density) + ":");
            out.add("  f = e^(−(density·z)²) = e^(−(" + num(fog.density) + "·" + num(r.z) +
                    ")²) = " + num(r.f));
            break;
    }
    out.add("  c_s = " + rgb(r.color) + " (the lit colour)");
    out.add("  c_fog = " + rgb(fog.color));
    out.add("  c_p = f·c_s + (1 − f)·c_fog = " + num(r.f) + "·" + rgb(r.color) + " + " + num(1.0f - r.f) +
            "·" + rgb(fog.color));
    out.add("      = " + rgb(r.fogged));
    return {"fog", std::string("Fog: ") + std::string(nameOf(fog.mode)) + ", f = " + num(r.f), out.text()};
}

Screen outputScreen(const ShadingTrace& t) {
    Lines out;
    const OutputRecord& o = t.fragment.output;
    const std::string c = rgb(o.fog.fogged);
    out.add("The colour c = " + c + " and α = " + num(o.alpha) + " go to the blend (" +
            std::string(nameOf(o.blend)) + ") in the form it expects:");
    switch (o.blend) {
        case BlendMode::Replace:
        case BlendMode::Over:
        case BlendMode::OverGL:
            out.add("  straight alpha: the shader writes (c, α)");
            break;
        case BlendMode::PremultipliedOver:
        case BlendMode::Additive:
            out.add("  premultiplied alpha: the shader writes (α·c, α)");
            out.add("  α·c = " + num(o.alpha) + "·" + c + " = " + rgb(o.output));
            break;
        case BlendMode::Multiply:
            out.add("  a filter, clear (1) where α = 0: the shader writes (mix(1, c, α), α)");
            out.add("  mix(1, c, α) = 1 + (c − 1)·α = 1 + (" + c + " − 1)·" + num(o.alpha) + " = " +
                    rgb(o.output));
            break;
    }
    switch (o.blend) {
        case BlendMode::Replace:
            out.add("  The blend replaces the pixel's colour: c_o = c_s.");
            break;
        case BlendMode::Over:
            out.add("  The blend then computes c_o = α_s·c_s + (1 − α_s)·c_d.");
            break;
        case BlendMode::OverGL:
            out.add("  The blend then computes c_o = α_s·c_s + (1 − α_s)·c_d and, as OpenGL's");
            out.add("  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA), α_o = α_s·α_s + (1 − α_s)·α_d.");
            break;
        case BlendMode::PremultipliedOver:
            out.add("  The blend then computes c_o = c_s + (1 − α_s)·c_d (c_s already holds α·c).");
            break;
        case BlendMode::Additive:
            out.add("  The blend then computes c_o = c_d + c_s (c_s already holds α·c).");
            break;
        case BlendMode::Multiply:
            out.add("  The blend then computes c_o = c_s ⊗ c_d.");
            break;
    }
    out.blank();
    out.add("The fragment shader's output: " + rgba(t.fragment.result));
    if (!t.shaderRan)
        out.add("The pipeline did not run the shader here: the depth test failed first.");
    else if (t.matchesPipeline)
        out.add("The pipeline's output is the same, bit for bit.");
    else
        out.add("The pipeline's output differs: " + rgba(t.pipelineOutput) + ".");
    return {"output",
            "Output: " + rgba(t.fragment.result) + " for the " + std::string(nameOf(o.blend)) + " blend",
            out.text()};
}

}  // namespace

std::vector<Screen> shadingScreens(const ShadingTrace& trace) {
    return {lightingScreen(trace), fogScreen(trace), outputScreen(trace)};
}

// ---- JSON --------------------------------------------------------------------------------------------

namespace {

nlohmann::json json3(const vec3& v) {
    return {v.x, v.y, v.z};
}
nlohmann::json json4(const vec4& v) {
    return {v.x, v.y, v.z, v.w};
}

nlohmann::json toJson(const LightingTerms<vec3>& t) {
    return {{"emission", json3(t.emission)},
            {"ambient", json3(t.ambient)},
            {"diffuse", json3(t.diffuse)},
            {"specular", json3(t.specular)}};
}

nlohmann::json toJson(const LightRecord& r, bool physicallyBased) {
    nlohmann::json j = {{"kind", nameOf(r.light.kind)},
                        {"L", json3(r.L)},
                        {"distance", r.distance},
                        {"c0", r.light.c0},
                        {"c1", r.light.c1},
                        {"c2", r.light.c2},
                        {physicallyBased ? "falloff" : "attenuation", r.attenuation},
                        {"spot",
                         {{"cone", r.spot.cone},
                          {"profile", nameOf(r.light.spotProfile)},
                          {"cosAngle", r.spot.cosAngle},
                          {"cosCutoff", r.spot.cosCutoff},
                          {"exponent", r.light.spotExponent},
                          {"cosInner", r.spot.cosInner},
                          {"cosOuter", r.spot.cosOuter},
                          {"factor", r.spot.factor}}},
                        {"NdotL", r.NdotL},
                        {"shadowTested", r.shadowTested},
                        {"visibility", r.visibility},
                        {"ambient", json3(r.ambient)},
                        {"diffuse", json3(r.diffuse)},
                        {"specular", json3(r.specular)}};
    // Only for the lights that have them: a scene without ranges or area lights keeps its JSON.
    if (r.light.kind != LightKind::Directional && r.light.range > 0.0f)
        j["window"] = {{"function", nameOf(r.light.window)}, {"range", r.light.range}, {"value", r.window}};
    if (isAreaLight(r.light.kind)) {
        j["area"] = {{"normal", json3(r.light.areaNormal)},
                     {"samples", r.light.areaSamples},
                     {"emitterCosine", r.spot.factor}};
    }
    if (physicallyBased) {
        const BrdfRecord& b = r.brdf;
        j["irradianceFactor"] = r.reach;
        j["incoming"] = json3(r.incoming);
        j["brdf"] = {{"H", json3(b.H)},
                     {"NdotH", b.NdotH},
                     {"NdotV", b.NdotV},
                     {"NdotL", b.NdotL},
                     {"VdotH", b.VdotH},
                     {"alpha", b.alpha},
                     {"distribution", nameOf(b.model.distribution)},
                     {"D", b.D},
                     {"fresnel", nameOf(b.model.fresnel)},
                     {"F0", json3(b.f0)},
                     {"F", json3(b.F)},
                     {"eta", json3(b.eta)},
                     {"Rs", json3(b.Rs)},
                     {"Rp", json3(b.Rp)},
                     {"fresnelCosine", b.fresnelCosine},
                     {"denominator", microfacetConstant(b.model.denominator)},
                     {"metalTint", json3(b.metalTint)},
                     {"geometry", nameOf(b.model.geometry)},
                     {"G", b.G},
                     {"grazing", b.grazing},
                     {"diffuseLobe", json3(b.lobes.diffuse)},
                     {"specularLobe", json3(b.lobes.specular)}};
        if (b.anisotropic)
            j["brdf"]["anisotropic"] = {{"T", json3(b.T)},    {"B", json3(b.B)},  {"alphaX", b.alphaX},
                                        {"alphaY", b.alphaY}, {"HdotT", b.HdotT}, {"HdotB", b.HdotB}};
    } else {
        j["attTimesSpot"] = r.reach;
        j["reflected"] = json3(r.reflected);
        j["cosine"] = r.cosine;
        j["grazing"] = r.grazing;
        j["spec"] = r.spec;
    }
    return j;
}

nlohmann::json toJson(const SurfaceTermsRecord& s) {
    const LightingRecord& r = s.lighting;
    nlohmann::json lights = nlohmann::json::array();
    for (int k = 0; k < r.lightCount; ++k)
        lights.push_back(toJson(r.lights[static_cast<std::size_t>(k)], r.physicallyBased));
    nlohmann::json j = {{"model", modelName(r)},
                        {"P", json3(s.position)},
                        {"normalGiven", json3(s.normal)},
                        {"flipped", s.flipped},
                        {"underside", s.underside},
                        {"N", json3(r.N)},
                        {"V", json3(r.V)},
                        {"globalAmbient", json3(r.globalAmbient)},
                        {"globalAmbientTerm", json3(r.globalAmbientTerm)},
                        {"lights", lights},
                        {"selectedTerms", s.selectedTerms},
                        {"terms", toJson(s.terms)}};
    if (r.physicallyBased)
        j["material"] = {{"baseColor", json3(r.materialDiffuse)},
                         {"metalness", r.pbr.metalness},
                         {"roughness", r.pbr.roughness},
                         {"f0", json3(r.pbr.f0)}};
    else
        j["material"] = {{"ambient", json3(r.materialAmbient)},
                         {"diffuse", json3(r.materialDiffuse)},
                         {"specular", json3(r.materialSpecular)},
                         {"shininess", r.shininess},
                         {"specularExponent", r.specularExponent}};
    return j;
}

}  // namespace

nlohmann::json toJson(const ShadingTrace& t) {
    const FragmentRecord& f = t.fragment;
    const FogRecord& fog = f.output.fog;
    nlohmann::json j = {
        {"frequency", nameOf(t.frequency)},      {"x", t.x},      {"y", t.y}, {"triangle", t.triangle},
        {"barycentrics", json3(t.barycentrics)}, {"invW", t.invW}};
    if (f.perPixel) {
        j["lighting"] = toJson(f.lighting);
    } else {
        nlohmann::json corners = nlohmann::json::array();
        for (const CornerShading& c : t.corners)
            corners.push_back({{"corner", c.corner},
                               {"invW", c.invW},
                               {"lighting", toJson(c.lighting.lighting)},
                               {"clamped", c.lighting.clamped},
                               {"modulated", json3(c.lighting.modulated)},
                               {"added", json3(c.lighting.added)}});
        j["corners"] = corners;
        j["provokingCorner"] = t.provokingCorner;
        if (t.frequency == ShadingFrequency::Gouraud) {
            j["weightsMatchCorners"] = t.weightsMatchCorners;
            j["perspectiveWeights"] = json3(t.perspectiveWeights);
        }
    }
    j["fragment"] = {{"uv", {f.uv.x, f.uv.y}},
                     {"diffuseTexel", f.diffuseMapped ? json4(f.diffuseTexel) : nlohmann::json()},
                     {"emissionTexel", f.emissionMapped ? json4(f.emissionTexel) : nlohmann::json()},
                     {"opacity", f.opacity},
                     {"alpha", f.alpha},
                     {"clamped", f.clamped},
                     {"color", json3(f.color)}};
    if (!f.perPixel) {
        j["fragment"]["modulatedIn"] = json3(f.modulatedIn);
        j["fragment"]["addedIn"] = json3(f.addedIn);
        j["fragment"]["modulated"] = json3(f.modulated);
        j["fragment"]["added"] = json3(f.added);
    }
    j["fog"] = {{"mode", nameOf(fog.fog.mode)},
                {"distance", nameOf(fog.fog.distance)},
                {"z", fog.z},
                {"start", fog.fog.start},
                {"end", fog.fog.end},
                {"density", fog.fog.density},
                {"f", fog.f},
                {"color", json3(fog.color)},
                {"fogColor", json3(fog.fog.color)},
                {"fogged", json3(fog.fogged)}};
    j["output"] = {{"blend", nameOf(f.output.blend)},     {"alpha", f.output.alpha},
                   {"color", json3(f.output.output)},     {"result", json4(f.result)},
                   {"pipeline", json4(t.pipelineOutput)}, {"shaderRan", t.shaderRan},
                   {"matchesPipeline", t.matchesPipeline}};
    return j;
}

}  // namespace facet::step
