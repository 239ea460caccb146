// OpenSCAD's tokens. Follows OpenSCAD's lexer.l: numbers are decimal with optional fraction and
// exponent, strings take C escapes plus \x and \u, include/use read a <path> directly.
#include "io/Lexer.h"

#include <cctype>
#include <charconv>
#include <cstdlib>

namespace io {

const char* tokenName(Tok kind) {
    switch (kind) {
        case Tok::End:
            return "end of file";
        case Tok::Error:
            return "invalid token";
        case Tok::Identifier:
            return "identifier";
        case Tok::Number:
            return "number";
        case Tok::String:
            return "string";
        case Tok::IncludePath:
            return "include";
        case Tok::UsePath:
            return "use";
        case Tok::KwModule:
            return "'module'";
        case Tok::KwFunction:
            return "'function'";
        case Tok::KwIf:
            return "'if'";
        case Tok::KwElse:
            return "'else'";
        case Tok::KwFor:
            return "'for'";
        case Tok::KwLet:
            return "'let'";
        case Tok::KwEach:
            return "'each'";
        case Tok::KwTrue:
            return "'true'";
        case Tok::KwFalse:
            return "'false'";
        case Tok::KwUndef:
            return "'undef'";
        case Tok::LParen:
            return "'('";
        case Tok::RParen:
            return "')'";
        case Tok::LBracket:
            return "'['";
        case Tok::RBracket:
            return "']'";
        case Tok::LBrace:
            return "'{'";
        case Tok::RBrace:
            return "'}'";
        case Tok::Comma:
            return "','";
        case Tok::Semicolon:
            return "';'";
        case Tok::Colon:
            return "':'";
        case Tok::Question:
            return "'?'";
        case Tok::Dot:
            return "'.'";
        case Tok::Assign:
            return "'='";
        case Tok::Plus:
            return "'+'";
        case Tok::Minus:
            return "'-'";
        case Tok::Star:
            return "'*'";
        case Tok::Slash:
            return "'/'";
        case Tok::Percent:
            return "'%'";
        case Tok::Caret:
            return "'^'";
        case Tok::Bang:
            return "'!'";
        case Tok::Hash:
            return "'#'";
        case Tok::Less:
            return "'<'";
        case Tok::LessEqual:
            return "'<='";
        case Tok::Greater:
            return "'>'";
        case Tok::GreaterEqual:
            return "'>='";
        case Tok::Equal:
            return "'=='";
        case Tok::NotEqual:
            return "'!='";
        case Tok::And:
            return "'&&'";
        case Tok::Or:
            return "'||'";
    }
    return "token";
}

std::optional<TextPosition> findInvalidUtf8(std::string_view text) {
    uint32_t line = 1, col = 1;
    size_t i = 0;
    const size_t n = text.size();
    while (i < n) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c < 0x80) {
            if (c == '\n') {
                ++line;
                col = 1;
            } else {
                ++col;
            }
            ++i;
            continue;
        }
        // Multi-byte sequence: its length, the smallest code point it may encode (no overlong
        // forms), then continuation bytes.
        int length = 0;
        uint32_t codePoint = 0, minimum = 0;
        if ((c & 0xE0) == 0xC0) {
            length = 2, codePoint = c & 0x1F, minimum = 0x80;
        } else if ((c & 0xF0) == 0xE0) {
            length = 3, codePoint = c & 0x0F, minimum = 0x800;
        } else if ((c & 0xF8) == 0xF0) {
            length = 4, codePoint = c & 0x07, minimum = 0x10000;
        } else {
            return TextPosition{line, col};
        }
        if (i + length > n) return TextPosition{line, col};
        for (int k = 1; k < length; ++k) {
            const auto cc = static_cast<unsigned char>(text[i + k]);
            if ((cc & 0xC0) != 0x80) return TextPosition{line, col};
            codePoint = (codePoint << 6) | (cc & 0x3F);
        }
        if (codePoint < minimum || codePoint > 0x10FFFF ||
            (codePoint >= 0xD800 && codePoint <= 0xDFFF))
            return TextPosition{line, col};
        i += length;
        ++col;
    }
    return std::nullopt;
}

Lexer::Lexer(std::string_view text, uint32_t fileIndex) : text_(text), file_(fileIndex) {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;
}

void Lexer::advance() {
    const char c = text_[pos_++];
    if (c == '\n') {
        ++line_;
        col_ = 1;
    } else if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) {
        ++col_;  // continuation bytes belong to the code point already counted
    }
}

