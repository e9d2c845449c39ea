#include "step/views.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>

#include "pipeline/clip.h"
#include "pipeline/depth_format.h"
#include "pipeline/rasterize.h"
#include "shading/gamma.h"

namespace facet::step {

std::string number(double value) {
    if (std::isnan(value)) return "NaN";  // not "-nan": the sign of a NaN means nothing
    if (value == 0.0) value = 0.0;        // no "-0"
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", value);
    return text;
}

std::string vectorText(const vec2& v) {
    return "(" + number(v.x) + ", " + number(v.y) + ")";
}
std::string vectorText(const vec3& v) {
    return "(" + number(v.x) + ", " + number(v.y) + ", " + number(v.z) + ")";
}
std::string vectorText(const vec4& v) {
    return "(" + number(v.x) + ", " + number(v.y) + ", " + number(v.z) + ", " + number(v.w) + ")";
}

namespace {

// "−1.5" as "(−1.5)", to be subtracted.
std::string bracketedIfNegative(double value) {
    if (value >= 0) return number(value);
    std::string text = "(";
    text += number(value);
    text += ")";
    return text;
}

// `first` and `second` on one line when it fits the screen, else `second` on the next line after
// `indent` spaces: for a line whose numbers may be long. Ends in '\n'.
std::string oneLineOrTwo(const std::string& first, const std::string& second, std::size_t indent) {
    if (columnsOf(first) + 1 + columnsOf(second) <= kScreenColumns) return first + " " + second + "\n";
    return first + "\n" + std::string(indent, ' ') + second + "\n";
}

std::string integer(std::int64_t value) {
    return std::to_string(value);
}

// A fixed-point window coordinate: "123456/256 = 482.25".
std::string fixedText(std::int64_t value) {
    return integer(value) + "/" + integer(kFixedOne) + " = " + number(double(value) / kFixedOne);
}

// "+ 5" or "− 5": a term after the first of a sum.
std::string signedTerm(std::int64_t value) {
    return (value < 0 ? "− " : "+ ") + std::to_string(value < 0 ? -value : value);
}

std::string triangleName(const TriangleRef& ref) {
    return "triangle " + std::to_string(ref.number);
}

// "(draw 1, its triangle 7)" when the scene has more than one draw.
std::string drawPlace(const PreparedScene& prepared, const TriangleRef& ref) {
    if (prepared.draws.size() == 1) return "";
    return " (draw " + std::to_string(ref.draw) + ", its triangle " + std::to_string(ref.triangle) + ")";
}

void matrixLines(std::ostringstream& out, const std::string& name, const mat4& m) {
    for (int row = 0; row < 4; ++row) {
        out << (row == 0 ? "  " + name + " = [" : std::string(name.size() + 5, ' ') + " ");
        for (int column = 0; column < 4; ++column) {
            char cell[16];
            std::snprintf(cell, sizeof cell, "%11.5g",
                          double(m[column][row]) == 0.0 ? 0.0 : double(m[column][row]));
            out << cell;
        }
        out << (row == 3 ? " ]\n" : "\n");
    }
}

std::string planeRule(std::uint8_t plane, ClipDepthRange range) {
    const bool reversed = range == ClipDepthRange::ReversedZeroToW;
    switch (plane) {
        case kClipLeft:
            return "left   (x ≥ −w, d = w + x)";
        case kClipRight:
            return "right  (x ≤ w,  d = w − x)";
        case kClipBottom:
            return "bottom (y ≥ −w, d = w + y)";
        case kClipTop:
            return "top    (y ≤ w,  d = w − y)";
        case kClipNear:
            return reversed ? "near   (z ≤ w,  d = w − z; reversed Z)" : "near   (z ≥ −w, d = w + z)";
        case kClipFar:
            return reversed ? "far    (z ≥ 0,  d = z; reversed Z)" : "far    (z ≤ w,  d = w − z)";
        case kClipW:
            return "w      (w ≥ 1e−9, in front of the eye)";
        default:
            return "?";
    }
}

std::string compareText(CompareOp op) {
    switch (op) {
        case CompareOp::Never:
            return "never";
        case CompareOp::Less:
            return "<";
        case CompareOp::Equal:
            return "=";
        case CompareOp::LessEqual:
            return "≤";
        case CompareOp::Greater:
            return ">";
        case CompareOp::NotEqual:
            return "≠";
        case CompareOp::GreaterEqual:
            return "≥";
        case CompareOp::Always:
            return "always";
    }
    return "?";
}

// The names of a draw's varyings: its user shader's or its surface shader's (shaders.h), when the draw is one
// of the scene's and the count is the shader's; else numbered.
std::vector<std::string> varyingNames(const PreparedScene* prepared, std::uint32_t draw, int count) {
    std::vector<std::string> names;
    if (prepared && draw < prepared->draws.size()) {
        // A shader of one's own names its varyings itself (kVaryings: one name per float).
        if (const ShaderModule* module = prepared->draws[draw].userShader.module)
            if (static_cast<int>(module->varyingNames.size()) == count)
                return {module->varyingNames.begin(), module->varyingNames.end()};
        const std::span<const std::string_view> known = varyingNamesOf(prepared->draws[draw].frequency);
        if (static_cast<int>(known.size()) == count) return {known.begin(), known.end()};
    }
    for (int k = 0; k < count; ++k)
        names.push_back("varying " + std::to_string(k));
    return names;
}

// Flat shading's face normal, as renderer.h's flatFaceNormal made it for every corner of the triangle.
std::string faceNormalText(const TriangleTrace& t) {
    std::array<MeshVertex, 3> v;
    for (int k = 0; k < 3; ++k)
        v[k] = {t.objectPositions[k], t.objectNormals[k], vec2(0.0f)};
    FaceNormalRecord r;
    flatFaceNormal(v[0], v[1], v[2], &r);
    std::ostringstream out;
    out << "\nFlat shading: every corner carries the face normal, from two edges:\n"
        << "  v1 − v0 = " << vectorText(v[1].position - v[0].position)
        << "\n  v2 − v0 = " << vectorText(v[2].position - v[0].position) << "\n"
        << "  (v1 − v0) × (v2 − v0) = " << vectorText(r.cross) << "\n";
    if (r.turned)
        out << "  it points against the model's vertex normals, so it is turned: " << vectorText(-r.cross)
            << "\n";
    if (r.fallback)
        out << "  it has no length: the corners' normals' sum, normalised, instead = " << vectorText(r.normal)
            << "\n";
    else
        out << "  |(v1 − v0) × (v2 − v0)| = " << number(r.length) << " (twice the triangle's area)\n"
            << "  n = " << (r.turned ? "−" : "") << "(v1 − v0) × (v2 − v0) / " << number(r.length) << " = "
            << vectorText(r.normal) << "\n";
    return out.str();
}

// The model file of a draw: the object whose parts gave it (renderer.cpp's addDraws makes one draw per
// object and part with triangles, in order).
const ObjectSpec* objectOfDraw(const PreparedScene& prepared, std::uint32_t draw) {
    if (!prepared.assets) return nullptr;
    std::uint32_t k = 0;
    for (const ObjectSpec& object : prepared.scene.objects) {
        for (const MeshPart& part : prepared.assets->model(object.model).parts)
            if (part.indexCount != 0 && k++ == draw) return &object;
    }
    return nullptr;
}

std::string weightName(VertexNormals w) {
    switch (w) {
        case VertexNormals::PolygonArea:
            return "its polygon's vector area ×2 (the sum of its fan triangles' cross\n  products)";
        case VertexNormals::TriangleArea:
            return "the cross products (twice the areas) of its fan triangles that hold\n  the vertex";
        case VertexNormals::Angle:
            return "its unit normal n̂ times its interior angle θ at the vertex (|w| = θ,\n  in radians)";
    }
    return "?";
}

// What the step mode asks of a model read again (loadObj with a VertexNormalTrace): how its computed
// normals were made, or its vertices as the file gives them.
enum class ModelRecord { Normals, FileCorners };

// The record of a model read again: for its computed normals, of every position for a model of up to
// kEveryPosition triangles (else of the triangle's corners); for the file's values, of every vertex.
// Whole records are kept for the next triangles of the same models (the web page's walks ask for
// many). None when the file cannot be read again.
std::shared_ptr<const VertexNormalTrace> modelRecordOf(const std::filesystem::path& model,
                                                       const ObjOptions& options, const Mesh& mesh,
                                                       const TriangleTrace& t, ModelRecord what) {
    constexpr std::size_t kEveryPosition = 200000, kKept = 8;
    struct Kept {
        std::filesystem::path model;
        ObjOptions options;
        std::filesystem::file_time_type time;
        ModelRecord what;
        std::shared_ptr<const VertexNormalTrace> trace;
    };
    static std::mutex mutex;
    static std::vector<Kept> kept;  // the most recently used last
    const bool whole = what == ModelRecord::FileCorners || mesh.stats.trianglesKept <= kEveryPosition;
    std::error_code unknown;  // then no time: compared as such
    const std::filesystem::file_time_type time = std::filesystem::last_write_time(model, unknown);
    if (whole) {
        const std::lock_guard lock(mutex);
        for (auto it = kept.begin(); it != kept.end(); ++it)
            if (it->model == model && it->options == options && it->time == time && it->what == what) {
                std::rotate(it, it + 1, kept.end());
                return kept.back().trace;
            }
    }
    auto trace = std::make_shared<VertexNormalTrace>();
    if (what == ModelRecord::FileCorners)
        trace->fileCornersOfAll = true;
    else if (whole)
        trace->all = true;
    else
        trace->positions.assign(t.objectPositions.begin(), t.objectPositions.end());
    try {
        loadObj(model, options, trace.get());
    } catch (const std::exception&) {
        return nullptr;  // the file changed since: nothing to show
    }
    if (whole) {
        const std::lock_guard lock(mutex);
        if (kept.size() == kKept) kept.erase(kept.begin());
        kept.push_back({model, options, time, what, trace});
    }
    return trace;
}

// The record of the triangle's model (modelRecordOf), when its draw is an object's.
std::shared_ptr<const VertexNormalTrace> modelRecordOf(const PreparedScene& prepared, const TriangleTrace& t,
                                                       ModelRecord what) {
    const ObjectSpec* object = objectOfDraw(prepared, t.ref.draw);
    if (!object) return nullptr;
    return modelRecordOf(object->model, prepared.assets->options.obj, prepared.assets->model(object->model),
                         t, what);
}

// How the computed normals of the triangle's corners were made: the model read again with
// loadObj's VertexNormalTrace (the very sums the import computes), the groups whose normal is the
// vertex's. Nothing for corners whose normals the file gives.
std::string vertexNormalText(const PreparedScene& prepared, const TriangleTrace& t) {
    const ObjectSpec* object = objectOfDraw(prepared, t.ref.draw);
    if (!object || prepared.assets->model(object->model).stats.normalsComputed == 0) return "";
    const std::shared_ptr<const VertexNormalTrace> traced = modelRecordOf(prepared, t, ModelRecord::Normals);
    if (!traced) return "";
    // The groups at the corners' positions.
    VertexNormalTrace trace;
    trace.weighting = traced->weighting;
    trace.creaseCosine = traced->creaseCosine;
    trace.smoothAll = traced->smoothAll;
    for (const VertexNormalTrace::Group& g : traced->groups)
        if (std::find(t.objectPositions.begin(), t.objectPositions.end(), g.position) !=
            t.objectPositions.end())
            trace.groups.push_back(g);
    constexpr std::size_t kShown = 6;
    std::ostringstream out;
    out << "\nThe model gives no normals here: Facet computed them when it read the file,\n"
           "n = normalize(Σ w_f) over the faces f at the vertex's position (lecture deck A:\n"
           "a vertex normal averaged from its faces).\nw_f, by lighting.normals ("
        << nameOf(trace.weighting) << "):\n  " << weightName(trace.weighting) << ".\n";
    if (trace.smoothAll)
        out << "Crease angle 180°: every face at the position is summed.\n";
    else
        out << "Crease angle: a face counts when n̂_f·n̂_own ≥ cos(angle) = " << number(trace.creaseCosine)
            << ",\nn̂_own the unit normal of the corner's own face.\n";
    // The groups of each corner (its position and normal), seen from the triangle's own face: the
    // face all three corners' groups are seen from (else the first group of the corner).
    const auto corner = [&](int k, const VertexNormalTrace::Group& g) {
        return g.position == t.objectPositions[k] && g.normal == t.objectNormals[k];
    };
    std::optional<std::uint32_t> ownFace;
    for (const VertexNormalTrace::Group& g : trace.groups) {
        if (!corner(0, g)) continue;
        const auto seen = [&](int k) {
            return std::any_of(trace.groups.begin(), trace.groups.end(),
                               [&](const auto& h) { return corner(k, h) && h.ownFace == g.ownFace; });
        };
        if (seen(1) && seen(2)) {
            ownFace = g.ownFace;
            break;
        }
    }
    for (int k = 0; k < 3; ++k) {
        auto match = std::find_if(trace.groups.begin(), trace.groups.end(), [&](const auto& g) {
            return corner(k, g) && (!ownFace || g.ownFace == *ownFace);
        });
        if (match == trace.groups.end())
            match = std::find_if(trace.groups.begin(), trace.groups.end(),
                                 [&](const auto& g) { return corner(k, g); });
        out << "\n  v" << k;
        if (match == trace.groups.end()) {
            out << ": the model file gives its normal " << vectorText(t.objectNormals[k]) << "\n";
            continue;
        }
        const VertexNormalTrace::Group& g = *match;
        out << ": " << g.faces.size() << " face" << (g.faces.size() == 1 ? "" : "s")
            << " at its position, own face " << g.ownFace << (g.clustered ? " (greedy cluster)" : "") << "\n";
        std::size_t shown = 0;
        for (const VertexNormalTrace::Face& f : g.faces) {
            if (shown++ == kShown) {
                out << "    and " << g.faces.size() - kShown << " more\n";
                break;
            }
            out << "    face " << f.face << ": n̂ = " << vectorText(vec3(f.unit))
                << "\n      w = " << vectorText(vec3(f.weight))
                << ", |w| = " << number(glm::length(f.weight));
            if (trace.smoothAll)
                out << "\n";
            else
                out << "\n      n̂·n̂_own = " << number(f.cosine)
                    << (f.smoothed ? " ≥ cos: summed\n" : " < cos: left out (crease)\n");
        }
        const double length = glm::length(g.sum);
        out << "    Σ w = " << vectorText(vec3(g.sum)) << ", |Σ w| = " << number(length) << "\n"
            << "    n = Σ w / |Σ w| = " << vectorText(g.normal) << "\n";
    }
    return out.str();
}

// The file's vertex of corner k of the triangle: the recorded corner at its position with its
// texture coordinates, and its normal where the file gives one (flat shading's corners carry the face
// normal instead: any normal then); none when the record has none.
const VertexNormalTrace::FileCorner* fileCornerOf(const VertexNormalTrace& trace, const vec3& position,
                                                  const vec2& uv, const vec3& normal, bool anyNormal) {
    const VertexNormalTrace::FileCorner* found = nullptr;
    for (const VertexNormalTrace::FileCorner& c : trace.fileCorners) {
        if (c.position != position || c.uv != uv) continue;
        if (anyNormal || (c.normalIndex >= 0 && c.unitNormal == normal)) return &c;
        if (!found && (c.normalIndex < 0 || c.unitNormal == vec3(0.0f))) found = &c;  // a computed normal
    }
    return found;
}

Screen inputScreen(const PreparedScene& prepared, const TriangleTrace& t) {
    std::ostringstream out;
    const bool flat = t.ref.draw < prepared.draws.size() &&
                      prepared.draws[t.ref.draw].frequency == ShadingFrequency::Flat &&
                      prepared.scene.lighting.preset != LightingPreset::GL;
    out << wrapText("Triangle " + std::to_string(t.ref.number) + " of the scene" +
                        drawPlace(prepared, t.ref) + ": three corners of its draw's vertex array, numbers " +
                        std::to_string(t.indices[0]) + ", " + std::to_string(t.indices[1]) + ", " +
                        std::to_string(t.indices[2]) + ".",
                    kScreenColumns, 0);
    // The file's values: positions, texture coordinates and normals as written (numbered as the
    // file's v, vt and vn lines, from 1).
    const std::shared_ptr<const VertexNormalTrace> file =
        modelRecordOf(prepared, t, ModelRecord::FileCorners);
    std::array<const VertexNormalTrace::FileCorner*, 3> corners{};
    bool fromFile = file != nullptr;
    for (int k = 0; k < 3 && fromFile; ++k) {
        const PreparedDraw& draw = prepared.draws[t.ref.draw];
        const vec2 uv = draw.vertices[t.indices[k]].uv;
        corners[k] = fileCornerOf(*file, t.objectPositions[k], uv, t.objectNormals[k], flat);
        fromFile = corners[k] != nullptr;
    }
    if (fromFile) {
        out << "As the model file gives them (its v, vt and vn lines, counted from 1):\n";
        for (int k = 0; k < 3; ++k) {
            const VertexNormalTrace::FileCorner& c = *corners[k];
            out << "  v" << k << "  position  " << vectorText(c.position) << "  (v " << c.positionIndex + 1
                << ")\n";
            if (c.texcoordIndex >= 0)
                out << "      texture   " << vectorText(c.uv) << "  (vt " << c.texcoordIndex + 1 << ")\n";
            else
                out << "      texture   none: (0, 0) is used\n";
            if (c.normalIndex >= 0) {
                const float length = glm::length(c.normal);
                out << "      normal    " << vectorText(c.normal) << "  (vn " << c.normalIndex + 1 << ")\n";
                if (c.unitNormal == vec3(0.0f))
                    out << "      length 0: no usable normal, one is computed\n";
                else if (vectorText(c.unitNormal) != vectorText(c.normal))
                    out << "      length " << number(length) << ", normalised: " << vectorText(c.unitNormal)
                        << "\n";
            } else {
                out << "      normal    none: one is computed\n";
            }
        }
        out << "\n";
    }
    out << (fromFile ? "The vertices the pipeline draws (object space, normals of length 1):\n"
                     : "In object space, as the pipeline draws them (normals of length 1):\n");
    for (int k = 0; k < 3; ++k)
        out << "  v" << k << "  position " << vectorText(t.objectPositions[k]) << "\n      normal   "
            << vectorText(t.objectNormals[k]) << (flat ? "  (the face normal)" : "") << "\n";
    if (flat)
        out << faceNormalText(t);
    else
        out << vertexNormalText(prepared, t);
    out << "\nThe vertex shader runs once per vertex; the triangle is then assembled from\n"
           "its three outputs (primitive assembly) in this order, v0 v1 v2.\n";
    return {"input", "Input: triangle " + std::to_string(t.ref.number) + " and its vertices", out.str()};
}

// The columns a UTF-8 text takes: its code points.
std::size_t textColumns(const std::string& s) {
    return static_cast<std::size_t>(std::count_if(
        s.begin(), s.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xc0) != 0x80; }));
}

