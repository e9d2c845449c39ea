#include "step/stage_images.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

#include "base/errors.h"
#include "base/memory_limit.h"
#include "pipeline/depth_format.h"
#include "pipeline/viewport.h"
#include "shading/fog.h"

namespace facet::step {

namespace {

// One stage image in memory, before it goes to the sink.
struct Stage {
    StageImage image;
    LinearImage pixels;
    ColorEncoding encoding = kLinearEncoding;
};

Stage makeStage(const std::string& id, std::string title, std::string description, LinearImage pixels,
                ColorEncoding encoding) {
    return {{id, std::move(title), id + ".png", std::move(description)}, std::move(pixels), encoding};
}

// Every number of the titles and descriptions: four significant digits, enough to check by hand.
std::string fourDigits(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", value);
    return text;
}

LinearImage filledImage(int width, int height, vec4 colour) {
    LinearImage image;
    image.width = width;
    image.height = height;
    image.pixels.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), colour);
    return image;
}

// What the data images show where no surface is.
constexpr vec4 kNoSurface{0.0f, 0.0f, 0.0f, 1.0f};
// The fog factor's "no surface": black there would read as f = 0, all fog.
constexpr vec4 kNoSurfaceForFog{0.0f, 0.0f, 0.3f, 1.0f};

// How an 8-bit file encodes colours, in words.
std::string encodingInWords(ColorEncoding encoding) {
    switch (encoding.curve) {
        case TransferCurve::Srgb:
            return "encoded with the sRGB curve";
        case TransferCurve::Power:
            return "encoded as c^(1/" + fourDigits(encoding.gamma) + ")";
        case TransferCurve::Linear:
            return "written without encoding (code = 255·c)";
    }
    return "";
}

// ---- Variants of the frame ----------------------------------------------------------------------------

// A copy of `prepared` (which shares its assets, triangles and shadows) with every draw as `change`
// leaves it (one draw at a time).
template <class Change>
PreparedScene copyWithDraws(const PreparedScene& prepared, Change change) {
    PreparedScene copy = prepared;
    for (PreparedDraw& draw : copy.draws)
        change(draw);
    return copy;
}

bool hasFog(const PreparedScene& prepared) {
    return std::any_of(prepared.draws.begin(), prepared.draws.end(),
                       [](const PreparedDraw& d) { return d.uniforms.fog.mode != FogMode::None; });
}

// A triangle of the frame: its draw (PreparedScene::draws) and its number in the draw (indices / 3).
struct DrawTriangle {
    std::uint32_t draw;
    std::uint32_t triangle;
};

// Every triangle of the frame in the order the frame draws them: planFrame's draw calls one after
// another, the opaque draws first, then the transparent triangles as the scene orders them.
std::vector<DrawTriangle> drawingOrder(const PreparedScene& prepared) {
    FrameMemory memory;  // a first frame: the transparent triangles sorted from scratch, as facet render's
    FrameStats stats;
    const std::vector<PlannedDraw> plan =
        planFrame(prepared, prepared.scene.transparency.mode, memory, stats);
    std::vector<DrawTriangle> order;
    for (const PlannedDraw& call : plan)
        for (std::uint32_t t = 0; t < call.indices.size() / 3; ++t)
            order.push_back({call.draw, call.triangleOfDraw(t)});
    return order;
}

