#include "base/quote.h"

#include <cstdint>

namespace facet {
namespace {

// The length of the well-formed UTF-8 sequence starting `text`, or 0 when the bytes there are not
// one (a stray continuation byte, a truncated sequence, an overlong form, a surrogate, beyond U+10FFFF).
// `codePoint` gets the character.
std::size_t utf8Sequence(std::string_view text, std::uint32_t& codePoint) {
    const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
    const unsigned char lead = byte(0);
    std::size_t length = 0;
    std::uint32_t lowest = 0;
    if (lead < 0x80) {
        codePoint = lead;
        return 1;
    } else if (lead >= 0xC2 && lead <= 0xDF) {
        length = 2, lowest = 0x80, codePoint = lead & 0x1F;
    } else if (lead >= 0xE0 && lead <= 0xEF) {
        length = 3, lowest = 0x800, codePoint = lead & 0x0F;
    } else if (lead >= 0xF0 && lead <= 0xF4) {
        length = 4, lowest = 0x10000, codePoint = lead & 0x07;
    } else {
        return 0;
    }
    if (text.size() < length) return 0;
    for (std::size_t i = 1; i < length; ++i) {
        if ((byte(i) & 0xC0) != 0x80) return 0;
        codePoint = (codePoint << 6) | (byte(i) & 0x3F);
    }
    if (codePoint < lowest || codePoint > 0x10FFFF || (codePoint >= 0xD800 && codePoint <= 0xDFFF)) return 0;
    return length;
}

// Characters that are valid UTF-8 but would move the cursor, break the line or reorder the text
// around them: C1 controls, the line and paragraph separators, bidirectional controls, the BOM.
bool invisible(std::uint32_t c) {
    return (c >= 0x80 && c <= 0x9F) || c == 0x200E || c == 0x200F || (c >= 0x2028 && c <= 0x202E) ||
           (c >= 0x2066 && c <= 0x2069) || c == 0xFEFF;
}

void appendHex(std::string& out, unsigned char byte) {
    constexpr char kDigits[] = "0123456789ABCDEF";
    out += "\\x";
    out += kDigits[byte >> 4];
    out += kDigits[byte & 0xF];
}

}  // namespace

std::string printable(std::string_view text, std::size_t maxCharacters, char quote) {
    std::string out;
    std::size_t characters = 0;
    std::size_t i = 0;
    while (i < text.size()) {
        if (characters == maxCharacters) {
            out += "…";
            break;
        }
        std::uint32_t c = 0;
        const std::size_t length = utf8Sequence(text.substr(i), c);
        if (length == 0) {
            appendHex(out, static_cast<unsigned char>(text[i]));
            ++i;
        } else if (c == '\n') {
            out += "\\n", ++i;
        } else if (c == '\r') {
            out += "\\r", ++i;
        } else if (c == '\t') {
            out += "\\t", ++i;
        } else if (c == '\\' || (quote != '\0' && c == static_cast<unsigned char>(quote))) {
            out += '\\';
            out += text[i++];
        } else if (c < 0x20 || c == 0x7F || invisible(c)) {
            for (std::size_t k = 0; k < length; ++k)
                appendHex(out, static_cast<unsigned char>(text[i + k]));
            i += length;
        } else {
            out.append(text.substr(i, length));
            i += length;
        }
        ++characters;
    }
    return out;
}

std::string inQuotes(std::string_view text, char quote) {
    return quote + printable(text, kMaxQuotedCharacters, quote) + quote;
}

std::string quotedPath(std::string_view path) {
    constexpr std::size_t kMaxPathCharacters = 4096;
    return '"' + printable(path, kMaxPathCharacters, '"') + '"';
}

}  // namespace facet
