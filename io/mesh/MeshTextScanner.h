// Scanning the text mesh formats (OBJ, ASCII STL) one token at a time, with the 1-based line
// and column of each token for `file:line:col` errors. Numbers are read with std::from_chars:
// the double nearest the text, independent of the locale.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

namespace io::detail {

class MeshTextScanner {
public:
    // lineContinuations: a backslash ending a line joins the next line to it (OBJ's rule), so
    // skipBlanks() steps over it as over a blank.
    explicit MeshTextScanner(std::string_view text, bool lineContinuations = false)
        : text_(text), lineContinuations_(lineContinuations) {}

    // Skips spaces and tabs (and a carriage return before a newline), not newlines, except
    // the newline of a line continuation.
    void skipBlanks() {
        while (pos_ < text_.size()) {
            if (isBlank(text_[pos_]))
                advance();
            else if (const size_t end = continuationEnd(); end != pos_)
                while (pos_ < end) advance();
            else
                return;
        }
    }
    // Skips blanks and newlines.
    void skipWhitespace() {
        while (pos_ < text_.size() && (isBlank(text_[pos_]) || text_[pos_] == '\n')) advance();
    }
    // Moves past the next newline (or to the end).
    void skipLine() {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
        if (pos_ < text_.size()) advance();
    }
    bool atEnd() const { return pos_ >= text_.size(); }
    bool atLineEnd() const { return atEnd() || text_[pos_] == '\n'; }
    // At a line's end, a blank or a line continuation: where a token ends.
    bool atSeparator() const {
        return atLineEnd() || isBlank(text_[pos_]) || continuationEnd() != pos_;
    }

    // The next run of characters that are not blanks or newlines (empty at a line's end).
    std::string_view word() {
        const size_t start = pos_;
        while (pos_ < text_.size() && !isBlank(text_[pos_]) && text_[pos_] != '\n') ++pos_;
        column_ += uint32_t(pos_ - start);
        return text_.substr(start, pos_ - start);
    }

    // A finite number at the cursor (an optional '+' or '-' first), or false with the cursor
    // unmoved.
    bool number(double& value) {
        size_t start = pos_;
        if (start < text_.size() && text_[start] == '+') ++start;
        const char* end = text_.data() + text_.size();
        const auto [ptr, ec] = std::from_chars(text_.data() + start, end, value);
        if (ec != std::errc() || !std::isfinite(value)) return false;
        column_ += uint32_t(size_t(ptr - text_.data()) - pos_);
        pos_ = size_t(ptr - text_.data());
        return true;
    }
    // An integer at the cursor (an optional '+' or '-' first), or false with the cursor
    // unmoved.
    bool integer(int64_t& value) {
        size_t start = pos_;
        if (start < text_.size() && text_[start] == '+') ++start;
        const char* end = text_.data() + text_.size();
        const auto [ptr, ec] = std::from_chars(text_.data() + start, end, value);
        if (ec != std::errc()) return false;
        column_ += uint32_t(size_t(ptr - text_.data()) - pos_);
        pos_ = size_t(ptr - text_.data());
        return true;
    }
    // The character at the cursor, or '\0' at the end.
    char peek() const { return pos_ < text_.size() ? text_[pos_] : '\0'; }
    void advance() {
        if (text_[pos_] == '\n') {
            ++line_;
            column_ = 1;
        } else {
            ++column_;
        }
        ++pos_;
    }

    uint32_t line() const { return line_; }
    uint32_t column() const { return column_; }

private:
    static bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

    // Past the newline of a line continuation at the cursor (a backslash, optional carriage
    // returns, a newline), or pos_ when there is none.
    size_t continuationEnd() const {
        if (!lineContinuations_ || text_[pos_] != '\\') return pos_;
        size_t end = pos_ + 1;
        while (end < text_.size() && text_[end] == '\r') ++end;
        return end < text_.size() && text_[end] == '\n' ? end + 1 : pos_;
    }

    std::string_view text_;
    bool lineContinuations_;
    size_t pos_ = 0;
    uint32_t line_ = 1;
    uint32_t column_ = 1;
};

// ASCII case-insensitive equality (STL keywords are lower case by the format, upper case by
// some writers).
inline bool sameWord(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i) {
        const char x = a[i] >= 'A' && a[i] <= 'Z' ? char(a[i] - 'A' + 'a') : a[i];
        const char y = b[i] >= 'A' && b[i] <= 'Z' ? char(b[i] - 'A' + 'a') : b[i];
        if (x != y) return false;
    }
    return true;
}

}  // namespace io::detail