// `prepared` with only the first `count` triangles of `order` (drawingOrder): each draw keeps those of
// its triangles, in its own order, and a draw left with none is left out. planFrame then draws them in
// the same order as the whole frame does: the opaque draws, and the transparent ones in file order
// (unsorted, exact), are cut to prefixes of themselves; and the back-to-front sort is stable (ties in
// index order), so sorting some of the transparent triangles keeps the order the whole sort gave them.
PreparedScene firstTriangles(const PreparedScene& prepared, std::span<const DrawTriangle> order,
                             std::size_t count) {
    std::vector<std::vector<bool>> kept(prepared.draws.size());
    for (std::size_t k = 0; k < prepared.draws.size(); ++k)
        kept[k].assign(prepared.draws[k].indices.size() / 3, false);
    for (std::size_t i = 0; i < count; ++i)
        kept[order[i].draw][order[i].triangle] = true;

    PreparedScene part = prepared;
    part.draws.clear();
    std::vector<DrawTriangles> triangles;
    for (std::size_t k = 0; k < prepared.draws.size(); ++k) {
        const PreparedDraw& whole = prepared.draws[k];
        DrawTriangles drawn;
        for (std::uint32_t t = 0; t < kept[k].size(); ++t)
            if (kept[k][t])
                drawn.indices.insert(drawn.indices.end(), whole.indices.begin() + 3 * t,
                                     whole.indices.begin() + 3 * t + 3);
        if (drawn.indices.empty()) continue;
        drawn.vertices.assign(whole.vertices.begin(), whole.vertices.end());
        part.draws.push_back(whole);
        triangles.push_back(std::move(drawn));
    }
    // The transparent triangles keep their order: the kept ones of each draw, draw by draw, as the
    // whole frame lists them.
    setTriangles(part, std::move(triangles));
    return part;
}

// ---- The observed frame --------------------------------------------------------------------------------

// The wireframe's layers, bits of one byte per pixel; a pixel shows the highest one set, so a drawn
// edge covers the part of the original triangle clipping removed along it.
enum WireLayer : std::uint8_t { kCulledEdge = 1, kRemovedEdge = 2, kDrawnEdge = 4 };

// How far beyond the view volume a removed edge is followed, in view volume widths and heights: the
// segment is clipped to |x|, |y| ≤ kGuardBand·w (and w ≥ kMinClipW) before it is projected, so that
// its window positions are finite and the line short enough to step along.
constexpr float kGuardBand = 4.0f;

// Clips the clip-space segment [a, b] to the guard band (Liang–Barsky in homogeneous coordinates: each
// plane a linear function d(P) ≥ 0, cut where d changes sign). False when nothing of it is left.
bool clipToGuardBand(vec4& a, vec4& b) {
    const auto distances = [](const vec4& p) {
        return std::array<float, 5>{p.w - kMinClipW, kGuardBand * p.w - p.x, kGuardBand * p.w + p.x,
                                    kGuardBand * p.w - p.y, kGuardBand * p.w + p.y};
    };
    const std::array<float, 5> da = distances(a), db = distances(b);
    float enter = 0.0f, leave = 1.0f;
    for (std::size_t i = 0; i < da.size(); ++i) {
        if (da[i] < 0.0f && db[i] < 0.0f) return false;
        if (da[i] < 0.0f) enter = std::max(enter, da[i] / (da[i] - db[i]));
        if (db[i] < 0.0f) leave = std::min(leave, da[i] / (da[i] - db[i]));
    }
    if (enter > leave) return false;
    const vec4 start = a + (b - a) * enter, end = a + (b - a) * leave;
    a = start;
    b = end;
    return true;
}

// The varyings of the per-pixel surface shader, which every draw of the observed frame runs.
using PerPixelVaryings = SurfaceShader<ShadingFrequency::Phong>::Varyings;
static_assert(sizeof(PerPixelVaryings) <= sizeof(FragmentEvent::varyings));

// N·0.5 + 0.5 of the unit normal along `normal`; grey for a zero normal, which has no direction.
vec3 normalColour(const vec3& normal) {
    const float length = glm::length(normal);
    if (!(length > 0.0f) || !std::isfinite(length)) return vec3(0.5f);
    return normal / length * 0.5f + 0.5f;
}

// The fog factor f the surface shader computes at an eye-space position (surfaceOutput: the draw's
// own precision for exp).
float fogFactorAt(const SurfaceUniforms& u, const vec3& eyePosition) {
    return u.precision == MathPrecision::Exact
               ? facet::fogFactorAt<float, vec3, MathPrecision::Exact>(u.fog, eyePosition)
               : facet::fogFactorAt<float, vec3, MathPrecision::Fast>(u.fog, eyePosition);
}

