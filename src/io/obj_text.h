// What the OBJ pre-scan and the MTL reader share: "file:line: what" messages, reading a file whole,
// splitting a statement into tokens, and checking numbers and indices the way tinyobjloader reads them.
// Internal to the OBJ importer.
#pragma once

#include <cstddef>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>

namespace facet::obj {

constexpr std::size_t kNoLine = 0;

// "file:line: what", or "file: what" for kNoLine.
std::string located(const std::string& file, std::size_t line, std::string_view what);
// Throws InputError(located(file, line, what)).
[[noreturn]] void fail(const std::string& file, std::size_t line, std::string_view what);

std::string inSingleQuotes(std::string_view s);
// A path the importer resolved: shown whole (up to PATH_MAX), escaped like every quoted value.
std::string pathInSingleQuotes(const std::filesystem::path& path);

// Why a file cannot be read, or "" when `path` is a readable regular file; `text` gets its bytes.
// Every filesystem call takes an error_code: a filesystem_error must never escape as a crash.
std::string readTextFile(const std::filesystem::path& path, std::string& text);

// Where the line starting at `pos` ends: its first '\r' or '\n', or text.size(). Two memchr scans
// (vectorised) rather than find_first_of("\r\n"), which tests each byte against the set by a call.
inline std::size_t lineEnd(std::string_view text, std::size_t pos) {
    if (pos >= text.size()) return text.size();
    const char* begin = text.data() + pos;
    const std::size_t length = text.size() - pos;
    const void* newline = std::memchr(begin, '\n', length);
    const std::size_t toNewline =
        newline ? static_cast<std::size_t>(static_cast<const char*>(newline) - begin) : length;
    const void* carriage = std::memchr(begin, '\r', toNewline);
    return pos +
           (carriage ? static_cast<std::size_t>(static_cast<const char*>(carriage) - begin) : toNewline);
}

inline bool isBlank(char c) {
    return c == ' ' || c == '\t';
}

// Splits on blanks, like tinyobjloader's strspn/strcspn(" \t").
class Tokens {
  public:
    explicit Tokens(std::string_view text) : rest_(text) {}
    bool next(std::string_view& token) {
        std::size_t begin = 0;
        while (begin < rest_.size() && isBlank(rest_[begin]))
            ++begin;
        if (begin == rest_.size()) return false;
        std::size_t end = begin;
        while (end < rest_.size() && !isBlank(rest_[end]))
            ++end;
        token = rest_.substr(begin, end - begin);
        rest_.remove_prefix(end);
        return true;
    }

  private:
    std::string_view rest_;
};

enum class NumberCheck {
    kFinite,           // the whole token is a number a float holds
    kStrayCharacters,  // such a number followed by other characters ("0.0000c", "1.5,", "2.0)")
    kDecimalComma,     // a number followed by a comma and a digit ("2,5"): a locale's decimal comma
    kNotANumber,       // no number at its start ("abc", "nan", "", "1e")
    kNotFinite         // beyond float range or an MSVC NaN/Inf ("1e39", "1.#IND")
};

struct NumberRead {
    NumberCheck check = NumberCheck::kNotANumber;
    double value = 0.0;      // the number read, for kFinite and kStrayCharacters (and kDecimalComma)
    std::size_t length = 0;  // the characters of `token` it was read from
};

// Reads a number the way tinyobjloader's tryParseDouble does, which is how OBJ and MTL readers
// generally read: the longest prefix of the form [+-](digits[.digits*]|.digits*)[(e|E)[+-]digits],
// whatever follows it ("0.0000c" is 0, as in tinyobjloader and Blender); an exponent without digits
// ("1e", "1ex") makes tinyobjloader read no number at all, and so does it here. Unlike tinyobjloader,
// which reads "nan" and "inf" as 0 and 1e39 as inf, a prefix must hold a digit and a float must hold
// its value, and a decimal comma is told apart from a stray character.
NumberRead readNumber(std::string_view token);

// The float the OBJ's `token` stands for, computed as tinyobjloader's tryParseDouble computes it (the
// prefix readNumber reads: digits accumulated in a double, fraction digits scaled by 10^-k, then
// ldexp(m * 5^e, e), rounded to float), so that a mesh's attributes keep the bytes every earlier
// release gave them: a correctly rounded reading (from_chars) differs from it in the last float bit for
// some numbers with many digits. Only for a token readNumber found kFinite or kStrayCharacters.
float objCoordinate(std::string_view token);

// The number read from `token` as it is shown in messages: "0", "1.5", "-2.5e-07" (up to 9 digits).
std::string numberText(double value);

// The one warning for the numbers of a file with stray characters after them: the first, at its line,
// and how many there are, e.g. `car.mtl:12: "0.0000c" read as 0 (stray characters after the number)`.
std::string strayNumberWarning(const std::string& file, std::size_t line, std::string_view token,
                               double value, std::size_t count);

enum class IndexParse { kOk, kMalformed, kTooLarge };

// An index as tinyobjloader reads it: a whole number, a leading '+' allowed.
IndexParse parseIndex(std::string_view token, long long& index);

}  // namespace facet::obj