void matrixLines(std::ostringstream& out, const std::string& name, const glm::dmat3& m) {
    for (int row = 0; row < 3; ++row) {
        out << (row == 0 ? "  " + name + " = [" : std::string(textColumns(name) + 5, ' ') + " ");
        for (int column = 0; column < 3; ++column) {
            char cell[16];
            std::snprintf(cell, sizeof cell, " %12.6g", m[column][row] == 0.0 ? 0.0 : m[column][row]);
            out << cell;
        }
        out << (row == 2 ? " ]\n" : "\n");
    }
}

// The normals through the vertex shader: the normal matrix (renderer.h's normalMatrix, as placeDraw
// made the draw's uniform) and each corner's n_eye = M_n·n_obj, computed by the surface shader's vertex().
// `faceNormals`: flat shading gave the corners the face normal (not under the gl preset).
void normalLines(std::ostringstream& out, const PreparedDraw& draw, const TriangleTrace& t,
                 bool faceNormals) {
    const NormalMatrix n = normalMatrix(draw.viewFromObjectExact);
    out << "\nNormals: n_eye = M_n·n_obj, with the normal matrix M_n = ((V·M)⁻¹)ᵀ of the\n"
           "upper-left 3×3 of V·M (lecture deck A's vertex shader calls it N): it keeps\n"
           "normals perpendicular to the surface when M scales unevenly.\n";
    matrixLines(out, "((V·M)⁻¹)ᵀ", n.inverseTranspose);
    const double scale = std::cbrt(std::abs(n.determinant));
    out << "  det = " << number(n.determinant) << ", M_n = ((V·M)⁻¹)ᵀ / ∛|det| = ((V·M)⁻¹)ᵀ / "
        << number(scale)
        << "\n  (Facet scales M_n to determinant 1: the lighting normalises n_eye, so its\n"
           "  length is free), in float:\n";
    matrixLines(out, "M_n", glm::dmat3(draw.uniforms.normalFromObject));
    const bool perPixel = draw.frequency == ShadingFrequency::Phong;
    for (int k = 0; k < 3; ++k) {
        const MeshVertex vertex{t.objectPositions[k], t.objectNormals[k], vec2(0.0f)};
        const vec3 eye = PerPixelSurface::vertex(vertex, draw.uniforms).varyings.normal;
        const float length = glm::length(eye);
        out << "  v" << k << "  n_obj = " << vectorText(t.objectNormals[k]) << "\n"
            << "      n_eye = M_n·n_obj = " << vectorText(eye) << "\n"
            << "      |n_eye| = " << number(length);
        if (length > 0.0f) out << ", n_eye/|n_eye| = " << vectorText(eye / length);
        out << "\n";
    }
    out << (perPixel ? "Phong shading interpolates n_eye and normalises it at the pixel (lighting).\n"
                     : "The lighting at each vertex uses n_eye/|n_eye| (lighting).\n");
    if (draw.frequency == ShadingFrequency::Flat && faceNormals)
        out << "Flat shading: n_obj is the face normal at every corner (see the input screen).\n";
}

