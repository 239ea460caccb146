#include "io/Value.h"

#include <cmath>
#include <cstdio>
#include <cstring>

namespace io {

double Range::count() const {
    if (step == 0.0 || std::isnan(begin) || std::isnan(step) || std::isnan(end)) return 0.0;
    // A little slack so [0:0.1:0.3] reaches 0.3 despite rounding, as in OpenSCAD.
    const double n = std::floor((end - begin) / step + 1e-9);
    return n < 0.0 ? 0.0 : n + 1.0;
}

bool Value::truthy() const {
    switch (type()) {
        case Type::Undef:
            return false;
        case Type::Bool:
            return asBool();
        case Type::Number:
            return number() != 0.0;
        case Type::String:
            return !string().empty();
        case Type::Vector:
            return !list().empty();
        case Type::Range:
            return true;
        case Type::Function:
            return true;
    }
    return false;
}

std::string formatNumber(double d) {
    if (d == 0.0) return "0";
    if (std::isnan(d)) return "nan";
    if (std::isinf(d)) return d > 0 ? "inf" : "-inf";
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.6g", d);
    // Shorten the exponent as OpenSCAD does: 1e+06 -> 1e+6, 1e-07 -> 1e-7.
    char* e = std::strchr(buffer, 'e');
    if (e && (e[1] == '+' || e[1] == '-')) {
        char* digits = e + 2;
        char* firstNonZero = digits;
        while (*firstNonZero == '0' && firstNonZero[1] != '\0') ++firstNonZero;
        if (firstNonZero != digits)
            std::memmove(digits, firstNonZero, std::strlen(firstNonZero) + 1);
    }
    return buffer;
}

static void quote(std::string& out, const std::string& s) {
    out += '"';
    for (char c : s) {
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
            case '\t':
                out += "\\t";
                break;
            case '\r':
                out += "\\r";
                break;
            default:
                out += c;
        }
    }
    out += '"';
}

static void append(std::string& out, const Value& v, bool quoteStrings) {
    switch (v.type()) {
        case Value::Type::Undef:
            out += "undef";
            break;
        case Value::Type::Bool:
            out += v.asBool() ? "true" : "false";
            break;
        case Value::Type::Number:
            out += formatNumber(v.number());
            break;
        case Value::Type::String:
            if (quoteStrings)
                quote(out, v.string());
            else
                out += v.string();
            break;
        case Value::Type::Vector: {
            out += '[';
            bool first = true;
            for (const Value& item : v.list()) {
                if (!first) out += ", ";
                first = false;
                append(out, item, true);
            }
            out += ']';
            break;
        }
        case Value::Type::Range: {
            const Range& r = v.range();
            out += '[' + formatNumber(r.begin) + " : " + formatNumber(r.step) + " : " +
                   formatNumber(r.end) + ']';
            break;
        }
        case Value::Type::Function:
            out += "function";
            break;
    }
}

std::string Value::repr() const {
    std::string out;
    append(out, *this, true);
    return out;
}

std::string Value::toString() const {
    std::string out;
    append(out, *this, false);
    return out;
}

bool Value::operator==(const Value& other) const {
    if (type() != other.type()) return false;
    switch (type()) {
        case Type::Undef:
            return true;
        case Type::Bool:
            return asBool() == other.asBool();
        case Type::Number:
            return number() == other.number();
        case Type::String:
            return string() == other.string();
        case Type::Vector:
            return list() == other.list();
        case Type::Range:
            return range().begin == other.range().begin && range().step == other.range().step &&
                   range().end == other.range().end;
        case Type::Function:
            return &function() == &other.function();
    }
    return false;
}

const char* Value::typeName(Type t) {
    switch (t) {
        case Type::Undef:
            return "undefined";
        case Type::Bool:
            return "bool";
        case Type::Number:
            return "number";
        case Type::String:
            return "string";
        case Type::Vector:
            return "vector";
        case Type::Range:
            return "range";
        case Type::Function:
            return "function";
    }
    return "value";
}

}  // namespace io
