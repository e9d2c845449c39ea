#include "io/obj_text.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <system_error>

#include "base/errors.h"
#include "base/quote.h"

namespace facet::obj {

namespace fs = std::filesystem;

std::string located(const std::string& file, std::size_t line, std::string_view what) {
    std::string message = file;
    if (line != kNoLine) {
        message += ':';
        message += std::to_string(line);
    }
    message += ": ";
    message += what;
    return message;
}

[[noreturn]] void fail(const std::string& file, std::size_t line, std::string_view what) {
    throw InputError(located(file, line, what));
}

std::string inSingleQuotes(std::string_view s) {
    return inQuotes(s, '\'');
}

std::string pathInSingleQuotes(const fs::path& path) {
    std::string quoted(1, '\'');
    quoted += printable(path.string(), 4096, '\'');
    quoted += '\'';
    return quoted;
}

std::string readTextFile(const fs::path& path, std::string& text) {
    std::error_code error;
    const fs::file_status status = fs::status(path, error);
    if (status.type() == fs::file_type::not_found) return "no such file";
    if (error) return "cannot open (" + error.message() + ")";
    if (fs::is_directory(status)) return "is a directory, not a file";
    // FIFOs and devices could block or never end.
    if (!fs::is_regular_file(status)) return "is not a regular file";

    std::ifstream in(path, std::ios::binary);
    if (!in) return std::string("cannot open (") + std::strerror(errno) + ")";
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    in.seekg(0, std::ios::beg);
    if (size < 0 || !in) return std::string("cannot read (") + std::strerror(errno) + ")";
    text.assign(static_cast<std::size_t>(size), '\0');
    in.read(text.data(), size);
    if (in.gcount() != size) return std::string("cannot read (") + std::strerror(errno) + ")";
    return "";
}

NumberCheck checkNumber(std::string_view token) {
    std::string_view digits = token;
    if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-' && digits[1] != '+')
        digits.remove_prefix(1);
    double value = 0.0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (end != digits.data() + digits.size() || error == std::errc::invalid_argument) {
        // MSVC prints NaN and Inf as 1.#IND, 1.#QNAN, 1.#INF.
        if (error != std::errc::invalid_argument && *end == '#') return NumberCheck::kNotFinite;
        return NumberCheck::kNotANumber;
    }
    if (error == std::errc::result_out_of_range) {
        // Out of double range: overflow is not finite, underflow is a fine zero.
        const double rounded = std::strtod(std::string(digits).c_str(), nullptr);
        return std::isinf(rounded) ? NumberCheck::kNotFinite : NumberCheck::kFinite;
    }
    if (!std::isfinite(value) || std::abs(value) > double(std::numeric_limits<float>::max())) {
        return NumberCheck::kNotFinite;
    }
    return NumberCheck::kFinite;
}

IndexParse parseIndex(std::string_view token, long long& index) {
    if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), index);
    if (token.empty() || end != token.data() + token.size() || error == std::errc::invalid_argument) {
        return IndexParse::kMalformed;
    }
    if (error == std::errc::result_out_of_range) return IndexParse::kTooLarge;
    return IndexParse::kOk;
}

}  // namespace facet::obj