Screen transformScreen(const PreparedScene& prepared, const TriangleTrace& t) {
    std::ostringstream out;
    out << "The vertex shader maps each corner from object space to clip space:\n"
           "  world = M·object   M: the object's placement in the scene\n"
           "  eye   = V·world    V: the camera (eye at the origin, looking down −z)\n"
           "  clip  = P·eye      P: the perspective projection (w = −z_eye)\n\n";
    matrixLines(out, "M", t.worldFromObject);
    matrixLines(out, "V", t.viewFromWorld);
    matrixLines(out, "P", t.clipFromView);
    out << "\n";
    for (int k = 0; k < 3; ++k) {
        const vec4 world = t.worldFromObject * vec4(t.objectPositions[k], 1.0f);
        const vec4 eye = t.viewFromWorld * world;
        out << "  v" << k << "  object " << vectorText(t.objectPositions[k]) << "\n"
            << "      world  " << vectorText(vec3(world)) << "\n"
            << "      eye    " << vectorText(vec3(eye)) << "\n"
            << "      clip   " << vectorText(t.clipPositions[k]) << "\n";
    }
    out << "\n(clip is the vertex shader's gl_Position as the pipeline computed it.)\n";
    if (t.ref.draw < prepared.draws.size())
        normalLines(out, prepared.draws[t.ref.draw], t, prepared.scene.lighting.preset != LightingPreset::GL);
    return {"transform", "Vertex shader: object → world → eye → clip space", out.str()};
}

// A shader of one's own: its vertex part's outputs at the three corners, as the pipeline received them.
Screen userVertexScreen(const PreparedScene& prepared, const TriangleTrace& t) {
    const UserShader& shader = prepared.draws[t.ref.draw].userShader;
    std::ostringstream out;
    out << wrapText("The vertex part of your shader " + std::string(shader.module->name) + " (" +
                        shader.label +
                        ") runs once per corner: from the vertex (position, normal, texture coordinates) "
                        "and the uniforms it makes the clip position gl_Position and its varyings, the "
                        "values the triangle interpolates for the fragment part.",
                    80, 0)
        << "\n";
    const std::vector<std::string> names(shader.module->varyingNames.begin(),
                                         shader.module->varyingNames.end());
    for (int k = 0; k < 3; ++k) {
        out << "  v" << k << "  clip   " << vectorText(t.clipPositions[k]) << "\n";
        const std::vector<float>& v = t.vertexVaryings[static_cast<std::size_t>(k)];
        std::string line = "     ";
        for (std::size_t i = 0; i < v.size(); ++i) {
            std::string item = " ";  // appended piece by piece: GCC 12 warns falsely on a sum (-Wrestrict)
            item += i < names.size() ? names[i] : "varying " + std::to_string(i);
            item += " = ";
            item += number(v[i]);
            if (!std::isfinite(v[i])) item += " (!)";
            if (line.size() + item.size() > 78) {
                out << line << "\n";
                line.assign(5, ' ');
            }
            line += item;
        }
        if (!v.empty()) out << line << "\n";
    }
    bool nonFinite = false;
    for (const std::vector<float>& v : t.vertexVaryings)
        for (float x : v)
            nonFinite = nonFinite || !std::isfinite(x);
    if (nonFinite)
        out << "\n(!) not a finite number: NaN (0/0, normalize of a zero vector?) or infinite (a\n"
               "    division by zero?); interpolation spreads it over the whole triangle.\n";
    out << "\n(As the pipeline received them from the module; the clip positions go on to\nclipping.)\n";
    return {"transform", "Vertex shader: " + std::string(shader.module->name) + "'s vertex part", out.str()};
}

