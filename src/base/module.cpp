#include "base/module.h"

#include <dlfcn.h>
#include <unistd.h>

#include <climits>

#include "base/errors.h"

// Set by src/base/CMakeLists.txt from the install layout and the build folder.
#if !defined(FACET_MODULE_FOLDER_FROM_PROGRAM) || !defined(FACET_BUILD_TREE)
#error "FACET_MODULE_FOLDER_FROM_PROGRAM and FACET_BUILD_TREE are set by src/base/CMakeLists.txt"
#endif

namespace facet {

std::filesystem::path programFolder() {
    char path[PATH_MAX];
    const ssize_t length = ::readlink("/proc/self/exe", path, sizeof path - 1);
    if (length <= 0) return {};
    path[length] = '\0';
    return std::filesystem::path(path).parent_path();
}

bool inside(const std::filesystem::path& folder, const std::filesystem::path& tree) {
    if (folder.empty() || tree.empty()) return false;
    std::error_code error;
    const std::filesystem::path f = std::filesystem::weakly_canonical(folder, error);
    if (error) return false;
    const std::filesystem::path t = std::filesystem::weakly_canonical(tree, error);
    if (error) return false;
    const std::filesystem::path relative = f.lexically_relative(t);
    return !relative.empty() && *relative.begin() != "..";
}

bool programInBuildTree() {
    return inside(programFolder(), FACET_BUILD_TREE);
}

std::vector<std::filesystem::path> moduleCandidates(const std::filesystem::path& programFolder,
                                                    const std::filesystem::path& moduleFolder,
                                                    const std::filesystem::path& buildTree,
                                                    const char* fileName, const char* buildPath) {
    std::vector<std::filesystem::path> candidates;
    if (!programFolder.empty()) {
        candidates.push_back(programFolder / fileName);
        candidates.push_back((programFolder / moduleFolder / fileName).lexically_normal());
    }
    if (inside(programFolder, buildTree) && buildPath != nullptr && *buildPath != '\0')
        candidates.emplace_back(buildPath);
    return candidates;
}

void* loadModuleEntry(const char* fileName, const char* buildPath, const char* entry,
                      const std::string& neededFor) {
    const std::vector<std::filesystem::path> candidates = moduleCandidates(
        programFolder(), FACET_MODULE_FOLDER_FROM_PROGRAM, FACET_BUILD_TREE, fileName, buildPath);
    std::string reasons;
    for (const std::filesystem::path& candidate : candidates) {
        std::error_code error;
        if (!std::filesystem::exists(candidate, error)) continue;
        // Never closed: the libraries behind a module may keep threads and caches for the process's life.
        void* module = ::dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (module == nullptr) {
            reasons += reasons.empty() ? "" : "; ";
            reasons += ::dlerror();
            continue;
        }
        if (void* address = ::dlsym(module, entry)) return address;
        reasons += reasons.empty() ? "" : "; ";
        reasons += candidate.string() + " has no " + entry;
    }
    std::string message = neededFor + ", and " + fileName;
    if (reasons.empty()) {
        // Every place looked, so that the message is right for a facet in its build folder, an installed
        // one and a copied one alike.
        message += " was not found (looked for ";
        for (std::size_t k = 0; k < candidates.size(); ++k)
            message += (k == 0 ? "" : k + 1 == candidates.size() ? " and " : ", ") + candidates[k].string();
        message +=
            candidates.empty() ? "nothing: the program's folder is unknown)" : "; copy it to one of them)";
    } else {
        message += " could not be loaded: " + reasons;
    }
    throw InputError(message);
}

}  // namespace facet