// Watches one frame drawn with per-pixel shading and keeps, per pixel, what the data images show.
class StageRecorder final : public FrameWatcher {
  public:
    explicit StageRecorder(const PreparedScene& observed)
        : state_(observed.state),
          width_(observed.scene.width),
          height_(observed.scene.height),
          wire_(pixelCount(), 0),
          fragments_(pixelCount(), 0),
          layers_(pixelCount(), 0),
          triangles_(filledImage(width_, height_, kNoSurface)),
          normals_(filledImage(width_, height_, kNoSurface)),
          fogFactors_(filledImage(width_, height_, kNoSurfaceForFog)) {}

    void onPlannedDraw(const PlannedDraw& call, const PreparedDraw& draw) override {
        draw_ = call.draw;
        uniforms_ = &draw.uniforms;
        transparent_ = draw.transparent;
    }
    void onAssembled(std::uint32_t, const ClipPolygon& assembled) override {
        for (int k = 0; k < 3; ++k)
            assembled_[k] = assembled.vertices[k].position;
    }
    // The triangle as assembled, in the removed colour: the clipped polygon's window triangles
    // (onSetup) cover what clipping kept of it.
    void onClipped(std::uint32_t, const ClipPolygon&) override {
        ++clipped_;
        for (int k = 0; k < 3; ++k) {
            vec4 a = assembled_[k], b = assembled_[(k + 1) % 3];
            if (clipToGuardBand(a, b))
                drawLine(toWindow(a, state_.viewport, state_.raster.subpixelBits).window,
                         toWindow(b, state_.viewport, state_.raster.subpixelBits).window, kRemovedEdge);
        }
    }
    void onSetup(std::uint32_t, const WindowTriangle& window, TriangleFate fate,
                 const TriangleSetup&) override {
        const WireLayer layer = fate == TriangleFate::Culled ? kCulledEdge : kDrawnEdge;
        (fate == TriangleFate::Culled ? culled_ : windowTriangles_) += 1;
        for (int k = 0; k < 3; ++k)
            drawLine(window.vertices[k].window, window.vertices[(k + 1) % 3].window, layer);
    }
    void onRejected(std::uint32_t, TriangleFate fate) override {
        if (fate != TriangleFate::ClippedAway) ++outside_;
    }
    void onFragment(const FragmentEvent& event) override {
        const std::size_t pixel = static_cast<std::size_t>(event.y) * width_ + event.x;
        maxFragments_ = std::max(maxFragments_, ++fragments_[pixel]);
        if (event.fate != FragmentFate::Written && event.fate != FragmentFate::Stored) return;
        if (transparent_) maxLayers_ = std::max(maxLayers_, ++layers_[pixel]);
        if (event.varyingCount != kVaryingFloatCount<PerPixelVaryings>)
            throw std::logic_error("stage images: a fragment without the per-pixel shader's varyings");
        PerPixelVaryings in;
        std::memcpy(&in, event.varyings.data(), sizeof in);  // as the fragment stage reads them
        triangles_.at(event.x, event.y) = vec4(triangleIdColor(draw_, event.triangle), 1.0f);
        normals_.at(event.x, event.y) = vec4(normalColour(in.normal), 1.0f);
        fogFactors_.at(event.x, event.y) = vec4(vec3(fogFactorAt(*uniforms_, in.position)), 1.0f);
    }

    Stage wireframe() const;
    Stage triangles() const;
    Stage overdraw() const;
    Stage normals() const;
    Stage fogFactor(const FogParams& fog, double viewScale) const;
    Stage layers(TransparencyMode mode) const;

  private:
    std::size_t pixelCount() const {
        return static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
    }

    // A line from a to b in window coordinates (pixels, y down), stepped one pixel at a time along its
    // longer axis; the pixels it passes get `layer`.
    void drawLine(vec2 a, vec2 b, WireLayer layer) {
        if (!std::isfinite(a.x) || !std::isfinite(a.y) || !std::isfinite(b.x) || !std::isfinite(b.y)) return;
        const vec2 d = b - a;
        const int steps = std::max(1, static_cast<int>(std::ceil(std::max(std::abs(d.x), std::abs(d.y)))));
        for (int i = 0; i <= steps; ++i) {
            const vec2 p = a + d * (static_cast<float>(i) / static_cast<float>(steps));
            const int x = static_cast<int>(std::floor(p.x)), y = static_cast<int>(std::floor(p.y));
            if (x >= 0 && x < width_ && y >= 0 && y < height_)
                wire_[static_cast<std::size_t>(y) * width_ + x] |= layer;
        }
    }
    LinearImage heatImage(const std::vector<std::uint32_t>& counts, std::uint32_t maxCount) const;

