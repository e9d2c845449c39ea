#include "step/screen_export.h"

#include <algorithm>
#include <sstream>
#include <vector>

#include "base/errors.h"

namespace facet::step {

namespace {

// The table is kept in code-point order so that a lookup is a binary search.
constexpr LatexSymbol kSymbols[] = {
    {U'§', "\\S", "\\S{}"},
    {U'°', "^{\\circ}"},
    {U'²', "^{2}"},  // the superscripts are also read as runs by superscriptDigit
    {U'³', "^{3}"},
    {U'·', "\\cdot"},
    {U'¹', "^{1}"},
    {U'½', "\\tfrac{1}{2}"},
    {U'×', "\\times"},
    {U'\u0302', "\\hat"},  // combining circumflex: n̂ → \hat{n}, handled with the letter before it
    {U'Γ', "\\Gamma", "", true},
    {U'Δ', "\\Delta", "", true},
    {U'Θ', "\\Theta", "", true},
    {U'Λ', "\\Lambda", "", true},
    {U'Π', "\\Pi", "", true},
    {U'Σ', "\\sum"},  // the screens' sum sign: Σ w
    {U'Φ', "\\Phi", "", true},
    {U'Ω', "\\Omega", "", true},
    {U'α', "\\alpha", "", true},
    {U'β', "\\beta", "", true},
    {U'γ', "\\gamma", "", true},
    {U'δ', "\\delta", "", true},
    {U'ε', "\\varepsilon", "", true},
    {U'ζ', "\\zeta", "", true},
    {U'η', "\\eta", "", true},
    {U'θ', "\\theta", "", true},
    {U'κ', "\\kappa", "", true},
    {U'λ', "\\lambda", "", true},
    {U'μ', "\\mu", "", true},
    {U'ν', "\\nu", "", true},
    {U'ξ', "\\xi", "", true},
    {U'π', "\\pi", "", true},
    {U'ρ', "\\rho", "", true},
    {U'σ', "\\sigma", "", true},
    {U'τ', "\\tau", "", true},
    {U'φ', "\\varphi", "", true},
    {U'χ', "\\chi", "", true},
    {U'ψ', "\\psi", "", true},
    {U'ω', "\\omega", "", true},
    {U'ᵀ', "^{T}"},
    {U'ᵢ', "_{i}"},
    {U'\u2009', "\\,", "\\,"},  // thin space
    {U'–', "-", "--"},
    {U'—', "-", "---"},
    {U'‖', "\\|"},  // a pair is written \lVert … \rVert by latexMath
    {U'‘', "`", "`"},
    {U'’', "'", "'"},
    {U'“', "``", "``"},
    {U'”', "''", "''"},
    {U'…', "\\dots", "\\ldots{}"},
    {U'′', "'"},
    {U'″', "''"},
    {U'⁰', "^{0}"},
    {U'⁴', "^{4}"},
    {U'⁵', "^{5}"},
    {U'⁶', "^{6}"},
    {U'⁷', "^{7}"},
    {U'⁸', "^{8}"},
    {U'⁹', "^{9}"},
    {U'⁺', "^{+}"},
    {U'⁻', "^{-}"},
    {U'ⁿ', "^{n}"},
    {U'₀', "_{0}"},
    {U'₁', "_{1}"},
    {U'₂', "_{2}"},
    {U'₃', "_{3}"},
    {U'₊', "_{+}"},
    {U'₋', "_{-}"},
    {U'←', "\\leftarrow"},
    {U'→', "\\to"},
    {U'↔', "\\leftrightarrow"},
    {U'⇒', "\\Rightarrow"},
    {U'∂', "\\partial", "", true},
    {U'∇', "\\nabla"},
    {U'∑', "\\sum"},
    {U'−', "-"},
    {U'∓', "\\mp"},
    {U'∕', "/"},
    {U'√', "\\sqrt"},  // takes the group or word after it: √(x) → \sqrt{x}
    {U'∛', "\\sqrt[3]"},
    {U'∞', "\\infty"},
    {U'∧', "\\wedge"},
    {U'∨', "\\vee"},
    {U'∩', "\\cap"},
    {U'∪', "\\cup"},
    {U'∫', "\\int"},
    {U'≈', "\\approx"},
    {U'≠', "\\neq"},
    {U'≡', "\\equiv"},
    {U'≤', "\\leq"},
    {U'≥', "\\geq"},
    {U'⊕', "\\oplus"},
    {U'⊗', "\\otimes"},
    {U'⊥', "\\perp"},
    {U'⋅', "\\cdot"},
    {U'⌈', "\\lceil"},
    {U'⌉', "\\rceil"},
    {U'⌊', "\\lfloor"},
    {U'⌋', "\\rfloor"},
    {U'▸', "\\triangleright"},
    {U'✓', "\\checkmark"},
};

static_assert(std::is_sorted(std::begin(kSymbols), std::end(kSymbols),
                             [](const LatexSymbol& a, const LatexSymbol& b) {
                                 return a.character <= b.character;
                             }),
              "kSymbols in code-point order, each character once");

const LatexSymbol* symbolOf(char32_t c) {
    const auto it = std::lower_bound(std::begin(kSymbols), std::end(kSymbols), c,
                                     [](const LatexSymbol& s, char32_t v) { return s.character < v; });
    return it != std::end(kSymbols) && it->character == c ? &*it : nullptr;
}

std::u32string decode(std::string_view utf8) {
    std::u32string out;
    for (std::size_t i = 0; i < utf8.size();) {
        const auto b = static_cast<unsigned char>(utf8[i]);
        const int extra = b < 0x80 ? 0 : b < 0xE0 ? 1 : b < 0xF0 ? 2 : 3;
        char32_t c = extra == 0 ? b : extra == 1 ? b & 0x1F : extra == 2 ? b & 0x0F : b & 0x07;
        for (int k = 1; k <= extra && i + k < utf8.size(); ++k)
            c = (c << 6) | (static_cast<unsigned char>(utf8[i + k]) & 0x3F);
        out += c;
        i += 1 + extra;
    }
    return out;
}

std::string encode(char32_t c) {
    std::string out;
    if (c < 0x80) {
        out += static_cast<char>(c);
    } else if (c < 0x800) {
        out += static_cast<char>(0xC0 | (c >> 6));
        out += static_cast<char>(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
        out += static_cast<char>(0xE0 | (c >> 12));
        out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (c & 0x3F));
    } else {
        out += static_cast<char>(0xF0 | (c >> 18));
        out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
        out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (c & 0x3F));
    }
    return out;
}

const LatexSymbol& requireSymbol(char32_t c) {
    const LatexSymbol* symbol = symbolOf(c);
    if (!symbol)
        throw InputError("the LaTeX export has no translation for the character \"" + encode(c) +
                         "\" that a screen prints");
    return *symbol;
}

bool isAsciiLetter(char32_t c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}
bool isDigit(char32_t c) {
    return c >= '0' && c <= '9';
}
bool isSuperscript(char32_t c) {
    const LatexSymbol* s = c >= 0x80 ? symbolOf(c) : nullptr;
    return s && std::string_view(s->math).starts_with("^{") && c != U'°';
}
bool isSubscript(char32_t c) {
    const LatexSymbol* s = c >= 0x80 ? symbolOf(c) : nullptr;
    return s && std::string_view(s->math).starts_with("_{");
}
bool isLetterSymbol(char32_t c) {
    const LatexSymbol* s = c >= 0x80 ? symbolOf(c) : nullptr;
    return s && s->letter;
}

// Words that LaTeX sets as operators rather than as text.
constexpr std::pair<std::string_view, std::string_view> kOperators[] = {
    {"cos", "\\cos"}, {"det", "\\det"}, {"exp", "\\exp"}, {"log", "\\log"},
    {"max", "\\max"}, {"min", "\\min"}, {"sin", "\\sin"}, {"tan", "\\tan"}};

// Writes one formula as math, tracking scripts so that two in a row never make a "double subscript".
class MathWriter {
  public:
    explicit MathWriter(const std::u32string& s) : s_(s) {}