Screen clipScreen(const TriangleTrace& t) {
    std::ostringstream out;
    const ClipDepthRange range = clipDepthRange(t.state.depth.format);
    if (range == ClipDepthRange::ReversedZeroToW)
        out << "A clip-space point is inside the view volume when −w ≤ x, y ≤ w and 0 ≤ z ≤ w\n"
               "(reversed Z: the projection puts the near plane at z = w, the far one at z = 0).\n";
    else
        out << "A clip-space point is inside the view volume when −w ≤ x, y, z ≤ w.\n";
    out << "Outcode: the planes a vertex lies outside of.\n\n";
    std::uint8_t orCode = 0, andCode = 0xff;
    for (int k = 0; k < 3; ++k) {
        const vec4& p = t.clipPositions[k];
        out << oneLineOrTwo("  v" + std::to_string(k) + " " + vectorText(p) + ":",
                            t.outcodes[k] == 0 ? "inside" : "outside " + clipPlaneNames(t.outcodes[k]), 5);
        orCode |= t.outcodes[k];
        andCode &= t.outcodes[k];
    }
    out << "\n";
    if (t.rejected == TriangleFate::NonFinite) {
        out << "A coordinate is not a finite number: the triangle is dropped.\n";
        return {"clip", "Clipping: dropped (not a finite number)", out.str()};
    }
    if (t.rejected == TriangleFate::OutsideFrustum) {
        out << wrapText("All three vertices lie outside the same plane (" +
                            clipPlaneNames(andCode & kAllClipPlanes) +
                            "): the whole triangle is outside the view and is rejected without clipping.",
                        kScreenColumns, 0);
        return {"clip", "Clipping: rejected, wholly outside the view", out.str()};
    }
    if (orCode == 0) {
        out << "All three vertices are inside every plane: nothing to clip.\n";
        return {"clip", "Clipping: inside the view, nothing to clip", out.str()};
    }
    // The planes that cut (the recorded steps: the clipper skips a plane no vertex of the polygon
    // left by the earlier planes is outside of), and the outcodes' other planes.
    const std::uint8_t named = orCode & kAllClipPlanes;
    std::uint8_t cut = 0;
    for (const ClipStep& step : t.clipSteps)
        cut |= step.plane;
    // A plane after the one that left nothing is never tried.
    std::uint8_t tried = named;
    if (t.rejected == TriangleFate::ClippedAway && !t.clipSteps.empty())
        tried &= static_cast<std::uint8_t>((t.clipSteps.back().plane << 1) - 1);
    const std::uint8_t uncut = tried & ~cut, untried = named & ~tried;
    out << wrapText("The vertices lie outside " + clipPlaneNames(named) +
                        ". The polygon is clipped plane by plane (Sutherland-Hodgman), in the order "
                        "left, right, bottom, top, near, far, w, in homogeneous coordinates before "
                        "any division.",
                    kScreenColumns, 0)
        << wrapText("Planes that cut it: " + clipPlaneNames(cut) + " (a section each below).", kScreenColumns,
                    2);
    if (uncut)
        out << wrapText("Outside but not cut after the earlier planes: " + clipPlaneNames(uncut) +
                            " (a vertex lies outside it, but what the earlier cuts left lies "
                            "inside it).",
                        kScreenColumns, 2);
    if (untried)
        out << wrapText("Not tried: " + clipPlaneNames(untried) + " (nothing was left to clip).",
                        kScreenColumns, 2);
    out << "A new vertex lies where an edge crosses the plane: P = P_in + t·(P_out − P_in),\n"
           "t = d_in / (d_in − d_out), d the signed distance to the plane (≥ 0 inside).\n"
           "Each section numbers the polygon before its plane p0, p1, …; before the first\n"
           "cut they are v0, v1, v2.\n";
    // Huge triangles only (clip.h, clipEdgePoint): where the line's depth would be lost to rounding.
    const DepthFromW& fromW = t.state.depth.fromW;
    bool anyDepthFromW = false;
    for (const ClipStep& step : t.clipSteps)
        for (const ClipStep::NewVertex& made : step.made)
            anyDepthFromW = anyDepthFromW || made.depthFromW;
    if (anyDepthFromW)
        out << wrapText(
            "Marked \"z from w\": where rounding would lose the depth on the line (a huge "
            "triangle), a new vertex's z is set from its w, as the camera's projection ties "
            "them for every point: z = a·w + b, a = " +
                number(fromW.slope) + ", b = " + number(fromW.offset) + ".",
            kScreenColumns, 0);
    std::vector<vec4> polygon(t.clipPositions.begin(), t.clipPositions.end());
    for (const ClipStep& step : t.clipSteps) {
        out << "\nPlane " << planeRule(step.plane, range) << ":\n";
        for (std::size_t i = 0; i < polygon.size(); ++i)
            out << "  p" << i << " d = " << number(planeDistance(polygon[i], step.plane, range)) << "\n";
        for (const ClipStep::NewVertex& made : step.made) {
            const float dIn = planeDistance(polygon[made.from], step.plane, range);
            const float dOut = planeDistance(polygon[made.to], step.plane, range);
            out << "  new vertex on p" << made.from << "→p" << made.to << ": t = " << number(dIn) << " / ("
                << number(dIn) << " − " << bracketedIfNegative(dOut) << ") = " << number(made.t) << "\n"
                << "    P = " << vectorText(made.position) << (made.depthFromW ? ", z from w" : "") << "\n";
        }
        polygon = step.polygon;
        out << "  left: " << polygon.size() << " vertices\n";
        for (std::size_t i = 0; i < polygon.size(); ++i)
            out << "    p" << i << " " << vectorText(polygon[i]) << "\n";
    }
    if (t.rejected == TriangleFate::ClippedAway) {
        out << "\nNothing is left: the triangle is clipped away.\n";
        return {"clip", "Clipping: clipped away", out.str()};
    }
    out << "\nThe polygon left, p0.." << polygon.size() - 1 << ", is drawn as a fan of " << polygon.size() - 2
        << " triangle" << (polygon.size() > 3 ? "s" : "") << " around p0.\n";
    return {"clip",
            "Clipping: " + clipPlaneNames(cut) + " cut" + (cut & (cut - 1) ? "" : "s") + " the triangle",
            out.str()};
}

Screen windowScreen(const TriangleTrace& t) {
    std::ostringstream out;
    const Viewport& vp = t.state.viewport;
    out << "Perspective divide: NDC = (x/w, y/w, z/w). Viewport: x0 = " << vp.x << ", y0 = " << vp.y
        << ",\nW = " << vp.width << ", H = " << vp.height << ", depth range [d_near, d_far] = ["
        << number(vp.minDepth) << ", " << number(vp.maxDepth) << "]:\n"
        << "  x_w = x0 + (x_ndc + 1)/2·W   y_w = y0 + (1 − y_ndc)/2·H   (y grows down)\n"
        << (clipDepthRange(t.state.depth.format) == ClipDepthRange::ReversedZeroToW
                ? "  z_w = d_near + z_ndc·(d_far − d_near)\n  (reversed Z: z_ndc is 1 at the near plane, 0 "
                  "at the far "
                  "one)\n"
                : "  z_w = d_near + (z_ndc + 1)/2·(d_far − d_near)\n")
        << "Window x and y are then snapped to the fixed-point grid of 1/" << kFixedOne << " pixel\n"
        << "(" << t.state.raster.subpixelBits << " subpixel bits): the integers below are in 1/" << kFixedOne
        << " pixels.\n";
    if (t.pieces.empty()) {
        out << "\nThe triangle never reached this stage (see clipping).\n";
        return {"window", "Divide and viewport: not reached", out.str()};
    }
    if (t.clipSteps.empty()) {
        out << "\n";
        for (int k = 0; k < 3; ++k) {
            const vec4& c = t.clipPositions[k];
            const WindowVertex& w = t.pieces[0].vertices[k];
            out << "  v" << k << " NDC " << vectorText(vec3(c) / c.w) << "\n"
                << "     window " << vectorText(w.window) << "  z_w " << number(w.z) << "  1/w "
                << number(w.invW) << "\n"
                << "     snapped x " << fixedText(w.xFixed) << ", y " << fixedText(w.yFixed) << "\n";
        }
    } else {
        for (std::size_t p = 0; p < t.pieces.size(); ++p) {
            out << "\nFan piece " << p << ":\n";
            for (int k = 0; k < 3; ++k) {
                const WindowVertex& w = t.pieces[p].vertices[k];
                out << "  v" << k << " window " << vectorText(w.window) << "  z_w " << number(w.z) << "  1/w "
                    << number(w.invW) << "\n"
                    << "     snapped x " << fixedText(w.xFixed) << ", y " << fixedText(w.yFixed) << "\n";
            }
        }
    }
    return {"window", "Divide and viewport: window coordinates, snapped", out.str()};
}