    DrawState state_;
    int width_, height_;
    std::vector<std::uint8_t> wire_;        // WireLayer bits
    std::vector<std::uint32_t> fragments_;  // every fragment, whatever its fate
    std::vector<std::uint32_t> layers_;     // fragments of transparent draws that reached the colour
    std::uint32_t maxFragments_ = 0, maxLayers_ = 0;
    LinearImage triangles_, normals_, fogFactors_;  // of the last fragment to reach the colour
    std::array<vec4, 3> assembled_{};
    std::uint32_t draw_ = 0;
    const SurfaceUniforms* uniforms_ = nullptr;
    bool transparent_ = false;
    std::size_t clipped_ = 0, culled_ = 0, windowTriangles_ = 0, outside_ = 0;
};

// The heat scale's legend in counts: "Black: 0; blue: 1; red: 9, the most at any pixel; ...".
std::string heatLegend(std::uint32_t maxCount) {
    if (maxCount == 0) return "Black everywhere: no fragment reached any pixel.";
    if (maxCount == 1) return "Black: 0; blue: 1, the most at any pixel.";
    return "Black: 0; blue: 1; red: " + std::to_string(maxCount) +
           ", the most at any pixel; in between the colours run from blue through cyan, green (" +
           fourDigits(1.0 + 0.5 * (maxCount - 1.0)) + ") and yellow to red.";
}

LinearImage StageRecorder::heatImage(const std::vector<std::uint32_t>& counts, std::uint32_t maxCount) const {
    LinearImage image = filledImage(width_, height_, kNoSurface);
    for (std::size_t i = 0; i < counts.size(); ++i)
        image.pixels[i] = vec4(heatColor(counts[i], maxCount), 1.0f);
    return image;
}

Stage StageRecorder::wireframe() const {
    LinearImage image = filledImage(width_, height_, kNoSurface);
    for (std::size_t i = 0; i < wire_.size(); ++i) {
        if (wire_[i] & kDrawnEdge)
            image.pixels[i] = vec4(kDrawnEdgeColor, 1.0f);
        else if (wire_[i] & kRemovedEdge)
            image.pixels[i] = vec4(kRemovedEdgeColor, 1.0f);
        else if (wire_[i] & kCulledEdge)
            image.pixels[i] = vec4(kCulledEdgeColor, 1.0f);
    }
    return makeStage(
        "wireframe", "Wireframe: the triangles on the screen, after clipping and the viewport",
        "Every triangle's edges after the perspective divide and the viewport transform, as the rasterizer "
        "receives them. White: the " +
            std::to_string(windowTriangles_) +
            " triangles drawn (a triangle cut by a clipping plane becomes a polygon, drawn as a fan of "
            "triangles). Red: what clipping removed of the triangles it cut (" +
            std::to_string(clipped_) +
            " here), such as their parts in front of the near plane. Grey: "
            "triangles culled for facing away (" +
            std::to_string(culled_) + " here). Not shown: triangles wholly outside the view (" +
            std::to_string(outside_) + " here).",
        std::move(image), kLinearEncoding);
}

Stage StageRecorder::triangles() const {
    return makeStage("triangles", "Triangle ids: the triangle that drew each pixel last",
                     "Each triangle in a colour of its own (from its draw and its number in it), where it "
                     "was the last to write the pixel (with exact transparency: the last stored in the "
                     "pixel's fragment list). Black: no triangle. It shows how the surfaces are cut into "
                     "triangles, and which one won each pixel.",
                     triangles_, kLinearEncoding);
}