    std::string run(std::size_t from, std::size_t to) {
        std::size_t i = from;
        while (i < to)
            i = item(i, to);
        return out_;
    }

  private:
    const std::u32string& s_;
    std::string out_;
    bool subscripted_ = false, superscripted_ = false;
    bool openNorm_ = false;

    void emit(const std::string& text, bool ordinary = true) {
        // A control word followed by a letter would merge with it: \cdot x, not \cdotx.
        if (!out_.empty() && !text.empty() &&
            (isAsciiLetter(static_cast<unsigned char>(text[0])) ||
             isDigit(static_cast<unsigned char>(text[0])))) {
            const std::size_t slash = out_.rfind('\\');
            if (slash != std::string::npos &&
                std::all_of(out_.begin() + slash + 1, out_.end(),
                            [](char c) { return isAsciiLetter(static_cast<unsigned char>(c)); }) &&
                slash + 1 < out_.size())
                out_ += ' ';
        }
        out_ += text;
        if (ordinary) subscripted_ = superscripted_ = false;
    }
    void script(char mark, const std::string& content) {
        bool& already = mark == '_' ? subscripted_ : superscripted_;
        if (already) out_ += "{}";
        out_ += mark;
        out_ += "{" + content + "}";
        already = true;
    }

    // The subformula in [from, to) on its own (scripts inside it do not carry out).
    std::string inner(std::size_t from, std::size_t to) const { return MathWriter(s_).run(from, to); }
    std::size_t matching(std::size_t open, std::size_t to, char32_t left, char32_t right) const {
        int depth = 0;
        for (std::size_t k = open; k < to; ++k) {
            if (s_[k] == left && (left != right || k == open))
                ++depth;
            else if (s_[k] == right && --depth == 0)
                return k;
        }
        return std::string::npos;
    }
    // The end of a word of letters and digits (and a following scientific exponent) from `i`.
    std::size_t wordEnd(std::size_t i, std::size_t to) const {
        while (i < to && (isAsciiLetter(s_[i]) || isDigit(s_[i]) || isLetterSymbol(s_[i])))
            ++i;
        return i;
    }
    // A script's argument after _ or ^ or a root sign: a bracketed group or a word.
    std::pair<std::string, std::size_t> argument(std::size_t i, std::size_t to) {
        if (i < to && (s_[i] == '(' || s_[i] == '|')) {
            const std::size_t close = matching(i, to, s_[i], s_[i] == '(' ? U')' : U'|');
            if (close != std::string::npos) {
                if (s_[i] == '|') return {inner(i, close + 1), close + 1};  // ∛|det| keeps its bars
                return {inner(i + 1, close), close + 1};
            }
        }
        if (i < to && s_[i] == '-' && i + 1 < to && (isDigit(s_[i + 1]) || isAsciiLetter(s_[i + 1]))) {
            const std::size_t end = wordEnd(i + 1, to);
            return {"-" + inner(i + 1, end), end};
        }
        const std::size_t end = wordEnd(i, to);
        if (end == i) return {"", i};
        // A word in a script is upright text when it is a word (_add, _eye), a symbol when one letter.
        bool allLetters = true;
        for (std::size_t k = i; k < end; ++k)
            allLetters = allLetters && isAsciiLetter(s_[k]);
        if (allLetters && end - i >= 2) return {"\\text{" + asciiOf(i, end) + "}", end};
        return {inner(i, end), end};
    }
    std::string asciiOf(std::size_t from, std::size_t to) const {
        std::string out;
        for (std::size_t k = from; k < to; ++k)
            out += static_cast<char>(s_[k]);
        return out;
    }
    bool ordinaryAt(std::size_t k) const {
        const char32_t c = s_[k];
        return isAsciiLetter(c) || isDigit(c) || c == ')' || c == ']' || c == '(' || c == '[' || c == '.' ||
               isLetterSymbol(c) || isSuperscript(c) || c == U'′' || c == '\'';
    }

