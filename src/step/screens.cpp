#include "step/screens.h"

#include <algorithm>
#include <sstream>

namespace facet::step {

std::string wrapText(const std::string& text, std::size_t width, std::size_t indent) {
    auto columns = [](const std::string& s) {
        std::size_t n = 0;
        for (unsigned char c : s)
            n += (c & 0xC0) != 0x80;  // UTF-8 continuation bytes take no column
        return n;
    };
    const std::size_t lead = std::min(text.find_first_not_of(' '), text.size());
    std::string out, line(lead, ' ');
    bool lineHasWord = false;
    std::istringstream words(text);
    std::string word;
    while (words >> word) {
        if (lineHasWord && columns(line) + 1 + columns(word) > width) {
            out += line + "\n";
            line = std::string(indent, ' ');
            lineHasWord = false;
        }
        if (lineHasWord) line += " ";
        line += word;
        lineHasWord = true;
    }
    return out + line + "\n";
}

std::string printWalk(const Walk& walk) {
    std::ostringstream out;
    out << "Pixel (" << walk.x << ", " << walk.y << ")";
    if (walk.triangle) out << ", triangle " << walk.triangle->number;
    out << "\n" << wrapText("Verdict: " + walk.verdict, 80, 2);
    for (std::size_t k = 0; k < walk.screens.size(); ++k)
        out << "\n" << printScreen(walk, k);
    return out.str();
}

std::string printScreen(const Walk& walk, std::size_t index) {
    const Screen& screen = walk.screens.at(index);
    const std::string rule(80, '=');
    return rule + "\n" + std::to_string(index + 1) + ". " + screen.title + "\n" + rule + "\n" + screen.text;
}

}  // namespace facet::step