Stage StageRecorder::overdraw() const {
    return makeStage("overdraw", "Overdraw: fragments per pixel, at most " + std::to_string(maxFragments_),
                     "How many fragments reached the depth test at each pixel, whatever became of them "
                     "(written, hidden behind a nearer surface, blended). " +
                         heatLegend(maxFragments_) +
                         " Each fragment beyond the first at a pixel is work spent on a surface that is "
                         "hidden or blended.",
                     heatImage(fragments_, maxFragments_), kLinearEncoding);
}

Stage StageRecorder::normals() const {
    return makeStage("normals", "Normals in eye space as colours: RGB = N·0.5 + 0.5",
                     "The interpolated normal N of the fragment that wrote each pixel last, made unit "
                     "length, with x as red, y as green and z as blue. Facing the camera, N = (0, 0, 1), is "
                     "(0.5, 0.5, 1), light blue; facing right, (1, 0, 0), is (1, 0.5, 0.5), pink; facing "
                     "up, (0, 1, 0), is (0.5, 1, 0.5), light green. Black: no surface. Objects shaded per "
                     "vertex or per face are drawn per pixel here, so that the normal reaches the pixel.",
                     normals_, kLinearEncoding);
}

Stage StageRecorder::fogFactor(const FogParams& fog, double viewScale) const {
    const std::string distance = fog.distance == FogDistance::Radial
                                     ? "z = |P_eye|, the distance from the eye"
                                     : "z = |z_eye|, the depth in eye space";
    std::string formula;
    switch (fog.mode) {
        case FogMode::None:
            formula = "f = 1";
            break;
        case FogMode::Linear:
            formula = "f = (end − z)/(end − start) with start " + fourDigits(fog.start / viewScale) +
                      " and end " + fourDigits(fog.end / viewScale);
            break;
        case FogMode::Exponential:
            formula = "f = e^(−density·z) with density " + fourDigits(fog.density * viewScale);
            break;
        case FogMode::Height:
            formula = "f = e^(−τ), τ the height fog's optical depth with density " +
                      fourDigits(fog.density * viewScale) + " and falloff " +
                      fourDigits(fog.falloff * viewScale);
            break;
        case FogMode::ExponentialSquared:
            formula = "f = e^(−(density·z)²) with density " + fourDigits(fog.density * viewScale);
            break;
    }
    return makeStage("fog-factor", "Fog factor f per pixel: white 1 (no fog) to black 0 (only fog)",
                     "The fog factor of the fragment that wrote each pixel last, as grey: " + formula + ", " +
                         distance +
                         ", clamped to [0, 1]. The fog then mixes the colour c_s with "
                         "the fog colour c_fog: c_p = f·c_s + (1 − f)·c_fog. Dark blue: no surface.",
                     fogFactors_, kLinearEncoding);
}

Stage StageRecorder::layers(TransparencyMode mode) const {
    const std::string what =
        mode == TransparencyMode::Exact
            ? "How many fragments of transparent objects each pixel's fragment list holds, composited "
              "back to front after the last draw. "
            : "How many fragments of transparent objects each pixel blended: those that passed the depth "
              "test against the opaque surfaces (transparent ones do not write depth). ";
    return makeStage("layers", "Transparency layers per pixel, at most " + std::to_string(maxLayers_),
                     what + heatLegend(maxLayers_), heatImage(layers_, maxLayers_), kLinearEncoding);
}

