// The step mode's notation: every symbol its screens print, once, with what it means and where it
// appears. The notation screen of the terminal walk (?? or notation), facet step --notation, the web
// page's "Notation" legend and the table in docs/teaching.md all come from this one list (the docs'
// copy is checked against it by a test).
//
// The choices, where a symbol could mean two things:
//   λ0 λ1 λ2     the screen-space barycentric weights, and λ′0 λ′1 λ′2 (a prime, not μ) the
//                perspective-correct ones, as the history and the interpolation screens wrote them.
//   lod          the texture level of detail log2 ρ: OpenGL 2.1 §3.8.8 calls it λ, which is taken here.
//   d_near d_far the depth range (OpenGL's glDepthRange n, f): n is the normal and f the fog factor
//                here, so the near and far planes are named in words ("the near plane").
//   e e′         the specular exponents of Phong and Blinn-Phong, as lighting-deck-C.txt writes them
//                (e′ ≈ 4e); n is the normal.
//   M_n          the normal matrix (lighting-deck-A.txt's vertex shader calls it N, the lighting's
//                unit normal here).
//   m_a l_a ...  a material's and a light's colours by the lighting equation's short names only.
//   α α_s α_d α_o  the fragment's opacity, and the alphas in blending; α_r the roughness of the
//                Cook-Torrance screens (α in the literature, taken here by the opacity).
//   f_r          the BRDF of physically based shading, as f is the fog factor.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace facet::step {

struct Symbol {
    // As the screens print it; several forms of one quantity separated by single spaces ("λ0 λ1 λ2").
    std::string_view symbol;
    std::string_view meaning;  // plain words, with the formula where there is one
    std::string_view where;    // the screens (their short names) that print it
};

// The notation, grouped by the stage that first prints each symbol.
std::span<const Symbol> notation();

// Each form of a symbol on its own ("λ0 λ1 λ2" gives λ0, λ1 and λ2).
std::vector<std::string_view> formsOf(const Symbol& symbol);

// The notation as text within 80 columns: each symbol, then its meaning and where, indented.
std::string notationText();

}  // namespace facet::step
