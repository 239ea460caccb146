// Tokens of the part language: kinds, values, positions (1-based, code points) and errors.
#include <gtest/gtest.h>

#include <vector>

#include "io/Lexer.h"

using io::Lexer;
using io::Tok;
using io::Token;

static std::vector<Token> lexAll(std::string_view text) {
    Lexer lexer(text, 0);
    std::vector<Token> out;
    for (;;) {
        Token t = lexer.next();
        const bool stop = t.kind == Tok::End || t.kind == Tok::Error;
        out.push_back(std::move(t));
        if (stop) return out;
    }
}

TEST(IoLexer, OperatorsAndPunctuation) {
    const auto t = lexAll("<= >= == != && || < > = ! # % * / + - ^ ? : . , ; ( ) [ ] { }");
    const std::vector<Tok> expected = {
        Tok::LessEqual, Tok::GreaterEqual, Tok::Equal,  Tok::NotEqual,  Tok::And,    Tok::Or,
        Tok::Less,      Tok::Greater,      Tok::Assign, Tok::Bang,      Tok::Hash,   Tok::Percent,
        Tok::Star,      Tok::Slash,        Tok::Plus,   Tok::Minus,     Tok::Caret,  Tok::Question,
        Tok::Colon,     Tok::Dot,          Tok::Comma,  Tok::Semicolon, Tok::LParen, Tok::RParen,
        Tok::LBracket,  Tok::RBracket,     Tok::LBrace, Tok::RBrace,    Tok::End};
    ASSERT_EQ(t.size(), expected.size());
    for (size_t i = 0; i < t.size(); ++i) EXPECT_EQ(t[i].kind, expected[i]) << i;
}

TEST(IoLexer, Numbers) {
    const auto t = lexAll("0 12 3.5 .25 1e3 2.5E-2 7e");
    ASSERT_GE(t.size(), 8u);
    EXPECT_EQ(t[0].number, 0.0);
    EXPECT_EQ(t[1].number, 12.0);
    EXPECT_EQ(t[2].number, 3.5);
    EXPECT_EQ(t[3].number, 0.25);
    EXPECT_EQ(t[4].number, 1000.0);
    EXPECT_EQ(t[5].number, 0.025);
    // "7e" is one identifier: OpenSCAD's lexer takes the longest match, and [A-Za-z0-9_]+
    // matches two characters where a number matches one (2021: `7e = 3; echo(7e);` echoes 3).
    EXPECT_EQ(t[6].kind, Tok::Identifier);
    EXPECT_EQ(t[6].text, "7e");
}

// Identifiers may begin with a digit where the identifier match is longer than the number
// match (example023's `8bit_polyfont`); on a tie the number wins. Each case checked with
// OpenSCAD 2021: `8bit = 4; echo(8bit);` echoes 4, `echo(8e3)` 8000, `echo(12abc)` warns of the
// unknown variable 12abc, `echo(1.5e)` is a syntax error (1.5 then e).
TEST(IoLexer, LongestMatchDecidesBetweenNumbersAndDigitLedIdentifiers) {
    const auto t = lexAll("8bit_polyfont 8e3 12abc 1.5e 1_ 2.5 3e+2x");
    ASSERT_EQ(t.size(), 10u);
    EXPECT_EQ(t[0].kind, Tok::Identifier);
    EXPECT_EQ(t[0].text, "8bit_polyfont");
    EXPECT_EQ(t[1].kind, Tok::Number);
    EXPECT_EQ(t[1].number, 8000.0);
    EXPECT_EQ(t[2].kind, Tok::Identifier);
    EXPECT_EQ(t[2].text, "12abc");
    EXPECT_EQ(t[3].kind, Tok::Number);
    EXPECT_EQ(t[3].number, 1.5);
    EXPECT_EQ(t[4].kind, Tok::Identifier);
    EXPECT_EQ(t[4].text, "e");
    EXPECT_EQ(t[5].kind, Tok::Identifier);
    EXPECT_EQ(t[5].text, "1_");
    EXPECT_EQ(t[6].number, 2.5);
    // "3e+2x": the number 3e+2 (4 characters) beats the word "3e" (2), then x.
    EXPECT_EQ(t[7].kind, Tok::Number);
    EXPECT_EQ(t[7].number, 300.0);
    EXPECT_EQ(t[8].kind, Tok::Identifier);
    EXPECT_EQ(t[8].text, "x");
}

