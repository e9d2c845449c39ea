// Shaders of one's own through the facet program (--shader, --uniform, the scene key "shader"):
// every kind of bad shader or bad value ends in one clear line and exit status 1, never a crash; and
// the cache of compiled modules compiles a shader once, again when it or a header it includes changes,
// keeps two shaders of one file name apart, survives two runs compiling at once, and says so when it
// cannot be made.
//
// Modules these tests load without compiling are built with the test binary (tests/CMakeLists.txt):
// FACET_TEST_TOON_MODULE (tests/cli/shaders/toon.cpp through facet_add_shader), FACET_TEST_NO_ENTRY_MODULE
// (a plain C function's library) and FACET_TEST_OTHER_KEY_MODULE (one claiming another Facet's key).
// Each test keeps compiled shaders in a cache folder of its own (FACET_SHADER_CACHE).
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "io/image_io.h"
#include "run_facet.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
using testing_support::readText;
using testing_support::runFacet;
using testing_support::RunResult;
using testing_support::TempFolder;

const fs::path kSource = FACET_SOURCE_DIR;
const fs::path kShaders = kSource / "tests/cli/shaders";
const fs::path kModel = kSource / "models/spot/spot_triangulated.obj";

using testing_support::shellQuoted;

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

void writeFile(const fs::path& file, const std::string& text) {
    std::ofstream(file, std::ios::binary) << text;
}

// The lines of `text` that start with facet's error prefix.
int errorLines(const std::string& text) {
    int count = 0;
    std::istringstream lines(text);
    std::string line;
    while (std::getline(lines, line))
        count += line.starts_with("facet: error: ");
    return count;
}

// The test's own cache of compiled shaders, in `dir`, for every facet it runs.
void useCache(const fs::path& cache) {
    ::setenv("FACET_SHADER_CACHE", cache.c_str(), 1);
}

// facet render of the bundled cow, small, into `image`, with `options`.
RunResult render(const TempFolder& dir, const fs::path& image, const std::string& options,
                 const fs::path& workingFolder = {}) {
    return runFacet(
        "render " + shellQuoted(kModel) + " --width 64 --height 48 -o " + shellQuoted(image) + " " + options,
        dir, workingFolder);
}

// A refused run: status 1, one "facet: error:" line holding `message` (and for `exactlyOneLine`, nothing
// else on standard error: a compile error's compiler messages come first).
void expectRefused(const RunResult& run, const std::string& message, bool exactlyOneLine = true) {
    EXPECT_EQ(run.status, 1) << run.err;
    EXPECT_EQ(errorLines(run.err), 1) << run.err;
    EXPECT_TRUE(contains(run.err, message)) << "wanted \"" << message << "\" in:\n" << run.err;
    if (exactlyOneLine) {
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    }
}

class UserShaderCli : public ::testing::Test {
  protected:
    void SetUp() override { useCache(dir.path() / "cache"); }
    TempFolder dir;
    fs::path image() const { return dir.path() / "out.ppm"; }

    // A scene file in the test's folder drawing the cow with `shader` as its "shader" value.
    fs::path sceneWithShader(const std::string& shader) const {
        const fs::path scene = dir.path() / "scene.json";
        writeFile(scene, "{\"width\": 64, \"height\": 48, \"objects\": [{\"model\": \"" + kModel.string() +
                             "\"}], \"shader\": " + shader + "}\n");
        return scene;
    }
    RunResult renderScene(const fs::path& scene) const {
        return runFacet("render " + shellQuoted(scene) + " -o " + shellQuoted(image()), dir);
    }
};

// ---- Modules that load -----------------------------------------------------------------------------

// The module built by facet_add_shader draws, and not the built-in shader's picture. Breaks caught:
// facet_add_shader building a module facet cannot load (name, visibility, flags), or --shader ignored.
TEST_F(UserShaderCli, ModuleFromFacetAddShaderDraws) {
    const RunResult builtin = render(dir, dir.path() / "builtin.ppm", "");
    ASSERT_EQ(builtin.status, 0) << builtin.err;
    const RunResult toon = render(dir, image(), "--shader " + shellQuoted(FACET_TEST_TOON_MODULE));
    ASSERT_EQ(toon.status, 0) << toon.err;
    EXPECT_FALSE(contains(toon.err, "compiling")) << "a .so is loaded as it is: " << toon.err;
    EXPECT_NE(readText(image()), readText(dir.path() / "builtin.ppm"));
}

