// What the fuzz targets share: one input cut into the files it stands for, written to a temporary
// folder of this process, because the loaders under test read files by path.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <unistd.h>

namespace facet::fuzz {

// The input cut at its NUL bytes: part 0 up to the first NUL, part 1 up to the second, and so on, at
// most `maxParts` parts (the last one keeps any further NULs). An input without a NUL is one part, so
// the files after it are missing: a case the loaders must handle too.
inline std::vector<std::string_view> splitAtNul(const std::uint8_t* data, std::size_t size,
                                                std::size_t maxParts) {
    std::vector<std::string_view> parts;
    std::string_view rest(reinterpret_cast<const char*>(data), size);
    while (parts.size() + 1 < maxParts) {
        const std::size_t nul = rest.find('\0');
        if (nul == std::string_view::npos) break;
        parts.push_back(rest.substr(0, nul));
        rest.remove_prefix(nul + 1);
    }
    parts.push_back(rest);
    return parts;
}

// A folder of this process's own (several fuzzers may run at once), in memory where /dev/shm exists,
// emptied of the files the target wrote and removed when the process ends normally.
class ScratchFolder {
  public:
    ScratchFolder() {
        const char* tmpdir = std::getenv("TMPDIR");
        const std::filesystem::path base = tmpdir && *tmpdir                           ? tmpdir
                                           : std::filesystem::is_directory("/dev/shm") ? "/dev/shm"
                                                                                       : "/tmp";
        std::string pattern = (base / "facet-fuzz-XXXXXX").string();
        if (::mkdtemp(pattern.data()) == nullptr) {
            std::perror(("facet fuzz: cannot create a folder like " + pattern).c_str());
            std::abort();
        }
        path_ = pattern;
    }
    ~ScratchFolder() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    ScratchFolder(const ScratchFolder&) = delete;
    ScratchFolder& operator=(const ScratchFolder&) = delete;

    const std::filesystem::path& path() const { return path_; }

    // Writes `name` with exactly `bytes`, or aborts: a fuzzer that cannot write its input tests nothing.
    std::filesystem::path write(const std::string& name, std::string_view bytes) const {
        const std::filesystem::path file = path_ / name;
        std::FILE* out = std::fopen(file.c_str(), "wb");
        if (out == nullptr || std::fwrite(bytes.data(), 1, bytes.size(), out) != bytes.size() ||
            std::fclose(out) != 0) {
            std::perror(("facet fuzz: cannot write " + file.string()).c_str());
            std::abort();
        }
        return file;
    }

    // Removes `name` if it is there, so that a file of the previous input never stands in for a
    // missing one.
    void remove(const std::string& name) const {
        std::error_code ignored;
        std::filesystem::remove(path_ / name, ignored);
    }

  private:
    std::filesystem::path path_;
};

// The fixed names the inputs' parts are written under. Seeds (make-corpus.sh) and the dictionary use
// them: an OBJ part names its MTL as `mtllib model.mtl`, a scene names its model "model.obj".
inline constexpr const char* kObjName = "model.obj";
inline constexpr const char* kMtlName = "model.mtl";
inline constexpr const char* kSceneName = "scene.json";

}  // namespace facet::fuzz