TEST(IoLexer, KeywordsIdentifiersAndDollarNames) {
    const auto t = lexAll("module function if else for let each true false undef $fn _a1 cube");
    const std::vector<Tok> expected = {
        Tok::KwModule,   Tok::KwFunction, Tok::KwIf,       Tok::KwElse,  Tok::KwFor,
        Tok::KwLet,      Tok::KwEach,     Tok::KwTrue,     Tok::KwFalse, Tok::KwUndef,
        Tok::Identifier, Tok::Identifier, Tok::Identifier, Tok::End};
    ASSERT_EQ(t.size(), expected.size());
    for (size_t i = 0; i < t.size(); ++i) EXPECT_EQ(t[i].kind, expected[i]) << i;
    EXPECT_EQ(t[10].text, "$fn");
}

TEST(IoLexer, StringEscapes) {
    const auto t = lexAll(R"("a\"b\\c\n\t\x41\u03a9")");
    ASSERT_EQ(t[0].kind, Tok::String);
    EXPECT_EQ(t[0].text, "a\"b\\c\n\tA\xCE\xA9");
}

TEST(IoLexer, PositionsCountLinesAndCodePoints) {
    // "é" is two bytes but one column.
    const auto t = lexAll("a\n  \"é\" b // comment\n/* x\n y */ c");
    ASSERT_EQ(t.size(), 5u);
    EXPECT_EQ(t[0].loc.line, 1u);
    EXPECT_EQ(t[0].loc.col, 1u);
    EXPECT_EQ(t[1].loc.line, 2u);
    EXPECT_EQ(t[1].loc.col, 3u);
    EXPECT_EQ(t[2].loc.col, 7u);
    EXPECT_EQ(t[3].loc.line, 4u);
    EXPECT_EQ(t[3].loc.col, 7u);
}

TEST(IoLexer, UnterminatedStringIsAnErrorAtItsStart) {
    const auto t = lexAll("x = \"abc");
    EXPECT_EQ(t.back().kind, Tok::Error);
    EXPECT_EQ(t.back().loc.col, 5u);
    EXPECT_NE(t.back().text.find("unterminated string"), std::string::npos);
}

TEST(IoLexer, UnterminatedCommentIsAnErrorAtItsStart) {
    const auto t = lexAll("x\n  /* never closed");
    EXPECT_EQ(t.back().kind, Tok::Error);
    EXPECT_EQ(t.back().loc.line, 2u);
    EXPECT_EQ(t.back().loc.col, 3u);
    EXPECT_NE(t.back().text.find("unterminated comment"), std::string::npos);
}

TEST(IoLexer, StrayCharacterIsAnError) {
    const auto t = lexAll("a @");
    EXPECT_EQ(t.back().kind, Tok::Error);
    EXPECT_EQ(t.back().loc.col, 3u);
}

TEST(IoLexer, IncludeAndUsePaths) {
    const auto t = lexAll("include <lib/a.scad>\nuse <b.scad>");
    EXPECT_EQ(t[0].kind, Tok::IncludePath);
    EXPECT_EQ(t[0].text, "lib/a.scad");
    EXPECT_EQ(t[1].kind, Tok::UsePath);
    EXPECT_EQ(t[1].text, "b.scad");
    EXPECT_EQ(lexAll("include <open").back().kind, Tok::Error);
}

TEST(IoLexer, Utf8Validation) {
    EXPECT_FALSE(io::findInvalidUtf8("plain ascii\n\"héllo ✓ 𝄞\""));
    auto bad = io::findInvalidUtf8("ab\ncd\xFF");
    ASSERT_TRUE(bad);
    EXPECT_EQ(bad->line, 2u);
    EXPECT_EQ(bad->col, 3u);
    EXPECT_TRUE(io::findInvalidUtf8("\xC0\x80"));      // overlong
    EXPECT_TRUE(io::findInvalidUtf8("\xED\xA0\x80"));  // surrogate
    EXPECT_TRUE(io::findInvalidUtf8("\xE2\x82"));      // truncated
}

TEST(IoLexer, ByteOrderMarkIsSkipped) {
    const auto t = lexAll("\xEF\xBB\xBFx");
    EXPECT_EQ(t[0].kind, Tok::Identifier);
    EXPECT_EQ(t[0].loc.col, 1u);
}
