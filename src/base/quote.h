// Text from an input file, made safe to show in a one-line message: every value or key a message
// quotes goes through here, so a 50 MB string cannot become a 50 MB message and a raw byte such as
// 0xFF or an escape sequence never reaches the terminal.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace facet {

// Enough to recognise a value; the rest is cut and "…" appended.
inline constexpr std::size_t kMaxQuotedCharacters = 40;

// `text` cut after `maxCharacters` characters (followed by "…" when cut), with what a terminal would
// not show as written escaped: \n \r \t, other control characters and bytes that are not UTF-8 as
// \xHH (0xFF stays "\xFF"), and a backslash, or the `quote` character when given, behind a backslash.
std::string printable(std::string_view text, std::size_t maxCharacters = kMaxQuotedCharacters,
                      char quote = '\0');

// printable(text) between two `quote` characters: "camera.fvoy", or 'nan' in the OBJ reader's messages.
std::string inQuotes(std::string_view text, char quote = '"');

// A file path the program resolved, shown whole as far as any real path goes (PATH_MAX is 4096),
// escaped like every quoted value.
std::string quotedPath(std::string_view path);

}  // namespace facet