Screen setupScreen(const TriangleTrace& t) {
    std::ostringstream out;
    if (t.pieces.empty()) {
        out << "The triangle never reached setup (see clipping).\n";
        return {"setup", "Setup: not reached", out.str()};
    }
    const bool ccwFront = t.state.raster.frontFace == FrontFace::CounterClockwise;
    out << "Twice the signed area, from the snapped vertices (window y grows down, so a\n"
           "triangle counter-clockwise on screen has 2A < 0):\n"
           "  2A = (x1 − x0)(y2 − y0) − (x2 − x0)(y1 − y0)\n"
        << "Front faces are " << (ccwFront ? "counter-clockwise" : "clockwise")
        << "; culling: " << nameOf(t.state.raster.cull) << ".\n";
    for (std::size_t p = 0; p < t.pieces.size(); ++p) {
        const WindowPiece& piece = t.pieces[p];
        if (t.pieces.size() > 1) out << "\nFan piece " << p << ":";
        out << "\n  2A = " << piece.signedDoubleArea << " (1/" << kFixedOne
            << " px)² = " << number(double(piece.signedDoubleArea) / double(kFixedOne * kFixedOne))
            << " px²\n";
        switch (piece.fate) {
            case TriangleFate::ZeroArea:
                out << "  Zero area: its vertices lie on one line once snapped; nothing to draw.\n";
                continue;
            case TriangleFate::MissesSamples:
                out << "  Its bounding box holds no pixel centre: it covers no pixel.\n";
                continue;
            case TriangleFate::Culled:
                out << "  " << (piece.setup.frontFacing ? "Front" : "Back")
                    << "-facing, and that side is culled: the triangle is dropped.\n";
                if (piece.setup.boxEmpty()) {
                    out << "  (Kept, it would have covered no pixel: its box holds no pixel centre.)\n";
                    continue;
                }
                out << "  (Below: the setup it would have had.)\n";
                break;
            default:
                out << "  " << (piece.setup.frontFacing ? "Front" : "Back") << "-facing: kept.\n";
        }
        const TriangleSetup& s = piece.setup;
        out << "  Edge functions E_i(x, y) = a·x + b·y + c, ≥ 0 inside (x, y in 1/" << kFixedOne << " px).\n"
            << (piece.signedDoubleArea < 0
                    ? "  2A < 0: setup exchanges v1 and v2 to make it positive, 2A = " +
                          std::to_string(s.doubleArea) + ";\n  edge i is opposite the i-th of v0, v2, v1:\n"
                    : "  Edge i is opposite vertex i:\n");
        for (int i = 0; i < 3; ++i) {
            const EdgeFunction& e = s.edges[i];
            out << "    E" << i << " = " << e.a << "·x " << signedTerm(e.b) << "·y " << signedTerm(e.c)
                << "\n      "
                << (e.bias() == 0 ? "top or left edge: a centre exactly on it is inside"
                                  : "not top-left: bias −1, a centre exactly on it is outside")
                << "\n";
        }
        out << "  Bounding box: pixels x " << s.minX << ".." << s.maxX << ", y " << s.minY << ".." << s.maxY
            << " (in the viewport)\n";
        if (!piece.tiles.empty()) {
            out << "  Binned to " << piece.tiles.size() << " tile" << (piece.tiles.size() > 1 ? "s" : "")
                << " of " << t.tileSize << "×" << t.tileSize << " pixels (column, row):";
            int shown = 0;
            for (int tile : piece.tiles) {
                if (shown++ == 12) {
                    out << " …";
                    break;
                }
                const int columns = std::max(t.gridColumns, 1);
                out << (shown % 6 == 1 ? "\n   " : "") << " (" << tile % columns << ", " << tile / columns
                    << ")";
            }
            out << "\n";
        }
    }
    const bool culled = t.culled;
    return {"setup", culled ? "Setup: culled for its facing" : "Setup: area, facing, edge functions, tiles",
            out.str()};
}

Screen rasterScreen(const TriangleTrace& t) {
    std::ostringstream out;
    const int left = t.focusX - t.rasterWidth / 2, top = t.focusY - t.rasterHeight / 2;
    out << "Pixels around (" << t.focusX << ", " << t.focusY << "), tested at their centres (x + ½, y + ½):\n"
        << "  # covered   + covered, on a top-left edge   : on another edge, not covered\n"
        << "  . inside the bounding box, not covered   (blank: outside the box)\n"
        << "  the traced pixel is in brackets [ ]" << (t.culled ? "; culled: what it would cover" : "")
        << "\n\n";
    out << "        x " << left << ".." << left + t.rasterWidth - 1 << "\n";
    for (int row = 0; row < t.rasterHeight; ++row) {
        char label[16];
        std::snprintf(label, sizeof label, "%6d ", top + row);
        // Two columns a pixel: the traced one between brackets, which take the spaces beside it.
        std::string line = label;
        for (int column = 0; column < t.rasterWidth; ++column) {
            const char c = t.raster[static_cast<std::size_t>(row) * t.rasterWidth + column];
            const bool focus = left + column == t.focusX && top + row == t.focusY;
            const bool afterFocus = left + column - 1 == t.focusX && top + row == t.focusY;
            line += focus ? '[' : afterFocus ? ']' : ' ';
            line += c;
        }
        if (left + t.rasterWidth - 1 == t.focusX && top + row == t.focusY) line += ']';
        out << line.substr(0, line.find_last_not_of(' ') + 1);
        out << "\n";
    }
    out << "\n";
    if (!t.focusCoverage) {
        out << "The pixel (" << t.focusX << ", " << t.focusY
            << ") is outside this triangle's bounding box.\n";
        return {"raster", "Rasterization: the pixel is outside the box", out.str()};
    }
    const CoverageEvent& e = *t.focusCoverage;
    out << "At the centre of (" << e.x << ", " << e.y << "):\n";
    for (int i = 0; i < 3; ++i) {
        const std::int64_t v = e.edgeValues[i];
        const bool topLeft = (e.topLeftEdges >> i) & 1;
        out << "  E" << i << " = " << v
            << (v > 0   ? "  > 0: inside"
                : v < 0 ? "  < 0: outside"
                        : "  = 0: exactly on the edge, ")
            << (v == 0 ? (topLeft ? "a top-left edge: inside" : "not top-left: outside") : "") << "\n";
    }
    std::string title;
    if (e.covered)
        title = t.culled ? "Rasterization: would cover the pixel (culled)"
                         : "Rasterization: the pixel is covered";
    else if ((e.excludingEdges & ~e.tiesExcluded()) == 0)
        title = "Rasterization: a tie lost to the top-left rule";
    else
        title = "Rasterization: the pixel is outside an edge";
    out << (e.covered ? "All three allow it: the pixel is covered.\n"
                      : "An edge excludes it: not covered.\n");
    return {"raster", title, out.str()};
}

std::string fateText(const TriangleAtPixel& e) {
    std::ostringstream out;
    switch (e.fate) {
        case PixelFate::NonFinite:
            return "dropped: a vertex is not a finite number";
        case PixelFate::OutsideFrustum:
            return "rejected: wholly outside the view volume";
        case PixelFate::ClippedAway:
            return "clipped away: nothing left inside the view volume";
        case PixelFate::ZeroArea:
            return "zero area once snapped: draws nothing";
        case PixelFate::MissesSamples:
            return "its box holds no pixel centre: draws nothing";
        case PixelFate::Culled:
            out << "culled: " << (e.coverage ? "faces the culled side" : "its facing") << " ("
                << (e.coverage && e.coverage->covered ? "would cover it" : "would not cover it") << ")";
            return out.str();
        case PixelFate::OutsideEdge:
            if (e.coverage)
                for (int i = 0; i < 3; ++i)
                    if (((e.coverage->excludingEdges & ~e.coverage->tiesExcluded()) >> i) & 1) {
                        out << "outside edge " << i << " (E" << i << " = " << e.coverage->edgeValues[i]
                            << ")";
                        return out.str();
                    }
            return "outside an edge";
        case PixelFate::LostTie: {
            int edge = 0;
            if (e.coverage)
                for (int i = 0; i < 3; ++i)
                    if ((e.coverage->tiesExcluded() >> i) & 1) edge = i;
            out << "lost a tie: exactly on edge " << edge << " (E" << edge << " = 0), not top-left";
            if (e.tieOwner) out << "; " << triangleName(*e.tieOwner) << " owns the pixel";
            return out.str();
        }
        case PixelFate::DepthFailed:
            if (e.fragment)
                out << "depth test failed: " << number(e.fragment->depth) << " "
                    << compareText(e.depthCompare) << " " << number(e.fragment->depthBefore) << " is false";
            else
                out << "depth test failed";
            return out.str();
        case PixelFate::Discarded:
            return "discarded by the fragment shader";
        case PixelFate::Dropped:
            return "dropped: its tile's fragment lists were full";
        case PixelFate::Written:
        case PixelFate::Blended:
        case PixelFate::Stored:
            if (e.fragment)
                out << "depth " << number(e.fragment->depth)
                    << (e.depthCompare == CompareOp::Always
                            ? " (no depth test)"
                            : " " + compareText(e.depthCompare) + " " + number(e.fragment->depthBefore) +
                                  ": passed")
                    << ", ";
            out << (e.fate == PixelFate::Written   ? "written"
                    : e.fate == PixelFate::Blended ? "blended (" + std::string(nameOf(e.blend)) + ")"
                                                   : "stored in the pixel's fragment list");
            if (e.overwrittenBy) out << "; then overwritten by " << triangleName(*e.overwrittenBy);
            return out.str();
    }
    return "?";
}

}  // namespace

