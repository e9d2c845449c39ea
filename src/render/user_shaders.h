// Shaders of one's own (docs/shaders.md): a C++ file written with shaders/user_shader.h is compiled,
// the first time it is used, by the compiler and with the flags facet itself was built with, against
// facet's headers (installed, or the source tree's for a facet inside its build folder), into a shader
// module (shaders/shader_module.h) kept in a cache; a module built separately (.so, facet_add_shader of
// the CMake package) is loaded as it is. A module runs in facet's process as native code: it is as
// trusted as any program one compiles oneself.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene.h"
#include "shaders/shader_module.h"

namespace facet {

// A loaded shader module and the name its messages use (the file as the user gave it).
struct UserShader {
    const ShaderModule* module = nullptr;
    std::string label;                // "toon.cpp"
    std::filesystem::path source;     // as given
    std::filesystem::path canonical;  // the registry's key
};

// The shader of `source`: a .so loaded as it is, anything else compiled (on first use: then cached)
// into a module holding the pipeline's back-end `walks` (pipeline/back_end.h: the kinds of draw it can
// make; a scene's draws take one or two, and each walk is a large part of the compile time), with the
// watched ones once compileForWatchedDraws() was called (every walk after compileEveryWalk()). Each
// file is loaded once per process and stays loaded; asked for a walk its module lacks, it is compiled
// again with every walk. Throws InputError with a one-line message when it does not compile (the
// compiler's messages, which point at the file and line, go to stderr first), cannot be loaded, is no
// shader module or was built for another version of facet.
UserShader loadUserShader(const std::filesystem::path& source, unsigned walks = walk::kAll);

// The module of `shader` holding `walk`: its own, or (once) the file compiled again with every walk.
const ShaderModule& userShaderFor(const UserShader& shader, unsigned walk);

// From now on, shaders are compiled with the watched draws too (the step mode's): one compile serves
// both the watched and the unwatched draws of a scene.
void compileForWatchedDraws();

// From now on, shaders are compiled with every walk (a command that draws one scene in many settings:
// one compile instead of one for the first setting and another for the rest).
void compileEveryWalk();

// The settings of the uniforms `values` for `shader`, in the module's terms. Throws InputError,
// naming the value's origin, for a uniform the shader does not declare (the message lists the ones it
// does) or a value of the wrong type. With `onlyDeclared`, values the shader does not declare are
// skipped instead (--uniform, which goes to every shader of the scene that declares it).
std::vector<UniformSetting> uniformSettings(const UserShader& shader, std::span<const UniformValue> values,
                                            bool onlyDeclared = false);

// Whether `shader` declares a uniform `name`.
bool declaresUniform(const UserShader& shader, std::string_view name);

// "bands (int, 4: steps of light), ink (vec3, (0, 0, 0))": the declared uniforms, for messages and
// listings.
std::string describeUniforms(const ShaderModule& module);

// A uniform's value as text: "4", "0.02", "true", "(0, 0, 0)".
std::string uniformValueText(UniformType type, const std::array<float, 4>& value);

// Where compiled modules are kept: $FACET_SHADER_CACHE, else $XDG_CACHE_HOME/facet/shaders, else
// ~/.cache/facet/shaders.
std::filesystem::path shaderCacheFolder();

// The compiler's command line for `source` into a module of `walks` at `output` (the flags facet was built
// with, the headers' folders, the instruction set of the frame's code this CPU runs), for messages and
// the docs.
std::vector<std::string> shaderCompileCommand(const std::filesystem::path& source,
                                              const std::filesystem::path& output,
                                              unsigned walks = walk::kAll);

}  // namespace facet
