// inQuotes (base/quote.h): how a value from the input is shown in a message, cut short and escaped so
// that it cannot flood or rewrite the terminal.
#include "base/quote.h"

#include <string>

#include <gtest/gtest.h>

namespace facet {
namespace {

TEST(Quote, CutsAfterFortyCharactersAndEscapesWhatATerminalWouldNotShow) {
    EXPECT_EQ(inQuotes("camera.fvoy"), R"("camera.fvoy")");
    EXPECT_EQ(inQuotes("nan", '\''), "'nan'");
    EXPECT_EQ(inQuotes(std::string(40, 'x')), '"' + std::string(40, 'x') + '"');
    EXPECT_EQ(inQuotes(std::string(41, 'x')), '"' + std::string(40, 'x') + "…\"");
    // Characters, not bytes, are counted, and a cut never splits one.
    std::string accents;
    for (int i = 0; i < 41; ++i)
        accents += "é";
    EXPECT_EQ(inQuotes(accents), '"' + accents.substr(0, 80) + "…\"");
    EXPECT_EQ(inQuotes("a\nb\tc\rd"), R"("a\nb\tc\rd")");
    EXPECT_EQ(inQuotes("say \"hi\" \\ 'x'"), R"("say \"hi\" \\ 'x'")");
    EXPECT_EQ(inQuotes("it's", '\''), R"('it\'s')");
    EXPECT_EQ(inQuotes("\x1B[31mred"), R"("\x1B[31mred")");
    EXPECT_EQ(inQuotes("\x7F"), R"("\x7F")");
    // Not UTF-8: a stray byte, a stray continuation byte, an overlong '/', a cut sequence, a surrogate.
    EXPECT_EQ(inQuotes("\xFF"), R"("\xFF")");
    EXPECT_EQ(inQuotes("\x80"), R"("\x80")");
    EXPECT_EQ(inQuotes("\xC0\xAF"), R"("\xC0\xAF")");
    EXPECT_EQ(inQuotes("\xE2\x82"), R"("\xE2\x82")");
    EXPECT_EQ(inQuotes("\xED\xA0\x80"), R"("\xED\xA0\x80")");
    // UTF-8 that would still move the text: a C1 control (NEL), right-to-left override, line separator.
    EXPECT_EQ(inQuotes("a\u0085b"), R"("a\xC2\x85b")");
    EXPECT_EQ(inQuotes("\u202Eevil"), R"("\xE2\x80\xAEevil")");
    EXPECT_EQ(inQuotes("\u2028"), R"("\xE2\x80\xA8")");
    // Printable UTF-8 stays as written.
    EXPECT_EQ(inQuotes("Straße, 東京, 🙂"), R"("Straße, 東京, 🙂")");
}

}  // namespace
}  // namespace facet
