#include "step/versus.h"

#include <algorithm>
#include <optional>
#include <sstream>
#include <string_view>
#include <vector>

namespace facet::step {

namespace {

// `text` as it is when it fits `width` columns (its spacing kept), else wrapped with `indent`.
std::string fitted(const std::string& text, std::size_t width, std::size_t indent) {
    return columnsOf(text) <= width ? text + "\n" : wrapText(text, width, indent);
}

struct Row {
    std::optional<std::string> left, right;
};

// The two line lists aligned: equal lines side by side, the others paired in order where both sides
// have lines between two equal ones.
std::vector<Row> align(const std::vector<std::string>& a, const std::vector<std::string>& b) {
    const std::size_t n = a.size(), m = b.size();
    std::vector<std::vector<int>> lcs(n + 1, std::vector<int>(m + 1, 0));
    for (std::size_t i = n; i-- > 0;)
        for (std::size_t j = m; j-- > 0;)
            lcs[i][j] = a[i] == b[j] ? lcs[i + 1][j + 1] + 1 : std::max(lcs[i + 1][j], lcs[i][j + 1]);
    std::vector<Row> rows;
    std::size_t i = 0, j = 0;
    std::vector<std::string> onlyA, onlyB;
    auto flush = [&] {
        for (std::size_t k = 0; k < std::max(onlyA.size(), onlyB.size()); ++k)
            rows.push_back({k < onlyA.size() ? std::optional(onlyA[k]) : std::nullopt,
                            k < onlyB.size() ? std::optional(onlyB[k]) : std::nullopt});
        onlyA.clear();
        onlyB.clear();
    };
    while (i < n || j < m) {
        if (i < n && j < m && a[i] == b[j]) {
            flush();
            rows.push_back({a[i], b[j]});
            ++i, ++j;
        } else if (j >= m || (i < n && lcs[i + 1][j] >= lcs[i][j + 1])) {
            onlyA.push_back(a[i++]);
        } else {
            onlyB.push_back(b[j++]);
        }
    }
    flush();
    return rows;
}

}  // namespace

std::string sideBySide(const Walk& a, const std::string& nameA, const Walk& b, const std::string& nameB) {
    // A shader of one's own (its screen "shader") faces the built-in lighting (its screen "lighting").
    const auto counterpart = [](const std::string& id) -> std::string {
        return id == "shader" ? "lighting" : id == "lighting" ? "shader" : "";
    };
    auto find = [&](const Walk& w, const std::string& id) -> const Screen* {
        for (const Screen& s : w.screens)
            if (s.id == id) return &s;
        return nullptr;
    };
    auto findOrCounterpart = [&](const Walk& w, const Walk& other, const std::string& id) -> const Screen* {
        if (const Screen* s = find(w, id)) return s;
        const std::string c = counterpart(id);
        return !c.empty() && !find(other, c) ? find(w, c) : nullptr;
    };
    // The screens by id, in A's order, then those only B has.
    std::vector<std::string> ids;
    for (const Screen& s : a.screens)
        ids.push_back(s.id);
    for (const Screen& s : b.screens)
        if (std::find(ids.begin(), ids.end(), s.id) == ids.end() &&
            (counterpart(s.id).empty() || find(b, counterpart(s.id)) ||
             std::find(ids.begin(), ids.end(), counterpart(s.id)) == ids.end()))
            ids.push_back(s.id);

    struct Block {
        std::string titleA, titleB;
        std::vector<Row> rows;
    };
    std::vector<Block> blocks;
    std::optional<std::pair<std::size_t, std::size_t>> first;  // block, row
    {
        Block verdict{
            "Verdict", "Verdict",
            align(ownedLinesOf(wrapText(a.verdict, 80, 2)), ownedLinesOf(wrapText(b.verdict, 80, 2)))};
        blocks.push_back(verdict);
        for (std::size_t r = 0; r < verdict.rows.size() && !first; ++r)
            if (verdict.rows[r].left != verdict.rows[r].right) first = std::pair(std::size_t{0}, r);
    }
    for (const std::string& id : ids) {
        const Screen* sa = findOrCounterpart(a, b, id);
        const Screen* sb = findOrCounterpart(b, a, id);
        Block block{sa ? sa->title : "(no such screen)", sb ? sb->title : "(no such screen)",
                    align(sa ? ownedLinesOf(sa->text) : std::vector<std::string>{},
                          sb ? ownedLinesOf(sb->text) : std::vector<std::string>{})};
        for (std::size_t r = 0; r < block.rows.size(); ++r) {
            const Row& row = block.rows[r];
            if (!first && row.left != row.right) first = std::pair(blocks.size(), r);
        }
        blocks.push_back(std::move(block));
    }

    // Stacked rather than side by side, so that every line fits 80 columns: each line under a
    // two-column gutter, its text wrapped to the rest.
    constexpr std::size_t kWidth = 80, kGutter = 3;
    std::ostringstream out;
    const auto emit = [&out](std::string_view gutter, const std::string& text) {
        const std::size_t indent = std::min<std::size_t>(text.find_first_not_of(' '), 40);
        const std::vector<std::string> wrapped = ownedLinesOf(fitted(text, kWidth - kGutter, indent + 4));
        for (const std::string& line : wrapped.empty() ? std::vector<std::string>{""} : wrapped)
            out << gutter << line << "\n";
    };
    std::ostringstream heading;
    heading << "Pixel (" << a.x << ", " << a.y << ")";
    if (a.triangle) heading << ", triangle " << a.triangle->number;
    heading << ", under two settings:";
    out << heading.str() << "\n"
        << fitted("  left (<):  " + nameA, kWidth, 14) << fitted("  right (>): " + nameB, kWidth, 14);
    if (!first) {
        out << "The two traces are the same, line for line.\n";
    } else {
        const Block& block = blocks[first->first];
        const Row& row = block.rows[first->second];
        out << fitted("They first differ in \"" + block.titleA + "\":", kWidth, 2);
        if (row.left && row.right)
            out << fitted("  left:  " + *row.left, kWidth, 9) << fitted("  right: " + *row.right, kWidth, 9);
        else if (row.left)
            out << fitted("  a line only the left has: " + *row.left, kWidth, 4);
        else
            out << fitted("  a line only the right has: " + *row.right, kWidth, 4);
    }
    out << "Gutter: blank, the same line on both sides; < the left's line; > the right's\n"
           "(a changed line shows both, the left's first); * the first difference.\n";
    for (std::size_t k = 0; k < blocks.size(); ++k) {
        const Block& block = blocks[k];
        out << "\n" << std::string(kWidth, '=') << "\n";
        if (block.titleA == block.titleB) {
            emit("   ", block.titleA);
        } else {
            emit(" < ", block.titleA);
            emit(" > ", block.titleB);
        }
        for (std::size_t r = 0; r < block.rows.size(); ++r) {
            const Row& row = block.rows[r];
            const bool firstDifference = first && first->first == k && first->second == r;
            if (row.left && row.right && *row.left == *row.right) {
                emit("   ", *row.left);
                continue;
            }
            if (row.left) emit(firstDifference ? "*< " : " < ", *row.left);
            if (row.right) emit(firstDifference ? "*> " : " > ", *row.right);
        }
    }
    return out.str();
}

}  // namespace facet::step