// ---- Bad modules and files -------------------------------------------------------------------------

// Breaks caught: a missing shader file reaching the compiler (its messages instead of facet's line).
TEST_F(UserShaderCli, ShaderFileThatDoesNotExist) {
    expectRefused(render(dir, image(), "--shader " + shellQuoted(dir.path() / "missing.cpp")),
                  "missing.cpp: no such shader file");
}

// Breaks caught: a text file named .so passed to the program crashing it or giving dlerror alone.
TEST_F(UserShaderCli, FileNamedSoThatIsNoSharedLibrary) {
    writeFile(dir.path() / "fake.so", "not an ELF file\n");
    expectRefused(render(dir, image(), "--shader " + shellQuoted(dir.path() / "fake.so")),
                  "fake.so: the shader module does not load: ");
}

// Breaks caught: a library without FACET_SHADER's entry points called through a null pointer.
TEST_F(UserShaderCli, SharedLibraryWithoutEntryPoints) {
    expectRefused(render(dir, image(), "--shader " + shellQuoted(FACET_TEST_NO_ENTRY_MODULE)),
                  "not a facet shader module (it exports no facet_shader_abi or facet_shader_module: "
                  "does the shader's file end with FACET_SHADER(Name)?)");
}

// Breaks caught: a module of another Facet's headers run with this one's layouts (its module entry,
// null in the stand-in, would be called).
TEST_F(UserShaderCli, ModuleOfAnotherFacetIsRefused) {
    expectRefused(render(dir, image(), "--shader " + shellQuoted(FACET_TEST_OTHER_KEY_MODULE)),
                  "the shader module was built for facet 0.0.0, headers 0123456789abcdef, GNU 1.0 (a test's "
                  "stand-in), and this is facet ");
}

// ---- Uniforms ----------------------------------------------------------------------------------------

// Breaks caught: a misspelt --uniform silently ignored, or the message not listing the declared ones.
TEST_F(UserShaderCli, UniformTheShaderDoesNotDeclare) {
    expectRefused(
        render(dir, image(), "--shader " + shellQuoted(FACET_TEST_TOON_MODULE) + " --uniform band=3"),
        "--uniform band=3");
    const RunResult run =
        render(dir, image(), "--shader " + shellQuoted(FACET_TEST_TOON_MODULE) + " --uniform band=3");
    EXPECT_TRUE(contains(run.err, "(it has: bands (int, 4), outline (float, 0.3), ink (vec3, (0, 0, 0)))"))
        << run.err;
    // In the scene file: the uniform's place in the file, and the shader's declarations.
    expectRefused(renderScene(sceneWithShader("{\"source\": \"" + std::string(FACET_TEST_TOON_MODULE) +
                                              "\", \"uniforms\": {\"colour\": 1}}")),
                  "\"shader.uniforms.colour\": " + std::string(FACET_TEST_TOON_MODULE) +
                      " declares no uniform \"colour\" (it has: bands (int, 4)");
    EXPECT_FALSE(fs::exists(image()));
}

// Breaks caught: a value of the wrong type converted (true as an int, a vec3 from one number, a
// fraction for an int) instead of refused.
TEST_F(UserShaderCli, UniformValueOfTheWrongType) {
    const std::string toon = "--shader " + shellQuoted(FACET_TEST_TOON_MODULE);
    expectRefused(render(dir, image(), toon + " --uniform bands=true"), "declares bands as int");
    expectRefused(render(dir, image(), toon + " --uniform ink=1,2"), "declares ink as vec3: give 3 numbers");
    expectRefused(render(dir, image(), toon + " --uniform outline=false"), "declares outline as float");
    const std::string module = "\"" + std::string(FACET_TEST_TOON_MODULE) + "\"";
    expectRefused(renderScene(sceneWithShader("{\"source\": " + module + ", \"uniforms\": {\"ink\": 0.5}}")),
                  "\"shader.uniforms.ink\": " + fs::path(FACET_TEST_TOON_MODULE).string() +
                      " declares ink as vec3: give 3 numbers");
    expectRefused(
        renderScene(sceneWithShader("{\"source\": " + module + ", \"uniforms\": {\"bands\": \"4\"}}")),
        "\"shader.uniforms.bands\" must be a number, true or false, or an array of 2 to 4 numbers");
    EXPECT_FALSE(fs::exists(image()));
}