// The depth buffer as distance from the eye: the viewport transform (viewport.h) and the projection
// undone with the camera's own matrix, in world units, brightest at the frame's nearest point.
Stage depthStage(const PreparedScene& prepared, const Framebuffer& framebuffer) {
    const Viewport& v = prepared.state.viewport;
    const glm::dmat4 viewFromClip = glm::inverse(prepared.camera.clipFromViewExact);
    const int width = framebuffer.width(), height = framebuffer.height();
    std::vector<double> distances(static_cast<std::size_t>(width) * height, -1.0);  // −1: no surface
    double nearest = std::numeric_limits<double>::infinity(), farthest = -nearest;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const DepthBufferFormat format = prepared.state.depth.format;
            const float stored = framebuffer.depth(x, y);
            if (stored == depthClearValue(format)) continue;
            // The window depth under OpenGL's convention, which clipFromViewExact's inverse undoes:
            // unorm codes back to [0, 1]; reversed Z's z_r = (1 − z_ndc)/2, i.e. 1 − z_r.
            const float window = windowDepthOf(format, stored);
            const double depth = format == DepthBufferFormat::ReversedFloat ? 1.0 - window : window;
            // Window → normalised device coordinates at the pixel's centre, then → eye space.
            const glm::dvec4 ndc(2.0 * (x + 0.5 - v.x) / v.width - 1.0,
                                 1.0 - 2.0 * (y + 0.5 - v.y) / v.height,
                                 2.0 * (depth - v.minDepth) / (v.maxDepth - v.minDepth) - 1.0, 1.0);
            const glm::dvec4 eye = viewFromClip * ndc;
            const double distance = -eye.z / eye.w / prepared.camera.viewScale;
            if (!std::isfinite(distance)) continue;
            distances[static_cast<std::size_t>(y) * width + x] = distance;
            nearest = std::min(nearest, distance);
            farthest = std::max(farthest, distance);
        }
    // Nearest white, farthest a dark grey (not black, which is "no surface").
    constexpr double kFarthestGrey = 0.2;
    LinearImage image = filledImage(width, height, kNoSurface);
    for (std::size_t i = 0; i < distances.size(); ++i) {
        if (distances[i] < 0.0) continue;
        const double t = farthest > nearest ? (distances[i] - nearest) / (farthest - nearest) : 0.0;
        image.pixels[i] = vec4(vec3(static_cast<float>(1.0 - (1.0 - kFarthestGrey) * t)), 1.0f);
    }
    const bool any = nearest <= farthest;
    const std::string title = any ? "Depth as distance from the eye: white " + fourDigits(nearest) +
                                        " to dark grey " + fourDigits(farthest) + " (this frame's range)"
                                  : "Depth: no surface wrote the depth buffer";
    return makeStage(
        "depth", title,
        "The depth buffer after the frame, turned back into distance from the eye along the view "
        "direction (world units) through the inverse of the projection: the buffer stores z_w = (z_ndc + "
        "1)/2, which crowds the far distances together. Nearer is brighter, from this frame's nearest "
        "surface to its farthest; the camera's near and far planes are at " +
            fourDigits(prepared.camera.near) + " and " + fourDigits(prepared.camera.far) +
            ". Black: no surface (the buffer holds its clear value). Transparent surfaces do not write "
            "depth.",
        std::move(image), kLinearEncoding);
}

std::string termDescription(LightingTerm term) {
    switch (term) {
        case kEmissionTerm:
            return "Only the emission term m_emission: light the surface gives off itself, the same from "
                   "every direction and under any light.";
        case kAmbientTerm:
            return "Only the ambient term m_a ⊗ (a_global + Σ l_a): light that has bounced "
                   "around the scene so often that it has no direction left.";
        case kDiffuseTerm:
            return "Only the diffuse term m_d ⊗ Σ l_d·max(N·L, 0)·attenuation·spot: Lambert's "
                   "cosine law, brightest where the surface faces the light, the same from every viewpoint.";
        case kSpecularTerm:
            return "Only the specular term m_s ⊗ Σ l_s·(R·V)^e (Phong) or (N·H)^e "
                   "(Blinn-Phong), times attenuation and spot (Cook-Torrance: D·F·G/(4(N·L)(N·V))): the "
                   "highlights, which move when the viewer moves.";
        default:
            return "";
    }
}

}  // namespace

vec3 triangleIdColor(std::uint32_t draw, std::uint32_t triangle) {
    // MurmurHash3's finaliser (fmix32): every input bit changes about half of the output bits, so
    // neighbouring triangles get unrelated colours.
    const auto mix = [](std::uint32_t h) {
        h ^= h >> 16;
        h *= 0x85ebca6bu;
        h ^= h >> 13;
        h *= 0xc2b2ae35u;
        h ^= h >> 16;
        return h;
    };
    const std::uint32_t h = mix(mix(draw + 0x9e3779b9u) ^ triangle);
    const auto channel = [&](int shift) {
        return 0.3f + 0.7f * static_cast<float>((h >> shift) & 0xffu) / 255.0f;
    };
    return {channel(0), channel(8), channel(16)};
}

