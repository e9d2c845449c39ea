#include "render/user_shaders.h"

#include <dlfcn.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <random>
#include <sstream>

#include "base/errors.h"
#include "base/module.h"
#include "base/quote.h"
#include "facet_shader_build.h"  // FACET_SHADER_COMPILER, _FLAGS, _BUILD_INCLUDES, _INCLUDES_FROM_PROGRAM
#include "render/frame_kernels.h"

extern char** environ;

namespace facet {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> splitList(std::string_view list) {
    std::vector<std::string> items;
    std::size_t start = 0;
    while (start <= list.size()) {
        const std::size_t end = std::min(list.find(';', start), list.size());
        if (end > start) items.emplace_back(list.substr(start, end - start));
        start = end + 1;
    }
    return items;
}

// The folders a shader's #include "shaders/user_shader.h" is found in: the source tree's for a facet
// inside its build folder, else the installed headers' relative to the program.
std::vector<fs::path> headerFolders() {
    std::vector<fs::path> folders;
    if (programInBuildTree()) {
        for (const std::string& folder : splitList(FACET_SHADER_BUILD_INCLUDES))
            folders.emplace_back(folder);
        return folders;
    }
    for (const std::string& folder : splitList(FACET_SHADER_INCLUDES_FROM_PROGRAM))
        folders.push_back((programFolder() / folder).lexically_normal());
    return folders;
}

// The code generation flags of the frame's copy this CPU runs (frame_kernels.h), so that the shader's
// eight lanes use the same vectors as the built-in shaders'.
std::vector<std::string> instructionSetFlags() {
    switch (frameKernels().instructionSet) {
        case InstructionSet::Baseline:
            return {};
        case InstructionSet::Avx2:
            return splitList(FACET_SHADER_AVX2_FLAGS);
        case InstructionSet::Avx512:
            return splitList(FACET_SHADER_AVX512_FLAGS);
    }
    return {};
}

// FNV-1a, 64 bits, from `seed`: two seeds make the cache's 128-bit key of a source and its settings.
std::uint64_t fnv1a(std::string_view bytes, std::uint64_t seed) {
    std::uint64_t hash = seed;
    for (const char c : bytes) {
        hash ^= static_cast<unsigned char>(c);
        hash *= 0x100000001b3ull;
    }
    return hash;
}

std::string hex(std::uint64_t value) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
    return text;
}

