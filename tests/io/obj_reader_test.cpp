// Facet's own OBJ reader against tinyobjloader, its peer: every model of ../shared/models and generated
// files read both ways must give the same mesh, byte for byte, and the same messages; a file checked in
// several runs on threads must give what one run gives.

#include <algorithm>
#include <cstring>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "io/obj_import.h"
#include "io/obj_scan.h"
#include "support/bundled_models.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

using testing_support::kSharedModels;

// A mesh, or the error that refused the file, as one comparable record: floats by their bytes.
struct Loaded {
    std::string error;
    Mesh mesh;
};

Loaded load(const fs::path& path, ObjReader reader) {
    Loaded loaded;
    try {
        loaded.mesh = loadObjWith(path, reader);
    } catch (const InputError& e) {
        loaded.error = e.what();
    }
    return loaded;
}

template <class T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool sameMaterial(const Material& a, const Material& b) {
    return a.name == b.name && a.ambient == b.ambient && a.diffuse == b.diffuse && a.specular == b.specular &&
           a.shininess == b.shininess && a.emission == b.emission && a.opacity == b.opacity &&
           a.ior == b.ior && a.diffuseTexture == b.diffuseTexture && a.emissionTexture == b.emissionTexture &&
           a.fallback == b.fallback;
}

// Expects `path` read by Facet's reader and by tinyobjloader to give the same result.
void expectSameBothWays(const fs::path& path) {
    SCOPED_TRACE(path.string());
    const Loaded own = load(path, ObjReader::kFacet);
    const Loaded peer = load(path, ObjReader::kTinyobjloader);
    ASSERT_EQ(own.error, peer.error);
    if (!own.error.empty()) return;
    const Mesh &a = own.mesh, &b = peer.mesh;
    EXPECT_TRUE(sameBytes(a.vertices, b.vertices)) << a.vertices.size() << " vs " << b.vertices.size();
    EXPECT_TRUE(sameBytes(a.indices, b.indices)) << a.indices.size() << " vs " << b.indices.size();
    EXPECT_TRUE(sameBytes(a.parts, b.parts));
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (std::size_t m = 0; m < a.materials.size(); ++m)
        EXPECT_TRUE(sameMaterial(a.materials[m], b.materials[m])) << a.materials[m].name;
    EXPECT_EQ(a.hasTexcoords, b.hasTexcoords);
    EXPECT_EQ(a.warnings, b.warnings);
    EXPECT_EQ(a.stats.facesRead, b.stats.facesRead);
    EXPECT_EQ(a.stats.trianglesKept, b.stats.trianglesKept);
    EXPECT_EQ(a.stats.degenerateSkipped, b.stats.degenerateSkipped);
    EXPECT_EQ(a.stats.normalsComputed, b.stats.normalsComputed);
    EXPECT_EQ(a.stats.creaseSplits, b.stats.creaseSplits);
}

// Catches: Facet's reader reading a number, an index, a face or a material of a real model differently
// from tinyobjloader (a mesh or a message that changed), on any file of ../shared/models.
TEST(ObjReader, EveryModelAsTinyobjloaderReadsIt) {
    if (!fs::is_directory(kSharedModels)) GTEST_SKIP() << kSharedModels << " is absent";
    std::size_t files = 0;
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(kSharedModels)) {
        if (entry.path().extension() != ".obj") continue;
        expectSameBothWays(entry.path());
        ++files;
    }
    EXPECT_GT(files, 0u);
}

// Random coordinates in every form the OBJ grammar allows: long fractions (scaled by pow(10, -k) past
// 7 digits), exponents, leading dots, signs.
std::string randomNumber(std::mt19937& random) {
    std::uniform_int_distribution<int> digit(0, 9), count(0, 12), form(0, 7), exponent(-40, 38);
    std::string number;
    if (form(random) < 3) number += form(random) < 4 ? '-' : '+';
    const int whole = form(random) == 0 ? 0 : 1 + count(random) % 6;
    for (int i = 0; i < whole; ++i)
        number += char('0' + digit(random));
    const int fraction = whole == 0 ? 1 + count(random) : count(random);
    if (fraction > 0 || form(random) == 0) number += '.';
    for (int i = 0; i < fraction; ++i)
        number += char('0' + digit(random));
    if (form(random) < 2) number += (form(random) < 4 ? "e" : "E") + std::to_string(exponent(random) / 3);
    return number;
}

