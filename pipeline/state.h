// Per-draw fixed-function state: everything the pipeline does besides the user's shaders.
// Accuracy choices (sub-pixel bits, interpolation) live here, per draw, not as scattered constants,
// so a caller can trade speed for accuracy knowingly and the step mode can print what was chosen.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <span>

#include "names.h"

namespace facet {

// The part of the framebuffer a draw maps normalised device coordinates onto; pixels outside it
// are never touched (it doubles as the scissor rectangle).
struct Viewport {
    int x = 0;  // pixels, left edge
    int y = 0;  // pixels, top edge (window y grows downwards, row 0 is the top of the image)
    int width = 0;
    int height = 0;
    float minDepth = 0.0f;  // window depth of the near plane (NDC z = −1)
    float maxDepth = 1.0f;  // window depth of the far plane (NDC z = +1)
};

// Whether two viewports cover the same pixels (their depth ranges may differ): draws into them share
// one tile grid.
inline bool samePixels(const Viewport& a, const Viewport& b) {
    return a.x == b.x && a.y == b.y && a.width == b.width && a.height == b.height;
}

enum class CullMode : std::uint8_t { None, Back, Front };
inline constexpr EnumName<CullMode> kCullModeNames[] = {
    {CullMode::Back, "back"}, {CullMode::Front, "front"}, {CullMode::None, "none"}};
constexpr std::span<const EnumName<CullMode>> enumNames(CullMode) {
    return kCullModeNames;
}

// Which winding, as seen on the screen, is a front face (OpenGL's glFrontFace; CCW by default).
enum class FrontFace : std::uint8_t { CounterClockwise, Clockwise };
inline constexpr EnumName<FrontFace> kFrontFaceNames[] = {{FrontFace::CounterClockwise, "counter-clockwise"},
                                                          {FrontFace::Clockwise, "clockwise"}};
constexpr std::span<const EnumName<FrontFace>> enumNames(FrontFace) {
    return kFrontFaceNames;
}

// Depth comparison: the fragment passes when `fragmentDepth OP storedDepth` holds (glDepthFunc).
enum class CompareOp : std::uint8_t {
    Never,
    Less,
    Equal,
    LessEqual,
    Greater,
    NotEqual,
    GreaterEqual,
    Always
};
inline constexpr EnumName<CompareOp> kCompareOpNames[] = {{CompareOp::Never, "never"},
                                                          {CompareOp::Less, "less"},
                                                          {CompareOp::Equal, "equal"},
                                                          {CompareOp::LessEqual, "less-equal"},
                                                          {CompareOp::Greater, "greater"},
                                                          {CompareOp::NotEqual, "not-equal"},
                                                          {CompareOp::GreaterEqual, "greater-equal"},
                                                          {CompareOp::Always, "always"}};
constexpr std::span<const EnumName<CompareOp>> enumNames(CompareOp) {
    return kCompareOpNames;
}

// glPolygonOffset (OpenGL 4.6 §14.6.5): every fragment of a triangle has its window depth moved by
// o = factor·m + units·r, m = max(|∂z/∂x|, |∂z/∂y|) the triangle's depth slope in window space (per
// pixel) and r DepthFormat::kResolution. Shadow maps are drawn with it, so that a lit surface does not
// shadow itself (shadow acne). 0, 0 (every other draw): nothing is computed, depths are untouched.
struct DepthOffset {
    float factor = 0;
    float units = 0;
    bool any() const { return factor != 0.0f || units != 0.0f; }
};

// What the depth buffer stores (depth_format.h): the trade of depth precision against memory that
// hardware offers (docs/trade.md, "Depth buffer"). Every format keeps Facet's 32-bit float buffer; the
// unorm ones store integer codes in it.
enum class DepthBufferFormat : std::uint8_t {
    Float,          // 32-bit float window depth, near 0, far 1 (OpenGL's default)
    Unorm16,        // 16-bit unsigned normalised: round(z_w·(2^16 − 1))
    Unorm24,        // 24-bit unsigned normalised: round(z_w·(2^24 − 1))
    ReversedFloat,  // 32-bit float, reversed Z: near 1, far 0, clip depth 0 ≤ z ≤ w (GL_ZERO_TO_ONE)
};
inline constexpr EnumName<DepthBufferFormat> kDepthBufferFormatNames[] = {
    {DepthBufferFormat::Float, "float"},
    {DepthBufferFormat::Unorm16, "unorm16"},
    {DepthBufferFormat::Unorm24, "unorm24"},
    {DepthBufferFormat::ReversedFloat, "reversed-float"}};
constexpr std::span<const EnumName<DepthBufferFormat>> enumNames(DepthBufferFormat) {
    return kDepthBufferFormatNames;
}

// How the draw's clip-space depth follows w, when its projection ties them: a perspective projection P
// gives w_c = −z_e and z_c = P[2][2]·z_e + P[3][2] for every point, so z_c = slope·w_c + offset with
// slope = −P[2][2], offset = P[3][2] (OpenGL's: slope = (f + n)/(f − n), offset = −2fn/(f − n); reversed
// Z's: slope = −n/(f − n), offset = fn/(f − n)). The clipper gives the vertices it makes this depth
// where the one interpolated from the corners' cannot be resolved (clip.h, clipEdgePoint): when the far plane
// is 10^8 near planes away, a huge triangle's corners near the far plane have z_c and w the same float (they
// differ by 2n(w − f)/(f − n), below half a step of w), so every vertex interpolated between them has z_c =
// w, window depth 1, and fails the test against the cleared far plane, where the relation keeps 1 − z_w ≈
// n/w. Unknown (the default): interpolation, as for a user's vertex shader (gl_Position need not follow the
// camera), an orthographic projection (z_c is tied to z_e, not to w = 1, and interpolation is exact there)
// and shadow maps.
struct DepthFromW {
    bool known = false;
    double slope = 0.0;
    double offset = 0.0;
    float at(float w) const { return static_cast<float>(slope * static_cast<double>(w) + offset); }
};

struct DepthState {
    bool testEnabled = true;
    bool writeEnabled = true;
    // ReversedFloat stores nearer surfaces as larger depths: it goes with Greater (nearerPasses()).
    CompareOp compare = CompareOp::Less;
    DepthOffset offset;
    DepthBufferFormat format = DepthBufferFormat::Float;
    DepthFromW fromW;  // z_c as a function of w, for the vertices the clipper makes
};

// How precisely the colour buffer keeps what is written to it (clears, blending, the resolve of
// fragment lists). The buffer's storage stays linear float; after every write the value is rounded as
// the chosen format would store it (blend.h, roundToColorBuffer), so blending runs at that precision.
enum class ColorBufferFormat : std::uint8_t {
    Float,   // 32-bit float per channel: no rounding (today's buffer)
    Half,    // IEEE binary16 per channel, round to nearest even, beyond 65504 clamped to 65504
    Unorm8,  // 8 bits per channel, linear: round(clamp(c, 0, 1)·255)/255
};
inline constexpr EnumName<ColorBufferFormat> kColorBufferFormatNames[] = {
    {ColorBufferFormat::Float, "float"},
    {ColorBufferFormat::Half, "half"},
    {ColorBufferFormat::Unorm8, "unorm8"}};
constexpr std::span<const EnumName<ColorBufferFormat>> enumNames(ColorBufferFormat) {
    return kColorBufferFormatNames;
}

// How varyings are interpolated across a triangle in screen space.
enum class Interpolation : std::uint8_t {
    PerspectiveCorrect,  // a = Σ λᵢ·aᵢ/wᵢ ÷ Σ λᵢ/wᵢ: right for a plane seen in perspective
    Affine,              // a = Σ λᵢ·aᵢ: cheaper, warps textures on tilted surfaces (kept to show that)
};
inline constexpr EnumName<Interpolation> kInterpolationNames[] = {
    {Interpolation::PerspectiveCorrect, "perspective"}, {Interpolation::Affine, "affine"}};
constexpr std::span<const EnumName<Interpolation>> enumNames(Interpolation) {
    return kInterpolationNames;
}

// How a fragment's colour combines with the colour already in the framebuffer (glBlendFunc).
// Only Replace ignores what was drawn before; of the others, Additive and Multiply commute (any
// order of the surfaces gives the same sum or product), Over and PremultipliedOver do not, which is
// why transparent surfaces are sorted back to front.
enum class BlendMode : std::uint8_t {
    Replace,   // c = c_s
    Additive,  // c = c_s + c_d, α = α_s + α_d (GL_ONE, GL_ONE): light adds up (glows, fire)
    Over,  // c = α_s·c_s + (1 − α_s)·c_d, α = α_s + (1 − α_s)·α_d (Porter–Duff over, straight alpha)
    PremultipliedOver,  // c = c_s + (1 − α_s)·c_d, α likewise (c_s already multiplied by α_s; GL_ONE,
                        // GL_ONE_MINUS_SRC_ALPHA)
    Multiply,           // c = c_s ⊗ c_d, α = α_d (GL_DST_COLOR, GL_ZERO): a coloured filter, tinted glass
    // c as Over, α = α_s·α_s + (1 − α_s)·α_d: glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA), whose
    // factors apply to alpha too. The gl preset's over; not offered to scene files (the preset picks it).
    OverGL,
};
// Replace and OverGL last: a scene's "blend" offers the others (a scene object is opaque or blended,
// and the gl preset turns over into OverGL).
inline constexpr EnumName<BlendMode> kBlendModeNames[] = {
    {BlendMode::Over, "over"},         {BlendMode::Additive, "additive"},
    {BlendMode::Multiply, "multiply"}, {BlendMode::PremultipliedOver, "premultiplied"},
    {BlendMode::Replace, "replace"},   {BlendMode::OverGL, "gl-over"}};
constexpr std::span<const EnumName<BlendMode>> enumNames(BlendMode) {
    return kBlendModeNames;
}

// Where a draw's fragments go after the fragment shader and the depth test.
enum class FragmentOutput : std::uint8_t {
    Blend,          // blended into the colour buffer now, in submission order (DrawState::blend)
    AppendToLists,  // appended to the pixel's fragment list with DrawState::blend, for
                    // resolveFragmentLists() to sort by depth and composite (fragment_lists.h):
                    // exact transparency, whatever the order of the draws and their triangles
};
inline constexpr EnumName<FragmentOutput> kFragmentOutputNames[] = {
    {FragmentOutput::Blend, "blend"}, {FragmentOutput::AppendToLists, "append to fragment lists"}};
constexpr std::span<const EnumName<FragmentOutput>> enumNames(FragmentOutput) {
    return kFragmentOutputNames;
}

// Sub-pixel precision of the rasterizer: window positions are snapped to 1/2^bits of a pixel.
// 8 bits is what Mesa llvmpipe and SwiftShader (and Vulkan's 2022 roadmap) use.
inline constexpr int kMaxSubpixelBits = 8;

// Which vertex of a triangle gives the values of flat varyings (glProvokingVertex).
enum class ProvokingVertex : std::uint8_t {
    Last,   // the third vertex, OpenGL's default (GL_LAST_VERTEX_CONVENTION)
    First,  // the first vertex, as Direct3D and Vulkan do
};
inline constexpr EnumName<ProvokingVertex> kProvokingVertexNames[] = {{ProvokingVertex::Last, "last"},
                                                                      {ProvokingVertex::First, "first"}};
constexpr std::span<const EnumName<ProvokingVertex>> enumNames(ProvokingVertex) {
    return kProvokingVertexNames;
}

struct RasterState {
    CullMode cull = CullMode::Back;
    FrontFace frontFace = FrontFace::CounterClockwise;
    ProvokingVertex provokingVertex = ProvokingVertex::Last;
    int subpixelBits = kMaxSubpixelBits;  // 0..8
};

struct DrawState {
    Viewport viewport;
    RasterState raster;
    DepthState depth;
    Interpolation interpolation = Interpolation::PerspectiveCorrect;
    BlendMode blend = BlendMode::Replace;
    FragmentOutput output = FragmentOutput::Blend;
    ColorBufferFormat colorBuffer = ColorBufferFormat::Float;
    // Multisampling: coverage and depth are tested at this many samples per pixel (1, 2, 4, 8 or 16, the
    // standard positions of sample_position.h) in the framebuffer's sample planes, which must hold as
    // many (Framebuffer::useSamples); the fragment is shaded once per pixel. 1: the pixel centre only.
    int samples = 1;
};

std::ostream& operator<<(std::ostream& os, CullMode mode);
std::ostream& operator<<(std::ostream& os, FrontFace face);
std::ostream& operator<<(std::ostream& os, ProvokingVertex vertex);
std::ostream& operator<<(std::ostream& os, CompareOp op);
std::ostream& operator<<(std::ostream& os, Interpolation mode);
std::ostream& operator<<(std::ostream& os, BlendMode mode);
std::ostream& operator<<(std::ostream& os, FragmentOutput output);
std::ostream& operator<<(std::ostream& os, DepthBufferFormat format);
std::ostream& operator<<(std::ostream& os, ColorBufferFormat format);
std::ostream& operator<<(std::ostream& os, const DrawState& state);

}  // namespace facet