std::string readWhole(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// Size and modification time of a file a shader includes, "" when it is gone.
std::string fileStamp(const fs::path& path) {
    std::error_code error;
    const auto size = fs::file_size(path, error);
    if (error) return "";
    const auto time = fs::last_write_time(path, error);
    if (error) return "";
    return std::to_string(size) + " " + std::to_string(time.time_since_epoch().count());
}

// The files a compiled shader included besides facet's headers and the system's (a make rule from
// -MD), each with its stamp: a change to one compiles the shader again.
std::string includedFileStamps(const fs::path& dependencyFile, const fs::path& source,
                               const std::vector<fs::path>& facetHeaders) {
    std::string rule = readWhole(dependencyFile);
    std::string stamps;
    std::istringstream words(rule);
    std::string word;
    bool afterColon = false;
    while (words >> word) {
        if (!afterColon) {
            afterColon = !word.empty() && word.back() == ':';
            continue;
        }
        if (word == "\\") continue;
        const fs::path file = fs::weakly_canonical(word);
        if (file == fs::weakly_canonical(source) || file.string().starts_with("/usr/")) continue;
        bool facets = false;
        for (const fs::path& folder : facetHeaders)
            facets = facets || inside(file.parent_path(), folder);
        if (!facets) stamps += file.string() + " " + fileStamp(file) + "\n";
    }
    return stamps;
}

bool stampsStillHold(const std::string& stamps) {
    std::istringstream lines(stamps);
    std::string line;
    while (std::getline(lines, line)) {
        const std::size_t cut = line.find(' ');
        if (cut == std::string::npos) continue;
        if (fileStamp(line.substr(0, cut)) != line.substr(cut + 1)) return false;
    }
    return true;
}

// Runs `command`, its output and errors into `log`; returns its exit status (127: not started).
int runCommand(const std::vector<std::string>& command, const fs::path& log) {
    std::vector<char*> argv;
    for (const std::string& word : command)
        argv.push_back(const_cast<char*>(word.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    pid_t child = 0;
    const int started = posix_spawnp(&child, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (started != 0) return 127;
    int status = 0;
    while (::waitpid(child, &status, 0) < 0)
        if (errno != EINTR) return 127;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Loads a module file and checks that it is a shader module built for this facet. A refused module is
// unloaded again, so that a later dlopen of the same path (the cache's module compiled anew) loads the
// new file instead of finding the refused one by its name.
const ShaderModule* openModule(const fs::path& file, const std::string& label) {
    void* handle = ::dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) throw InputError(label + ": the shader module does not load: " + ::dlerror());
    auto refuse = [&](const std::string& why) {
        ::dlclose(handle);
        return InputError(label + ": " + why);
    };
    using Abi = const char* (*)();
    const auto abi = reinterpret_cast<Abi>(::dlsym(handle, "facet_shader_abi"));
    const auto entry = reinterpret_cast<const ShaderModule* (*)()>(::dlsym(handle, "facet_shader_module"));
    if (!abi || !entry)
        throw refuse(
            "not a facet shader module (it exports no facet_shader_abi or facet_shader_module: does the "
            "shader's file end with FACET_SHADER(Name)?)");
    const std::string built = abi();
    if (built != FACET_SHADER_ABI)
        throw refuse("the shader module was built for " + built + ", and this is " + FACET_SHADER_ABI +
                     ": build it again against this facet (or give its .cpp file)");
    return entry();
}

// The compiler's definition that makes a module of `walks` (shaders/shader_module.h).
std::string walksDefinition(unsigned walks) {
    return "-DFACET_SHADER_WALKS=" + std::to_string(walks);
}

// `walks`, with the watched walks of its outputs when this process watches draws.
unsigned walksToCompile(unsigned walks, bool watched) {
    if (!watched) return walks;
    if (walks & (walk::kListsFloatDepth | walk::kListsUnormDepth)) walks |= walk::kWatchedLists;
    if (walks & ~(walk::kListsFloatDepth | walk::kListsUnormDepth | walk::kWatchedLists))
        walks |= walk::kWatched;
    return walks;
}

// The walks named for a message: "watched, multisampled".
std::string describeWalks(unsigned walks) {
    const std::pair<unsigned, const char*> kinds[] = {
        {walk::kWatched | walk::kWatchedLists, "watched (step mode)"},
        {walk::kMultisampleFloatDepth | walk::kMultisampleUnormDepth, "multisampled"},
        {walk::kListsFloatDepth | walk::kListsUnormDepth | walk::kWatchedLists, "exact transparency"},
        {walk::kUnormDepth | walk::kMultisampleUnormDepth | walk::kListsUnormDepth, "unorm depth"},
        {walk::kFloatDepth | walk::kMultisampleFloatDepth | walk::kListsFloatDepth, "float depth"}};
    std::string text;
    for (const auto& [bits, name] : kinds)
        if (walks & bits) text += (text.empty() ? "" : ", ") + std::string(name);
    return text;
}

// Where the cache keeps the module of a source text compiled with some walks: its key (the module's
// inputs but the files it includes, whose stamps follow the key in the key file) and its files.
struct CacheSlot {
    std::string key, name;
    fs::path module, keyFile;
};

CacheSlot cacheSlot(const fs::path& source, const std::string& text, unsigned walks,
                    const std::vector<fs::path>& headers) {
    std::vector<std::string> flags = splitList(FACET_SHADER_FLAGS);
    for (std::string& flag : instructionSetFlags())
        flags.push_back(std::move(flag));
    flags.push_back(walksDefinition(walks));
    CacheSlot slot;
    slot.key = std::string(FACET_SHADER_ABI) + "\n" + FACET_SHADER_COMPILER + "\n";
    for (const std::string& flag : flags)
        slot.key += flag + " ";
    for (const fs::path& folder : headers)
        slot.key += "\n-I" + folder.string();
    // Appended piece by piece: GCC 12 reports a false -Wrestrict on "…" + std::string chains.
    slot.key += '\n';
    slot.key += hex(fnv1a(text, 0xcbf29ce484222325ull));
    slot.key += hex(fnv1a(text, 0x84222325cbf29ce4ull));
    slot.key += '\n';
    slot.name = source.stem().string() + "-" + hex(fnv1a(slot.key, 0xcbf29ce484222325ull)) +
                hex(fnv1a(slot.key, 0x9e3779b97f4a7c15ull));
    const fs::path folder = shaderCacheFolder();
    slot.module = folder / (slot.name + ".so");
    slot.keyFile = folder / (slot.name + ".key");
    return slot;
}

// The cached module of `slot` when there is one whose included files are unchanged, else null. A cached
// module that does not load (damaged: cut short by a full disk, overwritten) is compiled again rather
// than standing in the way until someone empties the cache.
const ShaderModule* cachedModule(const CacheSlot& slot, const std::string& label, bool sayWhy) {
    std::error_code error;
    if (!fs::exists(slot.module, error) || !fs::exists(slot.keyFile, error)) return nullptr;
    const std::string stored = readWhole(slot.keyFile);
    if (!stored.starts_with(slot.key) || !stampsStillHold(stored.substr(slot.key.size()))) return nullptr;
    try {
        return openModule(slot.module, label);
    } catch (const InputError& refused) {
        if (sayWhy) std::cerr << "facet: " << refused.what() << ": compiling it again\n";
        return nullptr;
    }
}

// The compiled module of `source` holding `walks` (pipeline/back_end.h): from the cache, where one of
// these walks or of the larger sets facet compiles (with the watched walks, every walk) is kept, else
// compiled now. `more`, when not empty, says why an already loaded module of it is compiled again.
const ShaderModule* compiledModule(const fs::path& source, const std::string& label, unsigned walks,
                                   const std::string& more) {
    const std::string text = readWhole(source);
    const std::vector<fs::path> headers = headerFolders();
    const CacheSlot own = cacheSlot(source, text, walks, headers);
    const auto anyCached = [&](bool sayWhy) -> const ShaderModule* {
        if (const ShaderModule* found = cachedModule(own, label, sayWhy)) return found;
        for (const unsigned larger : {walksToCompile(walks, true), walk::kAll})
            if (larger != walks)
                if (const ShaderModule* found =
                        cachedModule(cacheSlot(source, text, larger, headers), label, false))
                    return found;
        return nullptr;
    };
    const fs::path folder = shaderCacheFolder();
    std::error_code error;
    if (const ShaderModule* found = anyCached(true)) return found;
    bool found = false;
    for (const fs::path& folder : headers)
        found = found || fs::exists(folder / "shaders" / "user_shader.h", error);
    if (!found)
        throw InputError(
            label + ": compiling a shader needs facet's headers, which are not in " +
            (headers.empty() ? std::string("the program's install folder") : headers.front().string()) +
            " (install them, or build the shader with facet_add_shader of facet's CMake package "
            "and give the .so)");
    fs::create_directories(folder, error);
    if (error)
        throw InputError(label + ": cannot make the shader cache " + folder.string() + ": " +
                         error.message());
    // One run compiles a shader at a time: the others (a job array's tasks started together) wait for
    // it and load its module, instead of each compiling the same. The lock goes with the process, so
    // one killed while compiling holds nobody up; where the file system has no locks, the runs compile
    // side by side, which the names below keep safe.
    const fs::path lockFile = folder / (own.name + ".lock");
    const int lock = ::open(lockFile.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (lock < 0)
        throw InputError(label + ": cannot write in the shader cache " + folder.string() + ": " +
                         std::strerror(errno));
    const struct Unlock {
        int fd;
        ~Unlock() { ::close(fd); }
    } unlock{lock};
    if (::flock(lock, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK) {
        std::cerr << "facet: waiting for another facet compiling " << label << "\n";
        while (::flock(lock, LOCK_EX) != 0 && errno == EINTR) {
        }
    }
    // Another run may have compiled it since the look above.
    if (const ShaderModule* found = anyCached(false)) return found;
    // Written under names of this run's own, then renamed: a run at the same time (another process, or
    // one on another machine or in another container sharing the folder, where process ids repeat) finds
    // either no module or a whole one, and two runs compiling at once each rename a whole module into
    // place, the same module.
    std::string unique = ".";
    unique += std::to_string(::getpid());
    unique += '-';
    unique += hex(std::random_device()());
    unique += ".tmp";
    const fs::path partial = folder / (own.name + unique + ".so");
    const fs::path dependencies = folder / (own.name + unique + ".d");
    const fs::path log = folder / (own.name + unique + ".log");
    // A folder one cannot write in would otherwise surface as the compiler failing to start.
    if (!std::ofstream(log))
        throw InputError(label + ": cannot write in the shader cache " + folder.string() + ": " +
                         std::strerror(errno));
    std::vector<std::string> command = shaderCompileCommand(source, partial, walks);
    command.insert(command.end(), {"-MD", "-MF", dependencies.string()});
    if (more.empty())
        std::cerr << "facet: compiling " << label << " (the first time only: the module is kept in "
                  << folder.string() << ")\n";
    else
        std::cerr << "facet: compiling " << label << " again, for " << more << " draws too (kept in "
                  << folder.string() << ")\n";
    const auto start = std::chrono::steady_clock::now();
    const int status = runCommand(command, log);
    const std::string messages = readWhole(log);
    fs::remove(log, error);
    if (!messages.empty()) std::cerr << messages;
    if (status != 0) {
        fs::remove(partial, error);
        fs::remove(dependencies, error);
        if (status == 127)
            throw InputError(label + ": the compiler " + std::string(FACET_SHADER_COMPILER) +
                             " could not be run: install it (facet compiles shaders with the compiler it was "
                             "built with)");
        throw InputError(label + ": the shader did not compile (the compiler's messages are above)");
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cerr << "facet: compiled " << label << " in " << std::lround(seconds * 10) / 10.0 << " s\n";
    std::ofstream(own.keyFile.string() + unique)
        << own.key << includedFileStamps(dependencies, source, headers);
    fs::remove(dependencies, error);
    fs::rename(partial, own.module, error);
    if (!error) fs::rename(own.keyFile.string() + unique, own.keyFile, error);
    if (error)
        throw InputError(label + ": cannot keep the compiled shader in " + folder.string() + ": " +
                         error.message());
    return openModule(own.module, label);
}

// Reads a uniform's numbers into the module's form, or says why they do not fit its type.
std::array<float, 4> checkedValue(const UniformInfo& info, const UniformValue& value,
                                  const std::string& shader) {
    const int count = componentCount(info.type);
    const std::string declared =
        shader + " declares " + std::string(info.name) + " as " + std::string(nameOf(info.type));
    if (static_cast<int>(value.numbers.size()) != count || (info.type == UniformType::Bool) != value.isBool) {
        std::string wanted = info.type == UniformType::Bool ? "true or false"
                             : count == 1                   ? "one number"
                                                            : std::to_string(count) + " numbers";
        throw InputError(value.origin + ": " + declared + ": give " + wanted);
    }
    std::array<float, 4> result{};
    for (int k = 0; k < count; ++k) {
        const double number = value.numbers[static_cast<std::size_t>(k)];
        if (!std::isfinite(number) || std::fabs(number) > 3.0e38)
            throw InputError(value.origin + ": " + declared + ": " + std::to_string(number) +
                             " is not a finite number");
        if (info.type == UniformType::Int && (number != std::floor(number) || std::fabs(number) > 16777216.0))
            throw InputError(value.origin + ": " + declared +
                             ": give a whole number (at most 16777216 in size)");
        result[static_cast<std::size_t>(k)] = static_cast<float>(number);
    }
    return result;
}

struct Registry {
    std::mutex mutex;
    std::map<fs::path, const ShaderModule*> loaded;  // by canonical path: the one holding the most walks
    bool watched = false;                            // compileForWatchedDraws()
    bool every = false;                              // compileEveryWalk()
};

Registry& registry() {
    static Registry r;
    return r;
}

}  // namespace

fs::path shaderCacheFolder() {
    if (const char* cache = std::getenv("FACET_SHADER_CACHE"); cache && *cache) return cache;
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
        return fs::path(xdg) / "facet" / "shaders";
    if (const char* home = std::getenv("HOME"); home && *home)
        return fs::path(home) / ".cache" / "facet" / "shaders";
    return fs::temp_directory_path() / ("facet-shaders-" + std::to_string(::getuid()));
}

std::vector<std::string> shaderCompileCommand(const fs::path& source, const fs::path& output,
                                              unsigned walks) {
    std::vector<std::string> command{FACET_SHADER_COMPILER};
    for (const std::string& flag : splitList(FACET_SHADER_FLAGS))
        command.push_back(flag);
    for (std::string& flag : instructionSetFlags())
        command.push_back(std::move(flag));
    command.push_back(walksDefinition(walks));
    // A shared library whose only visible symbols are the two entry points: the pipeline's functions
    // it calls are facet's own (the program exports them).
    command.insert(command.end(), {"-fPIC", "-shared", "-fvisibility=hidden", "-fvisibility-inlines-hidden"});
    for (const fs::path& folder : headerFolders())
        command.push_back("-I" + folder.string());
    command.insert(command.end(), {"-o", output.string(), source.string()});
    return command;
}

namespace {

// The registry's module of `canonical` holding `walks`: the loaded one if it holds them; else, the first
// time, the source compiled with them (and the watched walks, once compileForWatchedDraws was called;
// every walk, once compileEveryWalk was); else compiled with every walk. A .so is loaded as it is
// (facet_add_shader builds every walk); one built with fewer walks than a draw needs is refused.
const ShaderModule* moduleHolding(Registry& r, const fs::path& source, const fs::path& canonical,
                                  const std::string& label, unsigned walks) {
    const auto found = r.loaded.find(canonical);
    if (found != r.loaded.end() && (found->second->walks & walks) == walks) return found->second;
    const ShaderModule* module = nullptr;
    if (source.extension() == ".so") {
        module = found != r.loaded.end() ? found->second : openModule(fs::absolute(source), label);
        if ((module->walks & walks) != walks)
            throw InputError(label + ": the module was built without the code for " +
                             describeWalks(walks & ~module->walks) +
                             " draws: build it again without FACET_SHADER_WALKS (or give its .cpp file)");
    } else if (found != r.loaded.end()) {
        // A second kind of draw in one process (a trade, a benchmark of several settings, a walk): every
        // walk at once, so that a third costs nothing.
        module = compiledModule(source, label, walk::kAll, describeWalks(walks & ~found->second->walks));
    } else {
        module = compiledModule(source, label, r.every ? walk::kAll : walksToCompile(walks, r.watched), "");
    }
    r.loaded.insert_or_assign(canonical, module);
    return module;
}

}  // namespace

UserShader loadUserShader(const fs::path& source, unsigned walks) {
    const std::string label = source.string();
    std::error_code error;
    if (!fs::is_regular_file(source, error))
        throw InputError(label + ": no such shader file" +
                         (fs::exists(source, error) ? " (not a regular file)" : ""));
    const fs::path canonical = fs::weakly_canonical(source, error);
    Registry& r = registry();
    const std::lock_guard lock(r.mutex);
    return {moduleHolding(r, source, canonical, label, walks), label, source, canonical};
}

const ShaderModule& userShaderFor(const UserShader& shader, unsigned walk) {
    if (shader.module->walks & walk) return *shader.module;
    Registry& r = registry();
    const std::lock_guard lock(r.mutex);
    return *moduleHolding(r, shader.source, shader.canonical, shader.label, walk);
}

void compileForWatchedDraws() {
    Registry& r = registry();
    const std::lock_guard lock(r.mutex);
    r.watched = true;
}

void compileEveryWalk() {
    Registry& r = registry();
    const std::lock_guard lock(r.mutex);
    r.every = true;
}

bool declaresUniform(const UserShader& shader, std::string_view name) {
    for (const UniformInfo& info : shader.module->uniforms)
        if (info.name == name) return true;
    return false;
}

std::string uniformValueText(UniformType type, const std::array<float, 4>& value) {
    auto number = [](float v) {
        std::ostringstream text;
        text << v;
        return text.str();
    };
    if (type == UniformType::Bool) return value[0] != 0 ? "true" : "false";
    const int count = componentCount(type);
    if (count == 1) return number(value[0]);
    std::string text = "(";
    for (int k = 0; k < count; ++k)
        text += (k ? ", " : "") + number(value[static_cast<std::size_t>(k)]);
    return text + ")";
}

std::string describeUniforms(const ShaderModule& module) {
    if (module.uniforms.empty()) return "no uniforms of its own";
    std::string text;
    for (const UniformInfo& info : module.uniforms) {
        if (!text.empty()) text += ", ";
        text += std::string(info.name) + " (" + std::string(nameOf(info.type)) + ", " +
                uniformValueText(info.type, info.defaults) + ")";
    }
    return text;
}

std::vector<UniformSetting> uniformSettings(const UserShader& shader, std::span<const UniformValue> values,
                                            bool onlyDeclared) {
    std::vector<UniformSetting> settings;
    for (const UniformValue& value : values) {
        std::uint32_t index = 0;
        const UniformInfo* info = nullptr;
        for (const UniformInfo& candidate : shader.module->uniforms) {
            if (candidate.name == value.name) {
                info = &candidate;
                break;
            }
            ++index;
        }
        if (!info) {
            if (onlyDeclared) continue;
            throw InputError(value.origin + ": " + shader.label + " declares no uniform " +
                             inQuotes(value.name) + " (it has: " + describeUniforms(*shader.module) + ")");
        }
        settings.push_back({index, checkedValue(*info, value, shader.label)});
    }
    return settings;
}

}  // namespace facet