// ---- The scene key "shader" ----------------------------------------------------------------------------

// Breaks caught: a malformed "shader" value reaching the loader (a crash on a number, an empty path
// taken as the scene's folder, an unknown key ignored).
TEST_F(UserShaderCli, MalformedShaderKeyInTheScene) {
    expectRefused(renderScene(sceneWithShader("3")), "\"shader\" must be a file name or an object like");
    expectRefused(renderScene(sceneWithShader("\"\"")),
                  "\"shader\" must name a shader file (got an empty string)");
    expectRefused(renderScene(sceneWithShader("{\"source\": \"\"}")),
                  "\"shader.source\" must name a shader file (got an empty string)");
    expectRefused(renderScene(sceneWithShader("{\"uniforms\": {}}")), "\"shader.source\" is missing");
    expectRefused(renderScene(sceneWithShader("{\"source\": \"toon.cpp\", \"uniform\": {}}")),
                  "unknown key \"shader.uniform\" (did you mean \"uniforms\"?)");
    expectRefused(renderScene(sceneWithShader("{\"source\": \"toon.cpp\", \"uniforms\": [1]}")),
                  "\"shader.uniforms\" must be an object like");
    // A file the scene names, resolved against the scene's folder.
    expectRefused(renderScene(sceneWithShader("\"nowhere/toon.cpp\"")),
                  "nowhere/toon.cpp: no such shader file");
}

// ---- Shaders that do not compile ---------------------------------------------------------------------

// The compiler's messages name the user's file and line, and facet adds its one line. Breaks caught:
// the compiler's output swallowed, or the file given to the compiler by another name than the user's.
TEST_F(UserShaderCli, CompileErrorPointsAtTheFileAndLine) {
    fs::copy_file(kShaders / "compile_error.cpp", dir.path() / "compile_error.cpp");
    const RunResult run = render(dir, image(), "--shader compile_error.cpp", dir.path());
    expectRefused(
        run,
        "facet: error: compile_error.cpp: the shader did not compile (the compiler's messages are above)",
        false);
    EXPECT_TRUE(contains(run.err, "compile_error.cpp:14:")) << run.err;
    EXPECT_TRUE(contains(run.err, "undeclared_colour")) << run.err;
    EXPECT_FALSE(fs::exists(image()));
    // Nothing half-made is kept in the cache (its lock file alone).
    for (const auto& entry : fs::directory_iterator(dir.path() / "cache"))
        EXPECT_EQ(entry.path().extension(), ".lock") << entry.path();
}

// A shader whose parts are wrong (a vertex part of another signature, no fragment part) is told how
// each is written (shader_module.h's checkParts()). Breaks caught: the static_asserts' readable messages
// lost among (or replaced by) template errors from the pipeline.
TEST_F(UserShaderCli, WrongPartsSayHowThePartsAreWritten) {
    const RunResult run = render(dir, image(), "--shader " + shellQuoted(kShaders / "wrong_parts.cpp"));
    expectRefused(run, "wrong_parts.cpp: the shader did not compile", false);
    EXPECT_TRUE(contains(run.err,
                         "a user shader's vertex part: static VertexOut<VaryingsT<float>> "
                         "vertex(const MeshVertex&, const Uniforms&)"))
        << run.err;
    EXPECT_TRUE(contains(run.err,
                         "a user shader's fragment part: template <class F> static LaneVec4<F> "
                         "fragment(const VaryingsT<F>&, const Uniforms&, Fragment<F>&)"))
        << run.err;
}

// ---- The cache ---------------------------------------------------------------------------------------

