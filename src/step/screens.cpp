#include "step/screens.h"

#include <algorithm>
#include <sstream>

namespace facet::step {

std::size_t columnsOf(std::string_view text) {
    std::size_t n = 0;
    for (unsigned char c : text)
        n += (c & 0xC0) != 0x80;  // UTF-8 continuation bytes take no column
    return n;
}

std::string wrapText(const std::string& text, std::size_t width, std::size_t indent) {
    const auto columns = [](const std::string& s) { return columnsOf(s); };
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

std::vector<std::string_view> linesOf(std::string_view text) {
    std::vector<std::string_view> lines;
    while (!text.empty()) {
        const std::size_t end = text.find('\n');
        lines.push_back(text.substr(0, end));
        text = end == std::string_view::npos ? std::string_view() : text.substr(end + 1);
    }
    return lines;
}

std::vector<std::string> ownedLinesOf(std::string_view text) {
    const std::vector<std::string_view> lines = linesOf(text);
    return {lines.begin(), lines.end()};
}

std::vector<std::string> linesTooWide(const Walk& walk) {
    std::vector<std::string> wide;
    for (const Screen& screen : walk.screens) {
        if (columnsOf(screen.title) > kTitleColumns) wide.push_back(screen.id + " (title): " + screen.title);
        for (std::string_view line : linesOf(screen.text))
            if (columnsOf(line) > kScreenColumns) wide.push_back(screen.id + ": " + std::string(line));
    }
    return wide;
}

void fitToColumns(Walk& walk) {
    for (Screen& screen : walk.screens) {
        std::string text;
        if (columnsOf(screen.title) > kTitleColumns) {
            // The whole title opens the text; the title keeps the words that fit.
            walk.linesWrappedToFit.push_back(screen.id + " (title): " + screen.title);
            text = wrapText(screen.title, kScreenColumns, 2) + "\n";
            std::string shortened;
            std::istringstream words(screen.title);
            for (std::string word; words >> word;) {
                if (columnsOf(shortened) + 1 + columnsOf(word) + 2 > kTitleColumns) break;
                shortened += (shortened.empty() ? "" : " ") + word;
            }
            screen.title = shortened + " …";
        }
        for (std::string_view line : linesOf(screen.text)) {
            if (columnsOf(line) <= kScreenColumns) {
                text.append(line) += '\n';
                continue;
            }
            walk.linesWrappedToFit.push_back(screen.id + ": " + std::string(line));
            const std::size_t lead = std::min(line.find_first_not_of(' '), line.size());
            text += wrapText(std::string(line), kScreenColumns, lead + 2);
        }
        screen.text = std::move(text);
    }
}

std::string printWalk(const Walk& walk) {
    std::ostringstream out;
    out << "Pixel (" << walk.x << ", " << walk.y << ")";
    if (walk.triangle) out << ", triangle " << walk.triangle->number;
    out << "\n" << wrapText("Verdict: " + walk.verdict, kScreenColumns, 2);
    for (std::size_t k = 0; k < walk.screens.size(); ++k)
        out << "\n" << printScreen(walk, k);
    return out.str();
}

std::string printScreen(const Walk& walk, std::size_t index) {
    const Screen& screen = walk.screens.at(index);
    const std::string rule(kScreenColumns, '=');
    return rule + "\n" + std::to_string(index + 1) + ". " + screen.title + "\n" + rule + "\n" + screen.text;
}

}  // namespace facet::step