    std::size_t item(std::size_t i, std::size_t to) {
        const char32_t c = s_[i];
        if (c == ' ') {
            std::size_t end = i;
            while (end < to && s_[end] == ' ')
                ++end;
            // Math mode ignores spaces: kept where they part two words or numbers (v0 (x, y)), left to
            // TeX's own spacing around operators and relations.
            if (i > 0 && end < to) {
                if (end - i >= 2)
                    out_ += "\\quad ";
                else if (ordinaryAt(i - 1) && ordinaryAt(end))
                    out_ += "\\ ";
                else
                    out_ += ' ';
            }
            return end;
        }
        if (isDigit(c)) {
            std::size_t end = i;
            while (end < to && (isDigit(s_[end]) || (s_[end] == '.' && end + 1 < to && isDigit(s_[end + 1]))))
                ++end;
            std::string mantissa = asciiOf(i, end);
            // 5.73e-06 as the screens print it: 5.73 × 10^{-6}.
            if (end + 1 < to && (s_[end] == 'e' || s_[end] == 'E')) {
                std::size_t k = end + 1;
                const bool negative = s_[k] == '-';
                if (s_[k] == '-' || s_[k] == '+') ++k;
                const std::size_t digits = k;
                while (k < to && isDigit(s_[k]))
                    ++k;
                if (k > digits && (k == to || !isAsciiLetter(s_[k]))) {
                    std::string exponent = asciiOf(digits, k);
                    exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
                    emit(mantissa + "\\times 10");
                    script('^', (negative ? "-" : "") + exponent);
                    return k;
                }
            }
            emit(mantissa);
            return end;
        }
        if (isAsciiLetter(c)) {
            std::size_t end = i;
            // A word's apostrophe (the spot's axis) stays in its word; a prime after a letter (λ') does not.
            while (end < to && !(end + 1 < to && s_[end + 1] == U'\u0302') &&
                   (isAsciiLetter(s_[end]) ||
                    (s_[end] == '\'' && end - i >= 2 && end + 1 < to && isAsciiLetter(s_[end + 1]))))
                ++end;
            if (end == i) {  // a letter with a hat: n̂
                emit("\\hat{" + asciiOf(i, i + 1) + "}");
                end = i + 2;
            } else {
                const std::string word = asciiOf(i, end);
                const auto op = std::find_if(std::begin(kOperators), std::end(kOperators),
                                             [&](const auto& o) { return o.first == word; });
                if (word.size() == 1)
                    emit(word);
                else if (op != std::end(kOperators))
                    emit(std::string(op->second));
                else
                    emit("\\text{" + word + "}");
            }
            return digitsAsSubscript(end, to);
        }
        if (isLetterSymbol(c)) {
            if (i + 1 < to && s_[i + 1] == U'\u0302') {
                emit("\\hat{" + std::string(symbolOf(c)->math) + "}");
                return digitsAsSubscript(i + 2, to);
            }
            emit(symbolOf(c)->math);
            return digitsAsSubscript(i + 1, to);
        }
        if (c == '_') {
            auto [content, end] = argument(i + 1, to);
            if (content.empty()) {
                emit("\\_");
                return i + 1;
            }
            script('_', content);
            return end;
        }
        if (c == '^') {
            auto [content, end] = argument(i + 1, to);
            if (content.empty()) {
                emit("\\wedge");
                return i + 1;
            }
            script('^', content);
            return end;
        }
        if (isSuperscript(c) || isSubscript(c)) {
            const bool super = isSuperscript(c);
            std::string content;
            std::size_t end = i;
            while (end < to && (super ? isSuperscript(s_[end]) : isSubscript(s_[end]))) {
                const std::string_view math = symbolOf(s_[end])->math;
                content += math.substr(2, math.size() - 3);
                ++end;
            }
            script(super ? '^' : '_', content);
            return end;
        }
        if (c == U'√' || c == U'∛') {
            auto [content, end] = argument(i + 1, to);
            emit(std::string(symbolOf(c)->math) + "{" + content + "}");
            return end;
        }
        if (c == U'‖') {
            emit(openNorm_ ? "\\rVert" : "\\lVert", !openNorm_);
            openNorm_ = !openNorm_;
            return i + 1;
        }
        if (c == '\'' || c == U'′') {
            // A prime is a superscript: λ′_i is fine, λ′^2 would need the guard.
            if (superscripted_) out_ += "{}";
            out_ += "'";
            superscripted_ = true;
            return i + 1;
        }
        switch (c) {
            case '{':
                emit("\\{");
                return i + 1;
            case '}':
                emit("\\}");
                return i + 1;
            case '#':
                emit("\\#");
                return i + 1;
            case '$':
                emit("\\$");
                return i + 1;
            case '%':
                emit("\\%");
                return i + 1;
            case '&':
                emit("\\&");
                return i + 1;
            case '~':
                emit("\\sim");
                return i + 1;
            case '\\':
                emit("\\backslash");
                return i + 1;
            case '"':
                emit("\\text{''}");
                return i + 1;
            default:
                break;
        }
        if (c < 0x80) {
            emit(std::string(1, static_cast<char>(c)));
            return i + 1;
        }
        emit(requireSymbol(c).math);
        return i + 1;
    }

