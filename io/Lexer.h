// Tokens of OpenSCAD's language, produced one at a time (a 50 MB part is never held as a token
// list). Positions are 1-based lines and columns counted in UTF-8 code points.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace io {

// A place in a source file; file indexes the evaluator's file table (Model::files).
struct Loc {
    uint32_t file = 0;
    uint32_t line = 0;
    uint32_t col = 0;
};

enum class Tok : uint8_t {
    End,
    Error,        // text holds the message; loc where the problem starts
    Identifier,   // text; includes $-variables such as $fn
    Number,       // number
    String,       // text, escapes already decoded
    IncludePath,  // include <text>
    UsePath,      // use <text>
    KwModule,
    KwFunction,
    KwIf,
    KwElse,
    KwFor,
    KwLet,
    KwEach,
    KwTrue,
    KwFalse,
    KwUndef,
    LParen,
    RParen,
    LBracket,
    RBracket,
    LBrace,
    RBrace,
    Comma,
    Semicolon,
    Colon,
    Question,
    Dot,
    Assign,
    Plus,
    Minus,
    Star,
    Slash,
    Percent,
    Caret,
    Bang,
    Hash,
    Less,
    LessEqual,
    Greater,
    GreaterEqual,
    Equal,
    NotEqual,
    And,
    Or,
};

// A readable name for messages: "';'", "identifier", "end of file".
const char* tokenName(Tok kind);

struct Token {
    Tok kind = Tok::End;
    Loc loc;
    std::string text;
    double number = 0.0;
};

// The position (line, col) of the first byte that is not valid UTF-8, or nothing when the
// whole text is valid (overlong forms, surrogates and values above U+10FFFF are invalid).
struct TextPosition {
    uint32_t line, col;
};
std::optional<TextPosition> findInvalidUtf8(std::string_view text);

// Appends the UTF-8 encoding of a Unicode code point (string escapes, chr()).
void appendUtf8(std::string& out, uint32_t cp);

class Lexer {
public:
    // text must outlive the lexer; a leading UTF-8 byte-order mark is skipped.
    Lexer(std::string_view text, uint32_t fileIndex);

    // The next token; End forever after the end; Error tokens for unterminated strings and
    // comments, bad escapes and stray characters (the lexer then skips that character).
    Token next();

private:
    void advance();  // one byte, keeping line and col
    bool skipSpaceAndComments(Token& error);
    Token lexNumber();
    Token lexString();
    Token lexIdentifierOrKeyword();
    size_t numberLength() const;
    size_t wordLength() const;
    Token lexAnglePath(Tok kind, Loc start);
    Loc here() const { return {file_, line_, col_}; }
    char peek(size_t ahead = 0) const {
        return pos_ + ahead < text_.size() ? text_[pos_ + ahead] : '\0';
    }

    std::string_view text_;
    size_t pos_ = 0;
    uint32_t file_;
    uint32_t line_ = 1;
    uint32_t col_ = 1;
};

}  // namespace io