// Skips blanks and comments; false (with error set) for an unterminated block comment.
bool Lexer::skipSpaceAndComments(Token& error) {
    for (;;) {
        const char c = peek();
        if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v') {
            advance();
        } else if (c == '/' && peek(1) == '/') {
            while (pos_ < text_.size() && peek() != '\n') advance();
        } else if (c == '/' && peek(1) == '*') {
            const Loc start = here();
            advance();
            advance();
            while (pos_ < text_.size() && !(peek() == '*' && peek(1) == '/')) advance();
            if (pos_ >= text_.size()) {
                error = {Tok::Error, start, "unterminated comment (missing '*/')", 0.0};
                return false;
            }
            advance();
            advance();
        } else {
            return true;
        }
    }
}

Token Lexer::next() {
    Token error;
    if (!skipSpaceAndComments(error)) return error;
    const Loc start = here();
    if (pos_ >= text_.size()) return {Tok::End, start, {}, 0.0};
    const char c = peek();
    // OpenSCAD's lexer takes the longest match, a number on a tie: "8bit" is an identifier
    // (example023's 8bit_polyfont), "8e3" and "12" are numbers.
    if (std::isdigit(static_cast<unsigned char>(c)))
        return wordLength() > numberLength() ? lexIdentifierOrKeyword() : lexNumber();
    if (c == '.' && std::isdigit(static_cast<unsigned char>(peek(1)))) return lexNumber();
    if (c == '"') return lexString();
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_' || c == '$')
        return lexIdentifierOrKeyword();

    auto single = [&](Tok kind) {
        advance();
        return Token{kind, start, {}, 0.0};
    };
    auto pair = [&](char second, Tok ifPair, Tok otherwise) {
        advance();
        if (peek() == second) {
            advance();
            return Token{ifPair, start, {}, 0.0};
        }
        return Token{otherwise, start, {}, 0.0};
    };
    switch (c) {
        case '(':
            return single(Tok::LParen);
        case ')':
            return single(Tok::RParen);
        case '[':
            return single(Tok::LBracket);
        case ']':
            return single(Tok::RBracket);
        case '{':
            return single(Tok::LBrace);
        case '}':
            return single(Tok::RBrace);
        case ',':
            return single(Tok::Comma);
        case ';':
            return single(Tok::Semicolon);
        case ':':
            return single(Tok::Colon);
        case '?':
            return single(Tok::Question);
        case '.':
            return single(Tok::Dot);
        case '+':
            return single(Tok::Plus);
        case '-':
            return single(Tok::Minus);
        case '*':
            return single(Tok::Star);
        case '/':
            return single(Tok::Slash);
        case '%':
            return single(Tok::Percent);
        case '^':
            return single(Tok::Caret);
        case '#':
            return single(Tok::Hash);
        case '=':
            return pair('=', Tok::Equal, Tok::Assign);
        case '!':
            return pair('=', Tok::NotEqual, Tok::Bang);
        case '<':
            return pair('=', Tok::LessEqual, Tok::Less);
        case '>':
            return pair('=', Tok::GreaterEqual, Tok::Greater);
        case '&':
            if (peek(1) == '&') {
                advance();
                return single(Tok::And);
            }
            break;
        case '|':
            if (peek(1) == '|') {
                advance();
                return single(Tok::Or);
            }
            break;
        default:
            break;
    }
    // A stray character: report it and skip the whole code point.
    std::string shown(1, c);
    advance();
    while (pos_ < text_.size() && (static_cast<unsigned char>(peek()) & 0xC0) == 0x80) {
        shown += peek();
        advance();
    }
    return {Tok::Error, start, "unexpected character '" + shown + "'", 0.0};
}

// The length of the number at the cursor: digits, an optional fraction, an optional exponent.
size_t Lexer::numberLength() const {
    auto digit = [&](size_t i) { return std::isdigit(static_cast<unsigned char>(peek(i))) != 0; };
    size_t n = 0;
    while (digit(n)) ++n;
    if (peek(n) == '.') {
        ++n;
        while (digit(n)) ++n;
    }
    if ((peek(n) == 'e' || peek(n) == 'E') &&
        (digit(n + 1) || ((peek(n + 1) == '+' || peek(n + 1) == '-') && digit(n + 2)))) {
        n += peek(n + 1) == '+' || peek(n + 1) == '-' ? 2 : 1;
        while (digit(n)) ++n;
    }
    return n;
}

// The length of the run of identifier characters (letters, digits, '_') at the cursor.
size_t Lexer::wordLength() const {
    size_t n = 0;
    while (std::isalnum(static_cast<unsigned char>(peek(n))) || peek(n) == '_') ++n;
    return n;
}