    // v0 → v_{0}: the digits right after a symbol are its index.
    std::size_t digitsAsSubscript(std::size_t i, std::size_t to) {
        std::size_t end = i;
        while (end < to && isDigit(s_[end]))
            ++end;
        // Not a number's start (v0.5 is not written), nor a hexadecimal-like word.
        if (end > i && (end == to || (!isAsciiLetter(s_[end]) && s_[end] != '.'))) {
            script('_', asciiOf(i, end));
            return end;
        }
        return i;
    }
};

std::string escapeText(char32_t c, bool& quoteOpen) {
    switch (c) {
        case '#':
            return "\\#";
        case '$':
            return "\\$";
        case '%':
            return "\\%";
        case '&':
            return "\\&";
        case '_':
            return "\\_";
        case '{':
            return "\\{";
        case '}':
            return "\\}";
        case '~':
            return "\\textasciitilde{}";
        case '^':
            return "\\textasciicircum{}";
        case '\\':
            return "\\textbackslash{}";
        case '<':
            return "\\textless{}";
        case '>':
            return "\\textgreater{}";
        case '|':
            return "\\textbar{}";
        case '"':
            quoteOpen = !quoteOpen;
            return quoteOpen ? "``" : "''";
        default:
            break;
    }
    if (c < 0x80) return std::string(1, static_cast<char>(c));
    const LatexSymbol& symbol = requireSymbol(c);
    return *symbol.text ? std::string(symbol.text) : "$" + std::string(symbol.math) + "$";
}

bool isMathTrigger(char32_t c) {
    return c == '_' || c == '^' ||
           (c >= 0x80 && c != U'…' && c != U'–' && c != U'—' && c != U'§' && c != U'“' && c != U'”' &&
            c != U'‘' && c != U'’');
}

// --- the lines of a screen ---

enum class LineKind { Blank, Prose, Formula, Columns };

std::size_t indentOf(const std::string& line) {
    return std::min(line.find_first_not_of(' '), line.size());
}

// A row of the rasterization's picture: mostly its marks, one a column.
bool isPicture(const std::string& line) {
    const std::size_t start = indentOf(line);
    std::size_t marks = 0, other = 0;
    for (std::size_t k = start; k < line.size(); ++k) {
        if (line[k] == ' ') continue;
        (std::string_view("#+.:[]").find(line[k]) != std::string_view::npos ? marks : other) += 1;
    }
    return marks >= 5 && marks >= other;
}

// The screens write sentences from the left margin and indent what they compute: an indented line with
// a relation or an operator of the notation is a formula (its trailing "(GGX)" and column gaps too).
LineKind kindOf(const std::string& line) {
    if (line.find_first_not_of(' ') == std::string::npos) return LineKind::Blank;
    if (isPicture(line)) return LineKind::Columns;
    if (indentOf(line) == 0) return LineKind::Prose;
    static const std::u32string kRelations = U"=<>≤≥≠≈→⊗·×^Σ√∛²";
    for (const char32_t c : decode(line))
        if (kRelations.find(c) != std::u32string::npos) return LineKind::Formula;
    return line.find("   ", indentOf(line)) != std::string::npos ? LineKind::Columns : LineKind::Prose;
}

// "  M = [ 1 0 ... ": the first line of a matrix the screens print in rows, ending with "]".
bool startsMatrix(const std::string& line) {
    const std::size_t open = line.find("= [");
    return open != std::string::npos && line.find(']', open) == std::string::npos;
}

std::string indentSpace(std::size_t indent) {
    return indent ? "\\hspace*{" + std::to_string(indent) + "ex}" : "";
}

std::vector<std::string> numbersOf(const std::string& row) {
    std::istringstream in(row);
    std::vector<std::string> cells;
    for (std::string cell; in >> cell;)
        if (cell != "[" && cell != "]") cells.push_back(cell);
    return cells;
}

std::string latexBody(const std::string& text) {
    const std::vector<std::string> lines = ownedLinesOf(text);
    std::string out;
    bool inParagraph = false;
    auto endParagraph = [&] {
        if (inParagraph) out += "\\par\n";
        inParagraph = false;
    };
    for (std::size_t k = 0; k < lines.size(); ++k) {
        const std::string& line = lines[k];
        const std::size_t indent = indentOf(line);
        if (startsMatrix(line)) {
            // Its rows to the line that closes it.
            std::size_t last = k;
            while (last + 1 < lines.size() && lines[last].find(']') == std::string::npos)
                ++last;
            const std::size_t open = line.find("= [");
            endParagraph();
            out += indentSpace(indent) + "$" + latexMath(line.substr(indent, open - indent)) +
                   "= \\begin{bmatrix}";
            for (std::size_t r = k; r <= last; ++r) {
                const std::vector<std::string> cells = numbersOf(r == k ? line.substr(open + 3) : lines[r]);
                out += r == k ? " " : " \\\\ ";
                for (std::size_t c = 0; c < cells.size(); ++c)
                    out += (c ? " & " : "") + latexMath(cells[c]);
            }
            out += " \\end{bmatrix}$\\par\n";
            k = last;
            continue;
        }
        switch (kindOf(line)) {
            case LineKind::Blank:
                endParagraph();
                out += "\\medskip\n";
                break;
            case LineKind::Prose:
                if (indent > 0) {
                    endParagraph();
                    out += indentSpace(indent) + latexText(line.substr(indent)) + "\\par\n";
                } else {
                    out += latexText(line) + "\n";
                    inParagraph = true;
                }
                break;
            case LineKind::Formula:
                endParagraph();
                out += indentSpace(indent) + "$" + latexMath(line.substr(indent)) + "$\\par\n";
                break;
            case LineKind::Columns: {
                // Monospace, each space kept, so that the columns stay aligned.
                endParagraph();
                bool quoteOpen = false;
                std::string mono;
                for (const char32_t c : decode(line))
                    mono += c == ' ' ? std::string("~") : escapeText(c, quoteOpen);
                out += "\\texttt{" + mono + "}\\par\n";
                break;
            }
        }
    }
    endParagraph();
    return out;
}

// --- Markdown ---

std::string markdownText(const std::string& prose) {
    std::string out;
    for (const char c : prose) {
        if (std::string_view("\\`*_[]<>#|").find(c) != std::string_view::npos) out += '\\';
        out += c;
    }
    // A paragraph that starts like a list item or a numbered one is not one.
    if (!out.empty() && (out[0] == '+' || out[0] == '-')) out.insert(0, 1, '\\');
    const std::size_t digits = std::min(out.find_first_not_of("0123456789"), out.size());
    if (digits > 0 && digits < out.size() && (out[digits] == '.' || out[digits] == ')'))
        out.insert(digits, 1, '\\');
    return out;
}

std::string markdownBody(const std::string& text) {
    const std::vector<std::string> lines = ownedLinesOf(text);
    std::string out, paragraph;
    std::vector<std::string> block;
    auto flushParagraph = [&] {
        if (!paragraph.empty()) out += markdownText(paragraph) + "\n\n";
        paragraph.clear();
    };
    auto flushBlock = [&] {
        if (block.empty()) return;
        out += "```text\n";
        for (const std::string& line : block)
            out += line + "\n";
        out += "```\n\n";
        block.clear();
    };
    for (const std::string& line : lines) {
        if (line.find_first_not_of(' ') == std::string::npos) {
            flushParagraph();
            flushBlock();
        } else if (indentOf(line) == 0 && !isPicture(line)) {
            flushBlock();
            paragraph += (paragraph.empty() ? "" : " ") + line;
        } else {
            flushParagraph();
            block.push_back(line);
        }
    }
    flushParagraph();
    flushBlock();
    while (out.size() >= 2 && out.ends_with("\n\n"))
        out.pop_back();
    return out;
}

std::string latexFrame(const Screen& screen) {
    return "\\frametitle{" + latexText(screen.title) + "}\n" + latexBody(screen.text);
}

std::string markdownScreen(const Screen& screen) {
    return "## " + markdownText(screen.title) + "\n\n" + markdownBody(screen.text);
}

}  // namespace