std::vector<Screen> triangleScreens(const PreparedScene& prepared, const TriangleTrace& triangle) {
    const bool user =
        triangle.ref.draw < prepared.draws.size() && prepared.draws[triangle.ref.draw].userShader.module;
    return {inputScreen(prepared, triangle),
            user ? userVertexScreen(prepared, triangle) : transformScreen(prepared, triangle),
            clipScreen(triangle),
            windowScreen(triangle),
            setupScreen(triangle),
            rasterScreen(triangle)};
}

std::string verdictOf(const PixelTrace& p) {
    if (p.triangles.empty())
        return "nothing drew here: no triangle's bounding box holds this pixel (background)";
    if (p.producer) {
        const TriangleAtPixel& e = p.triangles[*p.producer];
        if (p.resolve && p.resolve->fragments.size() > 0)
            return "a later stage changed it: the exact-transparency resolve composited " +
                   std::to_string(p.resolve->fragments.size()) + " fragments, the nearest from " +
                   triangleName(e.ref);
        if (e.fate == PixelFate::Blended)
            return "a later stage changed it: blending (" + std::string(nameOf(e.blend)) + ") mixed " +
                   triangleName(e.ref) + "'s colour with the colour behind it";
        return "the shader computed this colour: " + triangleName(e.ref) + "'s fragment, written";
    }
    std::map<PixelFate, int> counts;
    for (const TriangleAtPixel& e : p.triangles)
        ++counts[e.fate];
    std::string list;
    for (const auto& [fate, count] : counts)
        list += (list.empty() ? "" : ", ") + std::to_string(count) + " " + std::string(nameOf(fate));
    const bool anyCovered = std::any_of(p.triangles.begin(), p.triangles.end(), [](const TriangleAtPixel& e) {
        return e.fragment || (e.coverage && e.coverage->covered);
    });
    if (!anyCovered)
        return "nothing drew here: " + std::to_string(p.triangles.size()) +
               " triangles came near, none covers the centre (" + list + ")";
    return "everything was rejected (" + list + "): the pixel keeps the background";
}

Screen historyScreen(const PixelTrace& p, const PreparedScene* prepared) {
    std::ostringstream out;
    out << wrapText("Verdict: " + verdictOf(p), 80, 2) << "\n";
    out << "Every triangle whose bounding box holds pixel (" << p.x << ", " << p.y
        << "), in the order\nthey were drawn, and what ended it here:\n\n";
    if (p.triangles.empty()) out << "  (none)\n";
    for (std::size_t i = 0; i < p.triangles.size(); ++i) {
        const TriangleAtPixel& e = p.triangles[i];
        std::string line = (p.producer == i ? "* " : "  ") + triangleName(e.ref);
        if (e.transparent && e.sortPlace)
            line += " (transparent, drawn " + std::to_string(*e.sortPlace + 1) + ".)";
        line += ": " + fateText(e);
        out << wrapText(line, 80, 6);
    }
    if (p.producer) out << "\n* gave the pixel its final colour.\n";
    // Every fragment that got past the depth test, with what interpolation gave it.
    bool heading = false;
    for (const TriangleAtPixel& e : p.triangles) {
        if (!e.fragment ||
            (e.fate != PixelFate::Written && e.fate != PixelFate::Blended && e.fate != PixelFate::Stored))
            continue;
        const FragmentEvent& f = *e.fragment;
        if (!heading)
            out << "\nThe fragments that passed the depth test: λ in screen space (λ_i = E_i / 2A),\n"
                   "λ′ perspective-correct (λ′_i = λ_i·(1/w_i) / (1/w)), for v0, v1, v2 as drawn:\n";
        heading = true;
        out << "\n"
            << triangleName(e.ref) << ": z = " << number(f.depth) << ", 1/w = " << number(f.invW) << "\n";
        // In the corners' order as drawn (v0, v1, v2), as the interpolation screen names them: setup
        // may have exchanged the last two.
        const auto drawn = [&](vec3 bySetup) {
            return e.setupExchanged ? vec3(bySetup.x, bySetup.z, bySetup.y) : bySetup;
        };
        out << "  λ  = " << vectorText(drawn(f.barycentrics)) << "\n";
        if (e.cornerInvW)
            out << "  λ′ = " << vectorText(drawn(f.barycentrics * *e.cornerInvW / f.invW)) << "\n";
        else
            out << "  λ′ = λ: affine interpolation, no perspective correction\n";
        const std::vector<std::string> names = varyingNames(prepared, e.ref.draw, f.varyingCount);
        std::string line(1, ' ');
        for (int k = 0; k < f.varyingCount; ++k) {
            std::string item = " ";  // appended piece by piece: GCC 12 warns falsely on a sum (-Wrestrict)
            item += names[k];
            item += " = ";
            item += number(f.varyings[k]);
            if (line.size() + item.size() > 78) {
                out << line << "\n";
                line.assign(1, ' ');  // not = " ": GCC 12 warns falsely (-Wrestrict)
            }
            line += item;
        }
        if (f.varyingCount > 0) out << line << "\n";
        out << "  shader output " << vectorText(f.shaded);
        if (e.fate != PixelFate::Stored)
            out << "\n  colour before " << vectorText(f.colorBefore) << "\n  colour after  "
                << vectorText(f.colorAfter);
        out << "\n";
    }
    if (p.resolve) {
        out << "\nExact transparency: the pixel's fragment list, as stored (drawing order):\n";
        for (std::size_t k = 0; k < p.resolve->submitted.size(); ++k)
            out << "  " << k << ": " << triangleName(p.resolve->submitted[k]) << "\n";
        out << "sorted far to near and composited with the over operator:\n";
        for (const ResolvedFragment& f : p.resolve->fragments) {
            const std::string name = f.submission < p.resolve->submitted.size()
                                         ? triangleName(p.resolve->submitted[f.submission])
                                         : "fragment " + std::to_string(f.submission);
            out << oneLineOrTwo("  depth " + number(f.depth) + "  " + name,
                                " colour after " + vectorText(vec3(f.colorAfter)), 3);
        }
    }
    return {"history", "Pixel history of (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ")",
            out.str()};
}