// Catches: a coordinate whose float differs in the last bit from tinyobjloader's (a correctly rounded
// reading such as from_chars, or a fused multiply-add, gives other bits for some of these).
TEST(ObjReader, RandomNumbersAsTinyobjloaderReadsThem) {
    testing_support::TempFolder folder;
    std::mt19937 random(44);
    std::ostringstream text;
    constexpr int kVertices = 20000;
    for (int v = 0; v < kVertices; ++v)
        text << "v " << randomNumber(random) << ' ' << randomNumber(random) << ' ' << randomNumber(random)
             << "\nvt " << randomNumber(random) << ' ' << randomNumber(random) << "\nvn "
             << randomNumber(random) << " 1 " << randomNumber(random) << '\n';
    for (int v = 1; v + 2 <= kVertices; v += 3)
        text << "f " << v << '/' << v << '/' << v << ' ' << v + 1 << '/' << v + 1 << '/' << v + 1 << ' '
             << v + 2 << '/' << v + 2 << '/' << v + 2 << '\n';
    expectSameBothWays(folder.write("numbers.obj", text.str()));
}

// Catches: relative indices, usemtl, mtllib order or unknown materials handled differently from
// tinyobjloader (materials named before their mtllib, after it, unknown, relative corners).
TEST(ObjReader, MaterialsAndRelativeIndicesAsTinyobjloaderReadsThem) {
    testing_support::TempFolder folder;
    folder.write("a.mtl", "newmtl red\nKd 1 0 0\nnewmtl green\nKd 0 1 0\n");
    folder.write("b.mtl", "newmtl blue\nKd 0 0 1\nnewmtl red\nKd 0.5 0 0\n");
    const fs::path path = folder.write(
        "m.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
        "usemtl blue\nf 1 2 3\nmtllib a.mtl\nusemtl red\nf -4 -3 -2\nusemtl nothing\nf 1/1 2/2 3/3\n"
        "mtllib missing.mtl b.mtl\nusemtl blue\nf 2//1 4//1 3//1\nusemtl red\nf -3/-3/-1 -2/-2/-1 -1/-1/-1\n"
        "usemtl green\nf 1 2 4 3\nf 1/9 2/1/5 3\n");
    expectSameBothWays(path);
    const Mesh mesh = loadObj(path);  // the file exercises what it compares: usemtl before its mtllib
    EXPECT_NE(std::find_if(mesh.warnings.begin(), mesh.warnings.end(),
                           [](const std::string& w) { return w.find("unknown material 'blue'") != w.npos; }),
              mesh.warnings.end());
}

// A file of `faces` triangles over a grid, long enough to be checked in several runs, with each of
// `extras` after its line (1-based, counting the grid's lines).
std::string gridWith(std::size_t faces, const std::map<std::size_t, std::string>& extras) {
    std::ostringstream text;
    std::size_t line = 0;
    const auto emit = [&](const std::string& statement) {
        text << statement << '\n';
        if (const auto extra = extras.find(++line); extra != extras.end()) text << extra->second;
    };
    emit("mtllib none.mtl");
    emit("usemtl first");
    for (std::size_t f = 0; f < faces; ++f) {
        emit("v " + std::to_string(f % 97) + " " + std::to_string(f / 97) + ".25 0.5");
        emit("vt 0." + std::to_string(f % 10) + " 1");
        if (f % 5000 == 4999) emit("usemtl m" + std::to_string(f));
        if (f >= 2) emit("f -3/-1 -2/-2 -1/-3");
    }
    return text.str();
}

obj::ObjScan scanOf(std::string text, unsigned threads) {
    const obj::ObjStatements statements = obj::splitObj(text);
    return obj::checkObj(text, statements, "t.obj", true, threads);
}