std::span<const LatexSymbol> latexSymbols() {
    return kSymbols;
}

std::optional<ScreenFormat> screenFormatNamed(std::string_view name) {
    for (std::size_t k = 0; k < kScreenFormatNames.size(); ++k)
        if (name == kScreenFormatNames[k]) return static_cast<ScreenFormat>(k);
    return std::nullopt;
}

std::string latexMath(std::string_view formula) {
    const std::u32string s = decode(formula);
    return MathWriter(s).run(0, s.size());
}

std::string latexText(std::string_view prose) {
    // Word by word: a word holding a symbol, _ or ^ is math, its brackets and punctuation around it text.
    const std::u32string s = decode(prose);
    std::string out;
    bool quoteOpen = false;
    for (std::size_t i = 0; i < s.size();) {
        if (s[i] == ' ') {
            out += ' ';
            ++i;
            continue;
        }
        std::size_t end = i;
        while (end < s.size() && s[end] != ' ')
            ++end;
        if (!std::any_of(s.begin() + i, s.begin() + end, isMathTrigger)) {
            for (std::size_t k = i; k < end; ++k)
                out += escapeText(s[k], quoteOpen);
            i = end;
            continue;
        }
        std::size_t first = i, last = end;
        // An opening bracket stays with a formula that closes it: ((V·M)⁻¹)ᵀ.
        auto opens = [&](std::size_t a, std::size_t b) {
            return std::count(s.begin() + a, s.begin() + b, U'(') -
                   std::count(s.begin() + a, s.begin() + b, U')');
        };
        while (first < last && std::u32string_view(U"(\"“‘").find(s[first]) != std::u32string_view::npos &&
               (s[first] != '(' || opens(first, last) > 0))
            ++first;
        while (last > first &&
               std::u32string_view(U".,:;)\"”’").find(s[last - 1]) != std::u32string_view::npos)
            --last;
        // A closing bracket that the word opened stays in the formula: max(a, b) or E_i(x,.
        if (last < end && s[last] == ')' &&
            std::count(s.begin() + first, s.begin() + last, U'(') >
                std::count(s.begin() + first, s.begin() + last, U')'))
            ++last;
        for (std::size_t k = i; k < first; ++k)
            out += escapeText(s[k], quoteOpen);
        out += '$';  // appended piece by piece: GCC 12 reports a false -Wrestrict on chains of operator+
        out += MathWriter(s).run(first, last);
        out += '$';
        for (std::size_t k = last; k < end; ++k)
            out += escapeText(s[k], quoteOpen);
        i = end;
    }
    return out;
}

