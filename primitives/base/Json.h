// A small streaming JSON writer for the command line's output (probe, info, stats). It appends
// to a caller-owned std::string, so a loop that reuses one string allocates nothing once the
// string has grown to its largest size. The writer inserts commas itself; callers only open,
// name and close. Numbers print in the shortest form that reads back to the same double;
// a non-finite number prints as null (JSON has no inf or NaN).
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

namespace csg {

class JsonWriter {
public:
    explicit JsonWriter(std::string& out) : out_(out) {}

    JsonWriter& beginObject() { return open('{'); }
    JsonWriter& endObject() { return close('}'); }
    JsonWriter& beginArray() { return open('['); }
    JsonWriter& endArray() { return close(']'); }

    // The name of the next member of the current object.
    JsonWriter& key(std::string_view name) {
        separate();
        quote(name);
        out_ += ':';
        afterKey_ = true;
        return *this;
    }

    JsonWriter& value(double v) {
        separate();
        if (!std::isfinite(v)) {
            out_ += "null";
            return *this;
        }
        if (v == 0.0) v = 0.0;  // -0 prints as 0: nobody wants "t": -0
        char buf[32];
        const auto r = std::to_chars(buf, buf + sizeof buf, v);
        out_.append(buf, r.ptr);
        return *this;
    }
    JsonWriter& value(int64_t v) {
        separate();
        char buf[24];
        const auto r = std::to_chars(buf, buf + sizeof buf, v);
        out_.append(buf, r.ptr);
        return *this;
    }
    JsonWriter& value(uint64_t v) {
        separate();
        char buf[24];
        const auto r = std::to_chars(buf, buf + sizeof buf, v);
        out_.append(buf, r.ptr);
        return *this;
    }
    JsonWriter& value(int v) { return value(static_cast<int64_t>(v)); }
    JsonWriter& value(uint32_t v) { return value(static_cast<uint64_t>(v)); }
    JsonWriter& value(bool v) {
        separate();
        out_ += v ? "true" : "false";
        return *this;
    }
    JsonWriter& value(std::string_view s) {
        separate();
        quote(s);
        return *this;
    }
    JsonWriter& value(const char* s) { return value(std::string_view(s)); }
    JsonWriter& null() {
        separate();
        out_ += "null";
        return *this;
    }
    // Inserts text that is already valid JSON (a value cached by the caller).
    JsonWriter& raw(std::string_view json) {
        separate();
        out_ += json;
        return *this;
    }

    // A fixed-size numeric array, e.g. a point: [x, y, z].
    template <class Vec>
    JsonWriter& vec(const Vec& v, int n) {
        beginArray();
        for (int i = 0; i < n; ++i) value(static_cast<double>(v[i]));
        return endArray();
    }

    // Appends s as a quoted JSON string, escaping quotes, backslashes and control characters.
    // Bytes >= 0x80 pass through: the input is UTF-8 (the language rejects other encodings).
    static void quoteInto(std::string& out, std::string_view s) {
        static constexpr char kHex[] = "0123456789abcdef";
        out += '"';
        for (const char c : s) {
            const auto u = static_cast<unsigned char>(c);
            switch (c) {
                case '"':
                    out += "\\\"";
                    break;
                case '\\':
                    out += "\\\\";
                    break;
                case '\n':
                    out += "\\n";
                    break;
                case '\r':
                    out += "\\r";
                    break;
                case '\t':
                    out += "\\t";
                    break;
                default:
                    if (u < 0x20) {
                        out += "\\u00";
                        out += kHex[u >> 4];
                        out += kHex[u & 15];
                    } else {
                        out += c;
                    }
            }
        }
        out += '"';
    }

private:
    JsonWriter& open(char c) {
        separate();
        out_ += c;
        first_ = true;
        return *this;
    }
    JsonWriter& close(char c) {
        out_ += c;
        first_ = false;
        return *this;
    }
    // A comma before every element but the first of its container, and none after a key.
    void separate() {
        if (afterKey_) {
            afterKey_ = false;
        } else if (!first_) {
            out_ += ',';
        }
        first_ = false;
    }
    void quote(std::string_view s) { quoteInto(out_, s); }

    std::string& out_;
    bool first_ = true;  // nothing written yet in the innermost container (or at top level)
    bool afterKey_ = false;
};

}  // namespace csg