Token Lexer::lexNumber() {
    const Loc start = here();
    const size_t begin = pos_;
    for (size_t n = numberLength(); n > 0; --n) advance();
    // strtod needs a terminated string; numbers are short, so a copy is cheap.
    const std::string digits(text_.substr(begin, pos_ - begin));
    return {Tok::Number, start, {}, std::strtod(digits.c_str(), nullptr)};
}

void appendUtf8(std::string& out, uint32_t cp) {
    if (cp < 0x80) {
        out += static_cast<char>(cp);
    } else if (cp < 0x800) {
        out += static_cast<char>(0xC0 | (cp >> 6));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
        out += static_cast<char>(0xE0 | (cp >> 12));
        out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
        out += static_cast<char>(0xF0 | (cp >> 18));
        out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
        out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    }
}

Token Lexer::lexString() {
    const Loc start = here();
    advance();  // the opening quote
    std::string value;
    while (pos_ < text_.size() && peek() != '"') {
        const char c = peek();
        if (c != '\\') {
            value += c;
            advance();
            continue;
        }
        const Loc escapeLoc = here();
        advance();
        if (pos_ >= text_.size()) break;
        const char e = peek();
        advance();
        switch (e) {
            case 'n':
                value += '\n';
                break;
            case 't':
                value += '\t';
                break;
            case 'r':
                value += '\r';
                break;
            case '\\':
                value += '\\';
                break;
            case '"':
                value += '"';
                break;
            case '\'':
                value += '\'';
                break;
            case 'x':
            case 'u':
            case 'U': {
                // \xNN (up to 7F, as OpenSCAD), \uNNNN, \UNNNNNN
                const int digits = e == 'x' ? 2 : e == 'u' ? 4 : 6;
                uint32_t cp = 0;
                int read = 0;
                while (read < digits && std::isxdigit(static_cast<unsigned char>(peek()))) {
                    const char h = peek();
                    cp = cp * 16 + (std::isdigit(static_cast<unsigned char>(h))
                                        ? h - '0'
                                        : (std::tolower(static_cast<unsigned char>(h)) - 'a' + 10));
                    advance();
                    ++read;
                }
                if (read == 0 || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF) ||
                    (e == 'x' && cp > 0x7F) || cp == 0)
                    return {Tok::Error, escapeLoc, "invalid escape sequence in string", 0.0};
                appendUtf8(value, cp);
                break;
            }
            default:
                // OpenSCAD keeps unknown escapes verbatim (with a warning); so do we.
                value += '\\';
                value += e;
                break;
        }
    }
    if (pos_ >= text_.size())
        return {Tok::Error, start, "unterminated string (missing closing '\"')", 0.0};
    advance();  // the closing quote
    return {Tok::String, start, std::move(value), 0.0};
}

Token Lexer::lexIdentifierOrKeyword() {
    const Loc start = here();
    const size_t begin = pos_;
    advance();
    while (std::isalnum(static_cast<unsigned char>(peek())) || peek() == '_') advance();
    const std::string_view word = text_.substr(begin, pos_ - begin);
    struct Keyword {
        std::string_view word;
        Tok kind;
    };
    static constexpr Keyword keywords[] = {
        {"module", Tok::KwModule}, {"function", Tok::KwFunction}, {"if", Tok::KwIf},
        {"else", Tok::KwElse},     {"for", Tok::KwFor},           {"let", Tok::KwLet},
        {"each", Tok::KwEach},     {"true", Tok::KwTrue},         {"false", Tok::KwFalse},
        {"undef", Tok::KwUndef},
    };
    for (const Keyword& k : keywords)
        if (word == k.word) return {k.kind, start, std::string(word), 0.0};
    if (word == "include") return lexAnglePath(Tok::IncludePath, start);
    if (word == "use") return lexAnglePath(Tok::UsePath, start);
    return {Tok::Identifier, start, std::string(word), 0.0};
}

// include <path> / use <path>: the path runs to the next '>' on the same line.
Token Lexer::lexAnglePath(Tok kind, Loc start) {
    while (peek() == ' ' || peek() == '\t' || peek() == '\r' || peek() == '\n') advance();
    const char* what = kind == Tok::IncludePath ? "include" : "use";
    if (peek() != '<')
        return {Tok::Error, start, std::string("expected '<file>' after '") + what + "'", 0.0};
    advance();
    const size_t begin = pos_;
    while (pos_ < text_.size() && peek() != '>' && peek() != '\n') advance();
    if (peek() != '>')
        return {Tok::Error, start, std::string("unterminated '") + what + " <' (missing '>')", 0.0};
    std::string path(text_.substr(begin, pos_ - begin));
    advance();
    return {kind, start, std::move(path), 0.0};
}

}  // namespace io