std::size_t screenIndex(const Walk& walk, const std::string& id) {
    for (std::size_t k = 0; k < walk.screens.size(); ++k)
        if (walk.screens[k].id == id) return k;
    std::string ids;
    for (const Screen& screen : walk.screens)
        ids += (ids.empty() ? "" : ", ") + screen.id;
    throw InputError("--screen " + id + ": this walk has no such screen; its screens are " + ids);
}

std::string formatScreen(const Walk& walk, std::size_t index, ScreenFormat format) {
    const Screen& screen = walk.screens.at(index);
    switch (format) {
        case ScreenFormat::Text:
            return printScreen(walk, index);
        case ScreenFormat::Markdown:
            return markdownScreen(screen);
        case ScreenFormat::Latex:
            return latexFrame(screen);
    }
    return "";
}

std::string formatWalk(const Walk& walk, ScreenFormat format) {
    if (format == ScreenFormat::Text) return printWalk(walk);
    std::string heading = "Pixel (" + std::to_string(walk.x) + ", " + std::to_string(walk.y) + ")";
    if (walk.triangle) heading += ", triangle " + std::to_string(walk.triangle->number);
    std::string out;
    if (format == ScreenFormat::Markdown) {
        out = "# " + markdownText(heading) + "\n\nVerdict: " + markdownText(walk.verdict) + "\n";
        for (const Screen& screen : walk.screens) {
            out += '\n';
            out += markdownScreen(screen);
        }
        return out;
    }
    out = "% " + heading + ". Verdict: " + latexText(walk.verdict) + "\n";
    for (const Screen& screen : walk.screens)
        out += "\n\\begin{frame}\n" + latexFrame(screen) + "\\end{frame}\n";
    return out;
}

}  // namespace facet::step