// The toon shader with its light's share in a header beside it (#include "my_helpers.h").
void writeShaderWithHelper(const fs::path& folder, const std::string& light) {
    std::string toon = readText(kShaders / "toon.cpp");
    const std::string use = "lanes<F>(0.8f)";
    toon.replace(toon.find(use), use.size(), "lanes<F>(kLightShare)");
    toon.insert(toon.find("using namespace facet;"), "#include \"my_helpers.h\"\n");
    writeFile(folder / "shader.cpp", toon);
    writeFile(folder / "my_helpers.h", "#pragma once\ninline constexpr float kLightShare = " + light + ";\n");
}

// One shader through the cache: compiled once, then loaded; compiled again when a header it includes
// changes, when the shader itself does, and when its cached module is damaged; each time the image
// follows the change.
// Breaks caught, in order: the cache never hit (every run compiles); an edited included header not
// noticed (the stale module drawn); an edited source not noticed; a damaged cached module an error
// for ever (or the damaged file found again by dlopen under its name).
TEST_F(UserShaderCli, CacheCompilesOnceAndAgainWhenTheShaderItsHeaderOrTheModuleChanges) {
    writeShaderWithHelper(dir.path(), "0.8f");
    const std::string shader = "--shader " + shellQuoted(dir.path() / "shader.cpp");
    const RunResult first = render(dir, dir.path() / "first.ppm", shader);
    ASSERT_EQ(first.status, 0) << first.err;
    EXPECT_TRUE(contains(first.err, "facet: compiling ")) << first.err;

    const RunResult second = render(dir, dir.path() / "second.ppm", shader);
    ASSERT_EQ(second.status, 0) << second.err;
    EXPECT_FALSE(contains(second.err, "compiling")) << "the second run compiled again: " << second.err;
    EXPECT_EQ(readText(dir.path() / "first.ppm"), readText(dir.path() / "second.ppm"));

    // The header, edited (a longer text: its size changes even where the clock is coarse).
    writeFile(dir.path() / "my_helpers.h",
              "#pragma once\ninline constexpr float kLightShare = 0.35f;  // dimmer\n");
    const RunResult edited = render(dir, dir.path() / "header.ppm", shader);
    ASSERT_EQ(edited.status, 0) << edited.err;
    EXPECT_TRUE(contains(edited.err, "facet: compiling ")) << "an edited header did not compile again";
    EXPECT_NE(readText(dir.path() / "first.ppm"), readText(dir.path() / "header.ppm"));

    // The source, edited: the ink's default red.
    std::string source = readText(dir.path() / "shader.cpp");
    source.replace(source.find("vec3 ink{0.0f};"), 15, "vec3 ink{1.0f, 0.0f, 0.0f};");
    writeFile(dir.path() / "shader.cpp", source);
    const RunResult again = render(dir, dir.path() / "source.ppm", shader);
    ASSERT_EQ(again.status, 0) << again.err;
    EXPECT_TRUE(contains(again.err, "facet: compiling ")) << "an edited source did not compile again";
    EXPECT_NE(readText(dir.path() / "header.ppm"), readText(dir.path() / "source.ppm"));

    // The cached modules, damaged: compiled again, not an error until the cache is emptied by hand.
    for (const auto& entry : fs::directory_iterator(dir.path() / "cache"))
        if (entry.path().extension() == ".so") writeFile(entry.path(), "cut short\n");
    const RunResult healed = render(dir, dir.path() / "healed.ppm", shader);
    ASSERT_EQ(healed.status, 0) << healed.err;
    EXPECT_TRUE(contains(healed.err, "the shader module does not load")) << healed.err;
    EXPECT_TRUE(contains(healed.err, "facet: compiling "))
        << "a damaged cached module was not compiled again";
    EXPECT_EQ(readText(dir.path() / "source.ppm"), readText(dir.path() / "healed.ppm"));
}

