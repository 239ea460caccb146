#include "io/Value.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "io/ExprPrint.h"
#include "primitives/base/Tolerances.h"

namespace io {

double Range::count() const {
    if (step == 0.0 || std::isnan(begin) || std::isnan(step) || std::isnan(end)) return 0.0;
    // A little slack so [0:0.1:0.3] reaches 0.3 despite rounding, as in OpenSCAD.
    const double n = std::floor((end - begin) / step + csg::tol::kRangeStepSlack);
    return n < 0.0 ? 0.0 : n + 1.0;
}

Value::Value(ValueList list) {
    uint32_t deepest = 0;
    for (const Value& item : list) deepest = std::max(deepest, item.depth());
    v_ = std::make_shared<const ListData>(ListData{std::move(list), deepest + 1});
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

void appendQuoted(std::string& out, const std::string& s) {
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

static void append(std::string& out, const Value& v, bool quoteStrings, WorkBudget& budget) {
    if (!budget.spend()) return;
    const size_t before = out.size();
    switch (v.type()) {
        case Value::Type::Undef:
            out += "undef";
            break;
        case Value::Type::Bool:
            out += v.asBool() ? "true" : "false";
            break;
        case Value::Type::Number:
            out += formatNumber(v.number());
            budget.spend(out.size() - before);  // printing costs a unit per character
            break;
        case Value::Type::String:
            if (!budget.spend(v.string().size())) return;
            if (quoteStrings)
                appendQuoted(out, v.string());
            else
                out += v.string();
            break;
        case Value::Type::Vector: {
            out += '[';
            bool first = true;
            for (const Value& item : v.list()) {
                if (!first) out += ", ";
                first = false;
                append(out, item, true, budget);
                if (budget.exhausted) return;
            }
            out += ']';
            break;
        }
        case Value::Type::Range: {
            const Range& r = v.range();
            out += '[' + formatNumber(r.begin) + " : " + formatNumber(r.step) + " : " +
                   formatNumber(r.end) + ']';
            budget.spend(out.size() - before);
            break;
        }
        case Value::Type::Function:
            // Its source, as OpenSCAD prints a function value: function(x) (x + 1).
            appendFunctionLiteral(out, *v.function().literal);
            budget.spend(out.size() - before);
            break;
    }
}

std::string Value::repr(WorkBudget& budget) const {
    std::string out;
    append(out, *this, true, budget);
    return out;
}

std::string Value::toString(WorkBudget& budget) const {
    std::string out;
    append(out, *this, false, budget);
    return out;
}

std::string Value::repr() const {
    WorkBudget unlimited;
    return repr(unlimited);
}

std::string Value::toString() const {
    WorkBudget unlimited;
    return toString(unlimited);
}

std::string Value::brief(size_t maxChars) const {
    WorkBudget budget{maxChars};
    std::string out = repr(budget);
    if (budget.exhausted || out.size() > maxChars) {
        out.resize(std::min(out.size(), maxChars));
        out += "...";
    }
    return out;
}

// How many values OpenSCAD 2021 says a range has (RangeType::numValues), for comparing ranges:
// none when a part is NaN or the step points away from the end, one when begin == end or the
// step is infinite, "unbounded" (infinity here) for an infinite end or a zero step.
static double openscadRangeSize(const Range& r) {
    if (std::isnan(r.begin) || std::isnan(r.step) || std::isnan(r.end)) return 0.0;
    if (r.step < 0 ? r.begin < r.end : r.begin > r.end) return 0.0;
    if (r.begin == r.end || std::isinf(r.step)) return 1.0;
    if (std::isinf(r.begin) || std::isinf(r.end) || r.step == 0.0) return INFINITY;
    return r.count();
}

// OpenSCAD 2021's range equality: as many values, and then (unless there are none) the same
// begin and step; the end itself is not compared ([0:2:4] == [0:2:5]), and two empty ranges
// are equal whatever their parts, NaN included (BOSL2's is_nan(x), x != x, relies on it).
static bool rangesEqual(const Range& a, const Range& b) {
    const double n = openscadRangeSize(a);
    if (n != openscadRangeSize(b)) return false;
    return n == 0.0 || (a.begin == b.begin && a.step == b.step);
}

bool Value::equals(const Value& other, WorkBudget& budget) const {
    if (!budget.spend()) return false;
    if (type() != other.type()) return false;
    switch (type()) {
        case Type::Undef:
            return true;
        case Type::Bool:
            return asBool() == other.asBool();
        case Type::Number:
            return number() == other.number();
        case Type::String:
            return budget.spend(string().size()) && string() == other.string();
        case Type::Vector: {
            const ValueList &a = list(), &b = other.list();
            if (a.size() != b.size()) return false;
            for (size_t i = 0; i < a.size(); ++i)
                if (!a[i].equals(b[i], budget)) return false;
            return true;
        }
        case Type::Range:
            return rangesEqual(range(), other.range());
        case Type::Function:
            return &function() == &other.function();
    }
    return false;
}

bool Value::operator==(const Value& other) const {
    WorkBudget unlimited;
    return equals(other, unlimited);
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
