#include "step/notation.h"

#include <array>

#include "step/screens.h"

namespace facet::step {
namespace {

// In pipeline order: the stage that prints a symbol first. `where` names the screens by the short
// names a student types in the walk.
constexpr std::array kNotation = {
    // Input and vertex shader.
    Symbol{"v0 v1 v2", "the triangle's three vertices (corners), in the order it is drawn",
           "input, transform, clip, window, setup"},
    Symbol{"n n̂ n̂_own n̂_f",
           "a normal in object space; n̂ a face's unit normal, n̂_own that of the corner's own face", "input"},
    Symbol{"w_f", "the weight of face f in a computed vertex normal n = normalize(Σ w_f)", "input"},
    Symbol{"Σ", "a sum: over the faces at a vertex, or over the lights", "input, lighting"},
    Symbol{"M", "the model matrix: the object's placement in the scene", "transform"},
    Symbol{"M_n", "the normal matrix ((V·M)⁻¹)ᵀ, scaled to determinant 1 (lecture deck A's N)", "transform"},
    Symbol{"n_obj n_eye", "a vertex normal as the model gives it, and in eye space: n_eye = M_n·n_obj",
           "transform"},
    Symbol{"z_eye", "a point's z in eye space, negative in front of the eye (w = −z_eye)", "transform"},
    Symbol{"gl_Position", "the vertex shader's output in clip space (OpenGL's name)", "transform"},
    // Clipping, divide and viewport.
    Symbol{"P_in P_out d_in d_out",
           "an edge's ends inside and outside a clip plane, and their distances d to it", "clip"},
    Symbol{"t",
           "the fraction of a linear mix (1 − t)·a + t·b: where an edge crosses a clip plane "
           "(t = d_in/(d_in − d_out)), or between two mip levels",
           "clip, lighting"},
    Symbol{"w w0 w1 w2 w_i", "the clip-space w of a vertex (its depth −z_eye); 1/w is affine on the screen",
           "window, interpolate, lighting"},
    Symbol{"x_ndc y_ndc z_ndc", "normalised device coordinates (x, y, z)/w, in [−1, 1] inside the view",
           "window"},
    Symbol{"x_w y_w z_w", "window coordinates: pixels from the left and from the top; z_w the stored depth",
           "window"},
    Symbol{"d_near d_far", "the depth range: z_w at the near and at the far plane (OpenGL's glDepthRange)",
           "window"},
    // Setup, rasterization, interpolation.
    Symbol{"E0 E1 E2 E_i",
           "the edge functions at the pixel centre: twice the signed area of the triangle "
           "the pixel makes with edge i (2A: the whole triangle's)",
           "setup, raster, interpolate"},
    Symbol{"λ λ0 λ1 λ2 λ_i", "the barycentric weights of the pixel centre on the screen: λ_i = E_i / 2A",
           "history, interpolate, lighting"},
    Symbol{"λ′ λ′0 λ′1 λ′2 λ′_i",
           "the perspective-correct weights the varyings are mixed with: λ′_i = (λ_i/w_i) / (1/w)",
           "history, interpolate, lighting"},
    Symbol{"z_fragment z_buffer", "the depth test: the fragment's z_w against the one the buffer holds",
           "depth"},
    // Lighting.
    Symbol{"N", "the unit surface normal at the point, in eye space", "lighting"},
    Symbol{"L", "the unit vector from the point to the light", "lighting"},
    Symbol{"V",
           "the view (camera) matrix in the vertex shader; in the lighting, the unit vector from "
           "the point to the eye",
           "transform, lighting"},
    Symbol{"P",
           "the projection matrix in the vertex shader; a point elsewhere (on a clipped edge, or "
           "the shaded point in eye space)",
           "transform, clip, lighting"},
    Symbol{"H R", "the half vector normalize(L + V), and the mirror direction R = 2(N·L)N − L", "lighting"},
    Symbol{"P_eye N_eye", "the point and its normal in eye space, as the fragment shader reads them",
           "lighting"},
    Symbol{"p_light", "the light's position in eye space", "lighting"},
    Symbol{"n_light", "the unit normal of an emitter's face (an area light, a one-sided spot)", "lighting"},
    Symbol{"r_max", "the light's range: its window f_win is 0 from distance r_max on", "lighting"},
    Symbol{"m_a m_d m_s m_emission", "the material's ambient, diffuse, specular and emitted colours",
           "lighting"},
    Symbol{"l_a l_d l_s", "a light's ambient, diffuse and specular colours", "lighting"},
    Symbol{"a_global", "the scene's global ambient light", "lighting"},
    Symbol{"e e′", "the specular exponent (shininess) of Phong, and Blinn-Phong's matched e′ = 4e",
           "lighting"},
    Symbol{"att f_win", "the light's attenuation 1/(c0 + c1·d + c2·d²), and the window of its range",
           "lighting"},
    Symbol{"c_base F0 F0_dielectric",
           "physically based shading: the base colour, and the reflectance F0 seen head-on", "lighting"},
    Symbol{"f_r", "the BRDF: the share of the light from L reflected towards V", "lighting"},
    Symbol{"c_light", "the light's colour in physically based shading", "lighting"},
    Symbol{"D F G G1", "the microfacet distribution, Fresnel and shadowing terms of Cook-Torrance",
           "lighting"},
    Symbol{"α_r α_x α_y", "the roughness α_r = roughness², and its two values along T and B when anisotropic",
           "lighting"},
    Symbol{"ω", "a direction, L or V, in the shadowing term G1(ω)", "lighting"},
    Symbol{"θ θ_h cosθ sinθ dθ dω",
           "an angle: a corner's interior angle (a vertex normal's weight), or the angle from N in the "
           "Gaussian's normalising integral (over θ and the solid angle ω); θ_h the angle between N and H",
           "input, lighting"},
    Symbol{"η θ_i θ_t R_s R_p",
           "exact Fresnel: the ratio of refractive indices, the angles of incidence and refraction, and the "
           "reflectances of the two polarisations",
           "lighting"},
    Symbol{"π", "pi, 3.14159…", "lighting"},
    Symbol{"ρ", "the texture footprint: texels of level 0 one pixel step spans", "lighting"},
    Symbol{"lod", "the texture's level of detail log2 ρ (OpenGL's λ, which names the barycentrics here)",
           "lighting"},
    Symbol{"c_mod c_add", "the interpolated colours multiplied by the texel and added after it (Gouraud)",
           "lighting"},
    // Fog, output, blending, encoding.
    Symbol{"f τ", "the fog factor, the share of the lit colour kept (1: no fog); τ the fog's optical depth",
           "fog"},
    Symbol{"c_p c_fog", "the colour after fog, and the fog's colour", "fog"},
    Symbol{"y_e Δy", "height fog: the eye's height, and the point's height above the eye's", "fog"},
    Symbol{"α", "the fragment's opacity (alpha): 1 opaque, 0 fully transparent", "output"},
    Symbol{"c_s α_s", "the blend's source: the colour and alpha the shader writes", "output, blend"},
    Symbol{"z_key", "a transparent triangle's sort key: minus its centroid's or farthest corner's eye z",
           "blend"},
    Symbol{"c_d α_d", "the blend's destination: the colour and alpha in the colour buffer", "blend"},
    Symbol{"c_o α_o", "the blend's result, written to the colour buffer", "blend, encode"},
    Symbol{"c′ γ", "a channel encoded for the file (sRGB's curve, or c^(1/γ) with the gamma γ)", "encode"},
};

}  // namespace

std::span<const Symbol> notation() {
    return kNotation;
}

std::vector<std::string_view> formsOf(const Symbol& symbol) {
    std::vector<std::string_view> forms;
    std::string_view rest = symbol.symbol;
    while (!rest.empty()) {
        const std::size_t space = rest.find(' ');
        forms.push_back(rest.substr(0, space));
        rest = space == std::string_view::npos ? std::string_view() : rest.substr(space + 1);
    }
    return forms;
}

std::string notationText() {
    std::string text =
        "The symbols the screens print, in pipeline order: what each means, and the\n"
        "screens (their short names) that print it.\n\n";
    for (const Symbol& s : kNotation) {
        text += "  " + std::string(s.symbol) + "\n";
        text += wrapText("      " + std::string(s.meaning) + " [" + std::string(s.where) + "]", 80, 6);
    }
    return text;
}

}  // namespace facet::step