// Two shaders called toon.cpp in two folders, one cache: each draws its own picture.
// Breaks caught: the cache keyed by the file's name (the second folder's toon.cpp drawn with the first's).
TEST_F(UserShaderCli, SameFileNameInTwoFoldersDoesNotCollide) {
    fs::create_directories(dir.path() / "a");
    fs::create_directories(dir.path() / "b");
    fs::copy_file(kShaders / "toon.cpp", dir.path() / "a/toon.cpp");
    std::string red = readText(kShaders / "toon.cpp");
    red.replace(red.find("return withAlpha(c, lanes<F>(1.0f));"), 36,
                "return withAlpha(V3(vec3(1.0f, 0.0f, 0.0f)) * ndotv, lanes<F>(1.0f));");
    writeFile(dir.path() / "b/toon.cpp", red);
    const RunResult a = render(dir, dir.path() / "a.ppm", "--shader a/toon.cpp", dir.path());
    ASSERT_EQ(a.status, 0) << a.err;
    const RunResult b = render(dir, dir.path() / "b.ppm", "--shader b/toon.cpp", dir.path());
    ASSERT_EQ(b.status, 0) << b.err;
    EXPECT_TRUE(contains(b.err, "facet: compiling b/toon.cpp")) << b.err;
    EXPECT_NE(readText(dir.path() / "a.ppm"), readText(dir.path() / "b.ppm"));
    // And a is still a's (b did not replace it).
    const RunResult aAgain = render(dir, dir.path() / "a2.ppm", "--shader a/toon.cpp", dir.path());
    ASSERT_EQ(aAgain.status, 0) << aAgain.err;
    EXPECT_FALSE(contains(aAgain.err, "compiling")) << aAgain.err;
    EXPECT_EQ(readText(dir.path() / "a.ppm"), readText(dir.path() / "a2.ppm"));
}

// A shader is compiled for the kind of draw its scene makes (the back end's walk: its depth coding,
// samples, output), once, and draws what the module built with every walk (facet_add_shader) draws.
// Breaks caught: the scene's walk reckoned otherwise than the draw takes it (the run compiles the shader
// a second time, "again", when it draws); the module's walks set by anything but the scene (a cached
// module of another scene's walk loaded and refused at the draw); a .so lacking a scene's walk drawing
// nothing, or failing with the pipeline's error instead of one line naming what it lacks.
TEST_F(UserShaderCli, AShaderIsCompiledOnceForTheDrawsOfItsScene) {
    fs::copy_file(kShaders / "toon.cpp", dir.path() / "toon.cpp");
    const std::string settings = "--aa msaa4 --depth unorm24 ";
    const RunResult compiled = render(dir, image(), settings + "--shader toon.cpp", dir.path());
    ASSERT_EQ(compiled.status, 0) << compiled.err;
    std::size_t compiles = 0;
    for (std::size_t at = compiled.err.find("facet: compiling "); at != std::string::npos;
         at = compiled.err.find("facet: compiling ", at + 1))
        ++compiles;
    EXPECT_EQ(compiles, 1u) << compiled.err;
    const RunResult module =
        render(dir, dir.path() / "module.ppm", settings + "--shader " + shellQuoted(FACET_TEST_TOON_MODULE));
    ASSERT_EQ(module.status, 0) << module.err;
    EXPECT_EQ(readText(image()), readText(dir.path() / "module.ppm"));
    // That module, given as a .so to a scene of another walk: refused in one line, not drawn blank.
    fs::path lean;
    for (const auto& entry : fs::directory_iterator(dir.path() / "cache"))
        if (entry.path().extension() == ".so") lean = entry.path();
    ASSERT_FALSE(lean.empty());
    expectRefused(render(dir, dir.path() / "lean.ppm", "--shader " + shellQuoted(lean)),
                  "the module was built without the code for float depth draws");
    // Another scene's walk (one sample, float depth): compiled for it, not the module above refused.
    const RunResult plain = render(dir, dir.path() / "plain.ppm", "--shader toon.cpp", dir.path());
    ASSERT_EQ(plain.status, 0) << plain.err;
    EXPECT_NE(readText(dir.path() / "plain.ppm"), readText(image()));
}