namespace {

// The corners a fragment's weights belong to: v0, v1, v2 of the triangle as drawn, or for a clipped
// triangle the corners p0, p(k+1), p(k+2) of its fan piece k (the polygon the clip screen lists
// last), each with its varyings as the rasterizer received them.
struct WeightedCorners {
    std::array<std::string, 3> names;
    std::array<const std::vector<float>*, 3> varyings{};
    bool clipped = false;
};

WeightedCorners cornersOf(const TriangleTrace* triangle, const WindowPiece* piece) {
    WeightedCorners c;
    c.names = {"v0", "v1", "v2"};
    if (!triangle) return c;
    for (int k = 0; k < 3; ++k)
        c.varyings[k] = &triangle->vertexVaryings[static_cast<std::size_t>(k)];
    if (triangle->clipSteps.empty() || !piece) return c;
    c.clipped = true;
    const ClipStep& last = triangle->clipSteps.back();
    const auto k = static_cast<std::size_t>(piece - triangle->pieces.data());
    const std::size_t polygon[3] = {0, k + 1, k + 2};
    for (int i = 0; i < 3; ++i) {
        c.names[i] = "p" + std::to_string(polygon[i]);
        c.varyings[i] = polygon[i] < last.varyings.size() ? &last.varyings[polygon[i]] : nullptr;
    }
    return c;
}

// The interpolation screen: λ from the edge functions, depth and 1/w affine, the perspective-correct
// weights λ′, and every varying at the three corners with the value at the pixel, each named by the
// corners of the triangle as drawn (setup may have exchanged the last two to make its area positive).
std::string interpolationText(const PreparedScene* prepared, const TriangleAtPixel& entry,
                              const TriangleTrace* triangle, const WindowPiece* piece) {
    const FragmentEvent& f = *entry.fragment;
    const TriangleSetup* setup = piece ? &piece->setup : nullptr;
    const WeightedCorners corners = cornersOf(triangle, piece);
    const std::string& a = corners.names[0];
    const std::string& b = corners.names[1];
    const std::string& c = corners.names[2];
    // setupOf[i]: the setup's corner that is corner i as drawn.
    const bool exchanged = piece && piece->signedDoubleArea < 0;
    const int setupOf[3] = {0, exchanged ? 2 : 1, exchanged ? 1 : 2};
    std::ostringstream out;
    if (corners.clipped)
        out << "The pixel lies in fan piece " << piece - triangle->pieces.data()
            << " of the clipped polygon: its corners " << a << ", " << b << ", " << c
            << "\n(see clipping) take the places of v0, v1, v2 below.\n";
    out << "Barycentric coordinates from the edge functions: λ_i = E_i / 2A, E_i the edge\n"
           "function of the edge opposite corner i.\n";
    if (exchanged)
        out << "Setup exchanged " << b << " and " << c << " to make 2A positive: its edge 1 is opposite " << c
            << ",\nits edge 2 opposite " << b << ". λ1 is " << b << "'s weight, λ2 " << c << "'s.\n";
    const auto& E = entry.coverage->edgeValues;
    vec3 lambda(0.0f), invW(0.0f), z(0.0f);
    for (int i = 0; i < 3; ++i)
        lambda[i] = f.barycentrics[setupOf[i]];
    if (setup) {
        const vec3 bySetupInvW(setup->invW0, setup->invW0 + setup->dInvW1, setup->invW0 + setup->dInvW2);
        const vec3 bySetupZ(setup->z0, setup->z0 + setup->dz1, setup->z0 + setup->dz2);
        for (int i = 0; i < 3; ++i) {
            invW[i] = bySetupInvW[setupOf[i]];
            z[i] = bySetupZ[setupOf[i]];
            out << "  λ" << i << " = " << E[setupOf[i]] << " / " << setup->doubleArea << " = "
                << number(lambda[i])
                << (setupOf[i] != i ? "   (edge " + std::to_string(setupOf[i]) + ")" : "") << "\n";
        }
    } else {
        out << "  λ = " << vectorText(lambda) << "\n";
    }
    out << "\nDepth is affine in screen space: z = λ0·z0 + λ1·z1 + λ2·z2\n";
    if (setup)
        out << "  z0, z1, z2 (" << a << ", " << b << ", " << c << ") = " << number(z[0]) << ", "
            << number(z[1]) << ", " << number(z[2]) << "\n";
    out << "  z = " << number(f.depth) << "\n";
    out << "\n1/w is affine in screen space too: 1/w = λ0/w0 + λ1/w1 + λ2/w2\n";
    vec3 weights = lambda;  // λ′
    if (setup) {
        out << "  1/w0, 1/w1, 1/w2 (" << a << ", " << b << ", " << c << ") = " << number(invW[0]) << ", "
            << number(invW[1]) << ", " << number(invW[2]) << "\n  1/w = " << number(f.invW) << "\n";
        if (setup->perspective) {
            weights = lambda * invW / f.invW;
            out << "Perspective-correct weights: λ′_i = (λ_i/w_i) / (1/w)\n  λ′ = (";
            for (int i = 0; i < 3; ++i)
                out << number(weights[i]) << (i < 2 ? ", " : ")\n");
            out << "Each varying a = λ′0·a0 + λ′1·a1 + λ′2·a2 (perspective-correct).\n";
        } else {
            out << "Affine interpolation (no perspective correction): a = λ0·a0 + λ1·a1 + λ2·a2.\n";
        }
    } else {
        out << "  1/w = " << number(f.invW) << "\n";
    }
    const std::vector<std::string> names = varyingNames(prepared, entry.ref.draw, f.varyingCount);
    bool atCorners = setup != nullptr;
    for (const std::vector<float>* v : corners.varyings)
        atCorners = atCorners && v && static_cast<int>(v->size()) >= f.varyingCount;
    if (!atCorners) {
        // Without the corners' values (not recorded): the interpolated values alone.
        out << "\nThe fragment shader's inputs, interpolated:\n";
        std::string line;
        for (int k = 0; k < f.varyingCount; ++k) {
            char cell[48];
            std::snprintf(cell, sizeof cell, "  %-8s %-13s", names[k].c_str(), number(f.varyings[k]).c_str());
            if (!line.empty() && line.size() + std::strlen(cell) > 80) {  // long names of one's own
                out << line.substr(0, line.find_last_not_of(' ') + 1) << "\n";
                line.clear();
            }
            line += cell;
            if (k % 3 == 2 || k + 1 == f.varyingCount) {
                out << line.substr(0, line.find_last_not_of(' ') + 1) << "\n";
                line.clear();
            }
        }
        return out.str();
    }
    // Flat varyings (GLSL flat) take the provoking vertex's value, not the weighted sum.
    int flat = 0;
    const PreparedDraw* draw =
        prepared && entry.ref.draw < prepared->draws.size() ? &prepared->draws[entry.ref.draw] : nullptr;
    if (draw && !draw->userShader.module && draw->frequency == ShadingFrequency::Flat)
        flat = PerVertexSurface<ShadingFrequency::Flat>::kFlatVaryingFloats;
    const std::string provoking =
        triangle && triangle->state.raster.provokingVertex == ProvokingVertex::First ? "v0" : "v2";
    out << "\nThe fragment shader's inputs: each varying a at the corners (the vertex shader's\n"
        << "outputs" << (corners.clipped ? ", mixed by clipping" : "") << ") and at the pixel, "
        << (setup->perspective ? "a = λ′0·a0 + λ′1·a1 + λ′2·a2" : "a = λ0·a0 + λ1·a1 + λ2·a2") << ":\n";
    char head[96];
    std::snprintf(head, sizeof head, "  %-10s %13s %13s %13s   %s", "", a.c_str(), b.c_str(), c.c_str(),
                  "at the pixel");
    out << head << "\n";
    for (int k = 0; k < f.varyingCount; ++k) {
        std::string name = names[k];
        if (name.size() > 10) {  // long names of one's own: a line of their own
            out << "  " << name << "\n";
            name.clear();
        }
        char row[128];
        std::snprintf(row, sizeof row, "  %-10s %13s %13s %13s = %s", name.c_str(),
                      number((*corners.varyings[0])[k]).c_str(), number((*corners.varyings[1])[k]).c_str(),
                      number((*corners.varyings[2])[k]).c_str(), number(f.varyings[k]).c_str());
        out << row << (k < flat ? " (flat)" : "") << "\n";
    }
    if (flat > 0)
        out << "(flat: the provoking vertex " << provoking << "'s value, the same all over the triangle)\n";
    return out.str();
}

}  // namespace

std::vector<Screen> fragmentScreens(const PreparedScene* prepared, const PixelTrace& p,
                                    const TriangleAtPixel* entry, const TriangleTrace* triangle) {
    std::vector<Screen> screens;
    const std::string at = "(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ")";
    if (!entry || !entry->fragment) {
        std::ostringstream out;
        out << wrapText("The traced triangle made no fragment at pixel " + at + ": " +
                            (entry ? fateText(*entry) : "its bounding box does not hold the pixel") + ".",
                        80, 0)
            << "Pick a triangle that covers the pixel (t N) or another pixel (p X,Y).\n";
        screens.push_back({"interpolate", "Interpolation: no fragment of this triangle here", out.str()});
        return screens;
    }
    const FragmentEvent& f = *entry->fragment;
    // The piece that covers the pixel, for the corners' 1/w, depths and varyings.
    const WindowPiece* setupPiece = nullptr;
    if (triangle)
        for (const WindowPiece& piece : triangle->pieces)
            if (piece.fate == TriangleFate::Drawn && coverageAt(piece.setup, p.x, p.y).covered)
                setupPiece = &piece;
    {
        std::ostringstream out;
        out << interpolationText(prepared, *entry, triangle, setupPiece);
        screens.push_back({"interpolate", "Interpolation: barycentrics, depth, 1/w, varyings", out.str()});
    }
    {
        std::ostringstream out;
        if (entry->depthCompare == CompareOp::Always) {
            out << "The depth test is off for this draw: every fragment passes.\n";
        } else {
            out << "Depth test: the fragment passes when z_fragment " << compareText(entry->depthCompare)
                << " z_buffer.\n"
                << "  z_fragment = " << number(f.depth) << "\n  z_buffer   = " << number(f.depthBefore)
                << (f.depthBefore == 1.0f ? " (cleared: nothing nearer drawn yet)" : "") << "\n  "
                << number(f.depth) << " " << compareText(entry->depthCompare) << " " << number(f.depthBefore)
                << (f.fate == FragmentFate::DepthFailed ? " is false: the fragment is dropped.\n"
                                                        : " is true: the fragment goes on.\n");
        }
        screens.push_back({"depth",
                           f.fate == FragmentFate::DepthFailed ? "Depth test: failed" : "Depth test: passed",
                           out.str()});
    }
    return screens;
}