vec3 heatColor(std::uint32_t count, std::uint32_t maxCount) {
    if (count == 0) return vec3(0.0f);
    static constexpr std::array<vec3, 5> kStops = {vec3(0, 0, 1), vec3(0, 1, 1), vec3(0, 1, 0), vec3(1, 1, 0),
                                                   vec3(1, 0, 0)};
    const float p = maxCount > 1
                        ? std::min(1.0f, static_cast<float>(count - 1) / static_cast<float>(maxCount - 1))
                        : 0.0f;
    const float scaled = p * static_cast<float>(kStops.size() - 1);
    const std::size_t below = std::min(static_cast<std::size_t>(scaled), kStops.size() - 2);
    return glm::mix(kStops[below], kStops[below + 1], scaled - static_cast<float>(below));
}

void renderStageImages(const PreparedScene& prepared, const StageImageOptions& options,
                       const StageImageSink& sink) {
    const auto emit = [&](const Stage& stage) { sink(stage.image, stage.pixels, stage.encoding); };
    Framebuffer framebuffer(prepared.scene.width, prepared.scene.height);
    DrawContext context(options.threads);
    // A frame as facet render draws its first one (fresh memory: the transparent triangles sorted from
    // scratch), with `terms`.
    const auto renderColour = [&](const PreparedScene& scene, std::uint8_t terms) {
        FrameMemory memory;
        renderFrame(scene, framebuffer, context, memory, terms);
        return toImage(framebuffer);
    };
    const bool fog = hasFog(prepared);
    const bool transparency = !prepared.transparentTriangles.empty();

    // The observed frame, every draw shaded per pixel so that every fragment's varyings carry the
    // eye-space position and normal (coverage, depth and fates do not depend on the shading frequency).
    // A shader of one's own is replaced by the built-in one here, its varyings being its own: only the
    // fragments a discarding one drops differ (the colour images below are drawn with it).
    std::optional<Stage> fogFactor, layers;
    {
        std::optional<PreparedScene> perPixel;
        if (std::any_of(prepared.draws.begin(), prepared.draws.end(), [](const PreparedDraw& d) {
                return d.frequency != ShadingFrequency::Phong || d.userShader.module;
            }))
            perPixel = copyWithDraws(prepared, [](PreparedDraw& d) {
                d.frequency = ShadingFrequency::Phong;
                d.userShader = {};
                d.userUniforms.clear();
            });
        const PreparedScene& observed = perPixel ? *perPixel : prepared;
        StageRecorder recorder(observed);
        FrameMemory memory;
        renderFrameWatched(observed, framebuffer, context, memory, recorder, options.terms);
        emit(recorder.wireframe());
        emit(recorder.triangles());
        emit(recorder.overdraw());
        emit(depthStage(prepared, framebuffer));
        emit(recorder.normals());
        const auto fogged =
            std::find_if(prepared.draws.begin(), prepared.draws.end(),
                         [](const PreparedDraw& d) { return d.uniforms.fog.mode != FogMode::None; });
        if (fog) fogFactor = recorder.fogFactor(fogged->uniforms.fog, prepared.camera.viewScale);
        if (transparency) layers = recorder.layers(prepared.scene.transparency.mode);
    }

    // Each lighting term alone, as facet render --components draws them.
    for (const EnumName<LightingTerm>& term : kLightingTermNames) {
        if (!(options.terms & term.value)) continue;
        std::string name(term.name);
        name[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(name[0])));
        emit(makeStage(std::string(term.name), name + " term alone",
                       termDescription(term.value) + " Where there is no fog and no transparency, the four "
                                                     "terms add up to the final image.",
                       renderColour(prepared, term.value), prepared.encoding));
    }

    if (fog) {
        const PreparedScene clear =
            copyWithDraws(prepared, [](PreparedDraw& d) { d.uniforms.fog.mode = FogMode::None; });
        emit(makeStage(
            "before-fog", "Before fog: the lit colour c_s",
            "The frame with fog turned off: the colour c_s each surface has before the fog "
            "mixes it with the fog colour c_fog, c_p = f·c_s + (1 − f)·c_fog (f in the next image).",
            renderColour(clear, options.terms), prepared.encoding));
        emit(*fogFactor);
    }
    if (layers) emit(*layers);

    emit(
        makeStage("final", "Final image, as facet render writes it",
                  "The frame with everything: the lighting terms, fog and transparency; the file's colours " +
                      encodingInWords(prepared.encoding) + ".",
                  renderColour(prepared, options.terms), prepared.encoding));

    // The build-up: the frame after the first 1/N, 2/N, ... of its triangles in drawing order.
    const std::vector<DrawTriangle> order = drawingOrder(prepared);
    const std::size_t frames =
        std::min(static_cast<std::size_t>(std::max(options.buildFrames, 0)), order.size());
    std::string orderInWords = "the opaque objects first, in the order of the file";
    if (transparency) {
        switch (prepared.scene.transparency.mode) {
            case TransparencyMode::Sorted:
                orderInWords += ", then the transparent triangles sorted back to front";
                break;
            case TransparencyMode::Unsorted:
                orderInWords += ", then the transparent ones, in the order of the file";
                break;
            case TransparencyMode::Exact:
                orderInWords +=
                    ", then the transparent ones into per-pixel lists, composited at the end of "
                    "each frame";
                break;
        }
    }
    for (std::size_t k = 1; k <= frames; ++k) {
        const std::size_t count = k * order.size() / frames;
        char id[32];
        std::snprintf(id, sizeof id, "build-%03zu", k);
        emit(makeStage(id,
                       "Build-up " + std::to_string(k) + " of " + std::to_string(frames) + ": the first " +
                           std::to_string(count) + " of " + std::to_string(order.size()) + " triangles",
                       "The frame after its first " + std::to_string(count) +
                           " triangles, in the order the renderer draws them: " + orderInWords +
                           ". A later triangle hides an earlier one only where it is nearer (the depth "
                           "test). The last frame is the final image.",
                       renderColour(firstTriangles(prepared, order, count), options.terms),
                       prepared.encoding));
    }
}