std::string errorOf(std::string text, unsigned threads) {
    try {
        scanOf(std::move(text), threads);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// Catches: runs on threads joined wrongly: a run's relative indices, usemtl inherited from the run
// before, a warning's first line or count, or the order of faces differing from one pass in file order.
TEST(ObjReader, RunsOnThreadsGiveWhatOnePassGives) {
    const std::string bad = "v 1 2.5x 3\nf 1/999999 2/1 3/1\nf 1 2\nusemtl late\n";
    const std::string text = gridWith(60000, {{70000, bad}, {130000, bad}, {170000, bad}});
    const obj::ObjScan one = scanOf(text, 1), four = scanOf(text, 4);
    EXPECT_TRUE(sameBytes(one.geometry.positions, four.geometry.positions));
    EXPECT_TRUE(sameBytes(one.geometry.texcoords, four.geometry.texcoords));
    EXPECT_TRUE(sameBytes(one.geometry.corners, four.geometry.corners));
    EXPECT_EQ(one.geometry.cornerCounts, four.geometry.cornerCounts);
    EXPECT_EQ(one.faceLines, four.faceLines);
    EXPECT_EQ(one.faceMaterial, four.faceMaterial);
    ASSERT_EQ(one.useMaterials.size(), four.useMaterials.size());
    EXPECT_EQ(one.useMaterials.back().line, four.useMaterials.back().line);
    EXPECT_EQ(one.strayNumbers, four.strayNumbers);
    EXPECT_EQ(one.firstStrayLine, four.firstStrayLine);
    EXPECT_EQ(one.badTexcoordIndices.line, four.badTexcoordIndices.line);
    EXPECT_EQ(one.badTexcoordIndices.count, four.badTexcoordIndices.count);
    EXPECT_EQ(one.shortFaces, four.shortFaces);
    EXPECT_EQ(one.firstShortFaceLine, four.firstShortFaceLine);
    EXPECT_EQ(one.facesRead, four.facesRead);
    EXPECT_GT(one.strayNumbers, 0u);  // the file exercises what it compares
    EXPECT_GT(one.badTexcoordIndices.count, 0u);
}

// Catches: a text split in runs on threads cut inside a `\` continuation or a CR LF pair, or lines
// numbered wrongly after the first run (statements, their lines or the rewritten text differing from
// one pass's).
TEST(ObjReader, SplitRunsGiveWhatOnePassGives) {
    std::mt19937 random(7);
    std::uniform_int_distribution<int> pick(0, 9);
    const char* const endings[] = {"\n", "\r\n", "\r", " \\\n", "\\\r\n", " \\ \n"};
    std::string text = "\xEF\xBB\xBF";
    while (text.size() < (5u << 20)) {
        switch (pick(random)) {
            case 0:
                text += "# a comment \\";
                break;
            case 1:
                text += "v 1 2 3 # trailing";
                break;
            case 2:
                text += "f 1 2 3";
                break;
            case 3:
                text += "vt 0.5";
                break;
            case 4:
                text += "  vn 0 0 1";
                break;
            case 5:
                text += "usemtl m";
                break;
            default:
                text += "v 4 5 6";
                break;
        }
        text += endings[pick(random) % 6];
    }
    std::string oneText = text, fourText = text;
    const obj::ObjStatements one = obj::splitObj(oneText, 1), four = obj::splitObj(fourText, 4);
    EXPECT_EQ(oneText, fourText);
    ASSERT_EQ(one.statements.size(), four.statements.size());
    for (std::size_t k = 0; k < one.statements.size(); ++k) {
        const obj::ScannedStatement &a = one.statements[k], &b = four.statements[k];
        ASSERT_TRUE(a.offset == b.offset && a.length == b.length && a.line == b.line && a.kind == b.kind)
            << "statement " << k << ": line " << a.line << " vs " << b.line;
    }
    EXPECT_EQ(one.counts.positions, four.counts.positions);
    EXPECT_EQ(one.counts.texcoords, four.counts.texcoords);
    EXPECT_EQ(one.counts.normals, four.counts.normals);
}

// Catches: an error in a later run reported instead of the file's first, or an error in a later run lost.
TEST(ObjReader, TheFirstErrorInTheFileWinsAcrossRuns) {
    const std::string late = gridWith(60000, {{150000, "v 1 nan 3\n"}});
    EXPECT_EQ(errorOf(late, 4), errorOf(late, 1));
    EXPECT_EQ(errorOf(late, 4).rfind("t.obj:150001: ", 0), 0u) << errorOf(late, 4);
    const std::string both = gridWith(60000, {{20000, "f 1 2 0\n"}, {170000, "v 1 nan 3\n"}});
    EXPECT_EQ(errorOf(both, 4), errorOf(both, 1));
    EXPECT_EQ(errorOf(both, 4).rfind("t.obj:20001: ", 0), 0u) << errorOf(both, 4);
}

}  // namespace
}  // namespace facet
