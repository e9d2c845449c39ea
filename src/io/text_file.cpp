#include "io/text_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include <unistd.h>

#include "base/errors.h"

namespace facet {

void checkTextDestination(const std::filesystem::path& path) {
    namespace fs = std::filesystem;
    const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::error_code error;
    if (path.empty()) throw InputError("no file name given");
    if (!fs::is_directory(folder, error))
        throw InputError(path.string() + ": cannot write: the folder " + folder.string() + " does not exist");
    if (fs::is_directory(path, error)) throw InputError(path.string() + ": cannot write: it is a folder");
}

void writeTextFile(const std::filesystem::path& path, std::string_view text) {
    namespace fs = std::filesystem;
    checkTextDestination(path);
    const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::string tempName = ".";  // appended piece by piece: GCC 12 warns falsely on one long sum (-Wrestrict)
    tempName += path.filename().string();
    tempName += ".tmp-";
    tempName += std::to_string(::getpid());
    const fs::path temp = folder / tempName;
    std::FILE* file = std::fopen(temp.c_str(), "wb");
    if (!file) throw InputError(path.string() + ": cannot write: " + std::strerror(errno));
    const bool written = std::fwrite(text.data(), 1, text.size(), file) == text.size();
    const int savedErrno = errno;
    const bool closed = std::fclose(file) == 0;
    if (!written || !closed) {
        ::unlink(temp.c_str());
        throw InputError(path.string() + ": cannot write: " + std::strerror(written ? errno : savedErrno));
    }
    if (std::rename(temp.c_str(), path.c_str()) != 0) {
        const int renameErrno = errno;
        ::unlink(temp.c_str());
        throw InputError(path.string() + ": cannot write: " + std::strerror(renameErrno));
    }
}

}  // namespace facet