LinearImage magnified(const LinearImage& image, int scale) {
    LinearImage out;
    out.width = image.width * scale;
    out.height = image.height * scale;
    out.pixels.resize(static_cast<std::size_t>(out.width) * out.height);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            out.at(x, y) = image.at(x / scale, y / scale);
    return out;
}

std::uint64_t stageImagesBytes(int width, int height, int scale) {
    const std::uint64_t pixels = std::uint64_t(width) * std::uint64_t(height);
    // StageRecorder: triangles_, normals_, fogFactors_, fragments_, layers_, wire_.
    const std::uint64_t recorder = 3 * sizeof(vec4) + 2 * sizeof(std::uint32_t) + sizeof(std::uint8_t);
    // The stage emitted (a LinearImage), depthStage's distances, renderColour's image.
    const std::uint64_t stage = sizeof(vec4) + sizeof(double) + sizeof(vec4);
    const std::uint64_t magnifiedCopy =
        scale > 1 ? timesSaturating(std::uint64_t(scale) * std::uint64_t(scale), sizeof(vec4)) : 0;
    return plusSaturating(Framebuffer::bytesFor(width, height, 1),
                          timesSaturating(pixels, recorder + stage + magnifiedCopy));
}

std::vector<StageImage> writeStageImages(const PreparedScene& prepared, const std::filesystem::path& dir,
                                         const StageImageOptions& options) {
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    if (error) throw InputError(dir.string() + ": cannot create the folder: " + error.message());
    std::vector<StageImage> written;
    renderStageImages(prepared, options,
                      [&](const StageImage& image, const LinearImage& pixels, ColorEncoding encoding) {
                          if (options.scale == 1)
                              writeImage(dir / image.file, pixels, encoding);
                          else
                              writeImage(dir / image.file, magnified(pixels, options.scale), encoding);
                          written.push_back(image);
                      });
    return written;
}

}  // namespace facet::step
