#include "io/obj_text.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
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

namespace {

bool isDigit(char c) {
    return c >= '0' && c <= '9';
}

// The length of the number tinyobjloader's tryParseDouble reads at the start of `s`, or 0 when it
// reads none (it then leaves the default, 0) or the prefix holds no digit ("." and "-." it reads as 0).
std::size_t numberPrefix(std::string_view s) {
    std::size_t i = 0, digits = 0;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    for (; i < s.size() && isDigit(s[i]); ++i)
        ++digits;
    if (i < s.size() && s[i] == '.') {
        for (++i; i < s.size() && isDigit(s[i]); ++i)
            ++digits;
    }
    if (digits == 0) return 0;
    if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
        std::size_t exponent = i + 1;
        if (exponent < s.size() && (s[exponent] == '+' || s[exponent] == '-')) ++exponent;
        std::size_t exponentDigits = 0;
        for (; exponent < s.size() && isDigit(s[exponent]); ++exponent)
            ++exponentDigits;
        if (exponentDigits == 0) return 0;  // tinyobjloader: "Empty E is not allowed", no number
        i = exponent;
    }
    return i;
}

}  // namespace

NumberRead readNumber(std::string_view token) {
    NumberRead read;
    read.length = numberPrefix(token);
    if (read.length == 0) {
        // "nan", "-inf", "infinity": strtod's spellings of what a float holds but a model cannot use.
        std::string_view word = token;
        if (word.size() > 1 && word[0] == '+') word.remove_prefix(1);
        double value = 0.0;
        const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
        if (error == std::errc() && end == word.data() + word.size() && !std::isfinite(value))
            read.check = NumberCheck::kNotFinite;
        return read;  // else kNotANumber
    }
    std::string_view digits = token.substr(0, read.length);
    if (digits[0] == '+') digits.remove_prefix(1);  // from_chars takes no '+'
    double value = 0.0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (error == std::errc::invalid_argument || end != digits.data() + digits.size()) {
        return read;  // not expected: the prefix has strtod's form
    }
    if (error == std::errc::result_out_of_range) {
        // Out of double range: overflow is not finite, underflow is a fine zero.
        value = std::strtod(std::string(digits).c_str(), nullptr);
        if (std::isinf(value)) {
            read.check = NumberCheck::kNotFinite;
            return read;
        }
    }
    read.value = value;
    if (!std::isfinite(value) || std::abs(value) > double(std::numeric_limits<float>::max())) {
        read.check = NumberCheck::kNotFinite;
        return read;
    }
    const std::string_view rest = token.substr(read.length);
    if (rest.empty()) {
        read.check = NumberCheck::kFinite;
    } else if (rest[0] == '#') {
        read.check = NumberCheck::kNotFinite;  // MSVC prints NaN and Inf as 1.#IND, 1.#QNAN, 1.#INF
    } else if (rest.size() > 1 && rest[0] == ',' && isDigit(rest[1])) {
        read.check = NumberCheck::kDecimalComma;
    } else {
        read.check = NumberCheck::kStrayCharacters;
    }
    return read;
}

float objCoordinate(std::string_view token) {
    // The same operations in the same order as tinyobjloader's tryParseDouble (the build has
    // -ffp-contract=off: no multiply-add is fused), for its grammar [+-]digits[.digits][(e|E)[+-]digits].
    const char* at = token.data();
    const char* const end = at + token.size();
    char sign = '+';
    if (at != end && (*at == '+' || *at == '-')) sign = *at++;
    double mantissa = 0.0;
    for (; at != end && isDigit(*at); ++at) {
        mantissa *= 10;
        mantissa += static_cast<int>(*at - '0');
    }
    if (at != end && *at == '.') {
        static constexpr double kPowers[] = {1.0, 0.1, 0.01, 0.001, 0.0001, 0.00001, 0.000001, 0.0000001};
        constexpr int kPowerCount = sizeof kPowers / sizeof kPowers[0];
        int read = 1;
        for (++at; at != end && isDigit(*at); ++at, ++read)
            mantissa +=
                static_cast<int>(*at - '0') * (read < kPowerCount ? kPowers[read] : std::pow(10.0, -read));
    }
    int exponent = 0;
    if (at != end && (*at == 'e' || *at == 'E')) {
        ++at;
        char exponentSign = '+';
        if (at != end && (*at == '+' || *at == '-')) exponentSign = *at++;
        for (; at != end && isDigit(*at); ++at) {
            if (exponent > 2147483647 / 10) return 0.0f;  // tinyobjloader gives up: the default, 0
            exponent *= 10;
            exponent += static_cast<int>(*at - '0');
        }
        exponent *= exponentSign == '+' ? 1 : -1;
    }
    const double value = (sign == '+' ? 1 : -1) *
                         (exponent ? std::ldexp(mantissa * std::pow(5.0, exponent), exponent) : mantissa);
    return static_cast<float>(value);
}

std::string numberText(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", value);
    return text;
}

std::string strayNumberWarning(const std::string& file, std::size_t line, std::string_view token,
                               double value, std::size_t count) {
    std::string what =
        inQuotes(token) + " read as " + numberText(value) + " (stray characters after the number";
    if (count > 1)
        what += "; " + std::to_string(count) + " numbers in this file have them, the first is here";
    what += ")";
    return located(file, line, what);
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