// Two facet processes asking for one shader of one cache at the same moment both draw, the same picture:
// one compiles, the other waits and loads its module; a third run finds a whole module. Breaks caught:
// the two writing one file (a torn module, "file too short" from dlopen), one removing what the other is
// about to load, or both compiling (a job array's hundred tasks compiling one shader a hundred times).
TEST_F(UserShaderCli, TwoRunsAtOnceBothSucceedAndOneCompiles) {
    fs::copy_file(kShaders / "toon.cpp", dir.path() / "toon.cpp");
    const std::string shader = "--shader " + shellQuoted(dir.path() / "toon.cpp");
    TempFolder other("second");  // runFacet keeps each run's output in its folder
    auto second =
        std::async(std::launch::async, [&] { return render(other, dir.path() / "two.ppm", shader); });
    const RunResult one = render(dir, dir.path() / "one.ppm", shader);
    const RunResult two = second.get();
    ASSERT_EQ(one.status, 0) << one.err;
    ASSERT_EQ(two.status, 0) << two.err;
    // One compiled; the other waited for it (or came after it) and loaded its module.
    const auto compiled = [](const RunResult& run) { return contains(run.err, "facet: compiling ") ? 1 : 0; };
    EXPECT_EQ(compiled(one) + compiled(two), 1) << one.err << "---\n" << two.err;
    EXPECT_EQ(readText(dir.path() / "one.ppm"), readText(dir.path() / "two.ppm"));
    const RunResult third = render(dir, dir.path() / "three.ppm", shader);
    ASSERT_EQ(third.status, 0) << third.err;
    EXPECT_FALSE(contains(third.err, "compiling")) << third.err;
    // Nothing of theirs is left but the module, its key and its lock.
    for (const auto& entry : fs::directory_iterator(dir.path() / "cache")) {
        const fs::path kind = entry.path().extension();
        EXPECT_TRUE(kind == ".so" || kind == ".key" || kind == ".lock") << entry.path();
    }
}

// Breaks caught: a cache folder that cannot be made ending in an exception's what() or a compiler error
// about its output file instead of facet's line naming the folder.
TEST_F(UserShaderCli, CacheFolderThatCannotBeMadeIsAnError) {
    writeFile(dir.path() / "file", "a file where the cache's parent folder should be\n");
    useCache(dir.path() / "file/cache");
    fs::copy_file(kShaders / "toon.cpp", dir.path() / "toon.cpp");
    expectRefused(render(dir, image(), "--shader " + shellQuoted(dir.path() / "toon.cpp")),
                  "toon.cpp: cannot make the shader cache " + (dir.path() / "file/cache").string() + ": ");
}

// ---- The README's shader -----------------------------------------------------------------------------

// The shader README.md shows, cut from it, compiles, draws with its uniform and shows its record in the
// step mode. Breaks caught: the README's example going stale against user_shader.h (a renamed part, a
// GLSL function missing for eight lanes), --uniform not reaching the draw, gl.record not traced; facet
// step loading the module the renders compiled and compiling again at its first watched draw.
TEST_F(UserShaderCli, ReadmeShaderDrawsAndIsTraced) {
    const std::string readme = readText(kSource / "README.md");
    const std::size_t begin = readme.find("<!-- readme-shader:begin -->");
    const std::size_t end = readme.find("<!-- readme-shader:end -->");
    ASSERT_NE(begin, std::string::npos);
    ASSERT_NE(end, std::string::npos);
    const std::size_t codeStart = readme.find("```cpp\n", begin);
    const std::size_t codeEnd = readme.rfind("```", end);
    ASSERT_LT(codeStart, codeEnd);
    const fs::path shader = dir.path() / "bands.cpp";
    writeFile(shader, readme.substr(codeStart + 7, codeEnd - codeStart - 7));
    const RunResult three = render(dir, image(), "--shader " + shellQuoted(shader) + " --uniform bands=3");
    ASSERT_EQ(three.status, 0) << three.err;
    const RunResult two =
        render(dir, dir.path() / "two.ppm", "--shader " + shellQuoted(shader) + " --uniform bands=2");
    ASSERT_EQ(two.status, 0) << two.err;
    EXPECT_NE(readText(image()), readText(dir.path() / "two.ppm"));
    const RunResult step =
        runFacet("step " + shellQuoted(kModel) + " --width 64 --height 48 --pixel 32,24 --print --shader " +
                     shellQuoted(shader),
                 dir);
    ASSERT_EQ(step.status, 0) << step.err;
    EXPECT_TRUE(contains(step.out, "level = ")) << step.out;
    // The walk's watched draws compiled with the first compile, not after the render's module was loaded.
    EXPECT_TRUE(contains(step.err, "facet: compiling ")) << step.err;
    EXPECT_FALSE(contains(step.err, " again, for ")) << step.err;
}

}  // namespace
}  // namespace facet