// The sort key that placed a transparent triangle in the back-to-front order (renderer.h's eyeDepthOf
// and sortKeyOf, as the frame's plan computed it).
std::string sortKeyText(const PreparedScene& prepared, const TriangleRef& ref) {
    if (ref.draw >= prepared.draws.size()) return "";
    const PreparedDraw& d = prepared.draws[ref.draw];
    const std::size_t first = 3 * std::size_t{ref.triangle};
    if (first + 2 >= d.indices.size()) return "";
    float z[3];
    for (int c = 0; c < 3; ++c)
        z[c] = eyeDepthOf(d.uniforms.viewFromObject, d.vertices[d.indices[first + c]].position);
    const SortKey key = prepared.scene.transparency.key;
    const float value = sortKeyOf(key, z[0], z[1], z[2]);
    std::ostringstream out;
    out << "Its sort key, the distance along the view direction (larger is farther, drawn\nearlier), of its "
        << (key == SortKey::Centroid ? "centroid" : "farthest corner") << ", from the corners' eye-space z:\n"
        << "  z0 = " << number(z[0]) << ", z1 = " << number(z[1]) << ", z2 = " << number(z[2]) << "\n";
    // The rule, the corners' numbers in it, the key: one line each, so that long numbers fit.
    if (key == SortKey::Centroid)
        out << "  z_key = −(z0 + z1 + z2)/3\n        = −(" << bracketedIfNegative(z[0]) << " + "
            << bracketedIfNegative(z[1]) << " + " << bracketedIfNegative(z[2]) << ")/3\n";
    else
        out << "  z_key = −min(z0, z1, z2)\n        = −min(" << number(z[0]) << ", " << number(z[1]) << ", "
            << number(z[2]) << ")\n";
    out << "        = " << number(value) << "\n";
    return out.str();
}

std::vector<Screen> outputScreens(const PreparedScene& prepared, const PixelTrace& p,
                                  const TriangleAtPixel* entry) {
    std::vector<Screen> screens;
    {
        std::ostringstream out;
        const FragmentEvent* f = entry && entry->fragment ? &*entry->fragment : nullptr;
        std::string title = "Blending";
        if (f && (f->fate == FragmentFate::Written)) {
            const vec4& s = f->shaded;
            const vec4& d = f->colorBefore;
            out << "Source, the shader's output:\n  c_s = " << vectorText(vec3(s))
                << ", α_s = " << number(s.a)
                << "\nDestination, the colour buffer:\n  c_d = " << vectorText(vec3(d)) << "\n";
            switch (entry->blend) {
                case BlendMode::Replace:
                    out << "No blending (opaque): c_o = c_s\n";
                    title = "Output merge: written, no blending";
                    break;
                case BlendMode::Over:
                    out << "The over operator: c_o = α_s·c_s + (1 − α_s)·c_d\n  = " << number(s.a) << "·"
                        << vectorText(vec3(s)) << "\n    + " << number(1.0f - s.a) << "·"
                        << vectorText(vec3(d)) << "\n";
                    title = "Blending: the over operator";
                    break;
                case BlendMode::OverGL:
                    out << "OpenGL's over: c_o = α_s·c_s + (1 − α_s)·c_d, α_o = α_s·α_s + (1 − α_s)·α_d\n  = "
                        << number(s.a) << "·" << vectorText(vec3(s)) << "\n    + " << number(1.0f - s.a)
                        << "·" << vectorText(vec3(d)) << "\n";
                    title = "Blending: OpenGL's over";
                    break;
                case BlendMode::PremultipliedOver:
                    out << "Over, premultiplied: c_o = c_s + (1 − α_s)·c_d (c_s already holds α_s·c)\n";
                    title = "Blending: premultiplied over";
                    break;
                case BlendMode::Additive:
                    out << "Additive: c_o = c_d + c_s (c_s holds α·c)\n";
                    title = "Blending: additive";
                    break;
                case BlendMode::Multiply:
                    out << "Multiply (a filter): c_o = c_s ⊗ c_d\n";
                    title = "Blending: multiply";
                    break;
            }
            out << "  c_o = " << vectorText(vec3(f->colorAfter)) << ", α_o = " << number(f->colorAfter.a)
                << "\n";
            if (entry->transparent && entry->sortPlace)
                out << "\nThis transparent triangle was drawn " << *entry->sortPlace + 1 << ". of "
                    << "the frame's transparent triangles\n(" << nameOf(prepared.scene.transparency.mode)
                    << " order).\n";
            if (entry->transparent && entry->sortPlace &&
                prepared.scene.transparency.mode == TransparencyMode::Sorted)
                out << sortKeyText(prepared, entry->ref);
            if (entry->overwrittenBy)
                out << "\nLater " << triangleName(*entry->overwrittenBy) << " wrote this pixel again.\n";
        } else if (f && f->fate == FragmentFate::Stored) {
            out << wrapText("Exact transparency: the fragment's colour " + vectorText(f->shaded) +
                                " went into the pixel's fragment list; after the frame the list is sorted "
                                "far to near and composited with the over operator,",
                            kScreenColumns, 0)
                << "  c_o = α_s·c_s + (1 − α_s)·c_d (see the history).\n";
            title = "Blending: stored in the pixel's fragment list";
        } else {
            out << "The traced triangle wrote nothing here.\n";
            title = "Blending: nothing written by this triangle";
        }
        screens.push_back({"blend", title, out.str()});
    }
    {
        std::ostringstream out;
        out << "The colour buffer holds linear light:\n  c = " << vectorText(p.finalColor) << "\n";
        const ColorEncoding& e = p.encoding;
        switch (e.curve) {
            case TransferCurve::Srgb:
                out << "8-bit files store it sRGB-encoded (the exact sRGB curve):\n"
                       "  c′ = 12.92·c for c ≤ 0.0031308, else 1.055·c^(1/2.4) − 0.055\n";
                break;
            case TransferCurve::Power:
                out << "8-bit files store it gamma-encoded: c′ = c^(1/γ), γ = " << number(e.gamma) << "\n";
                break;
            case TransferCurve::Linear:
                out << "8-bit files store it as it is (no encoding): c′ = c\n";
                break;
        }
        out << "then clamped to [0, 1] and rounded: byte = round(255·c′), alpha round(255·α_o).\n";
        static const char* const kChannel[] = {"R", "G", "B", "A"};
        for (int c = 0; c < 4; ++c) {
            const double linear = p.finalColor[c];
            const double encoded = c < 3 ? encodedUnit(float(linear), e) : linear;
            std::string line = "  " + std::string(kChannel[c]) + ": " + number(linear);
            std::string rest;  // the byte, and 255·c' before it: on a line of its own when too long
            if (c < 3 && e.curve == TransferCurve::Srgb) line += " → " + number(encoded);
            if (c < 3 && e.curve == TransferCurve::Power) {
                // c′ = c^(1/γ) (of c clamped to at most 1; c ≤ 0 gives 0), then 255·c′ rounded.
                if (linear > 0.0) {
                    line += "^(1/" + number(e.gamma) + ")" + (linear > 1.0 ? " (clamped to 1)" : "") + " = " +
                            number(encoded) + ",";
                    rest = "255·c′ = " + number(float(encoded) * 255.0f) + " ";
                } else {
                    line += " ≤ 0: c′ = 0";
                }
            }
            rest += "→ " + std::to_string(int(p.finalBytes[c]));
            out << oneLineOrTwo(line, rest, 5);
        }
        char hex[16];
        std::snprintf(hex, sizeof hex, "#%02x%02x%02x", p.finalBytes[0], p.finalBytes[1], p.finalBytes[2]);
        out << "The image file holds " << int(p.finalBytes[0]) << ", " << int(p.finalBytes[1]) << ", "
            << int(p.finalBytes[2]) << " (" << hex << ") at this pixel.\n";
        screens.push_back({"encode", "Encoding: the byte in the image file", out.str()});
    }
    return screens;
}

}  // namespace facet::step
