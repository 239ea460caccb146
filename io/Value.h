// OpenSCAD's values: undef, bool, number, string, vector, range and function. Values are
// immutable and cheap to copy (strings, vectors and functions are shared).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace io {

struct FunctionLiteralExpr;
struct Context;

struct Range {
    double begin = 0.0, step = 1.0, end = 0.0;
    // The number of values it yields ([0:2:5] yields 0 2 4), 0 for a step of the wrong sign.
    // Huge ranges are capped by the caller.
    double count() const;
};

// A function literal with the context it closes over.
struct FunctionValue {
    const FunctionLiteralExpr* literal;
    std::shared_ptr<Context> closure;
};

class Value;
using ValueList = std::vector<Value>;

// Work units for walks over values. Lists share their elements, so a list holding the same big
// list a thousand times is cheap to build but costly to print, compare or add: such walks
// spend one unit per element (and per character printed) and stop early, with exhausted set,
// once the budget runs out. The evaluator turns an exhausted budget into an error.
struct WorkBudget {
    uint64_t left = UINT64_MAX;
    bool exhausted = false;

    // False (and exhausted) when fewer than n units are left.
    bool spend(uint64_t n = 1) {
        if (n > left) {
            left = 0;
            exhausted = true;
            return false;
        }
        left -= n;
        return true;
    }
};

class Value {
public:
    enum class Type : uint8_t { Undef, Bool, Number, String, Vector, Range, Function };

    Value() = default;
    Value(bool b) : v_(b) {}
    Value(double d) : v_(d) {}
    Value(int i) : v_(static_cast<double>(i)) {}
    Value(std::string s) : v_(std::make_shared<const std::string>(std::move(s))) {}
    Value(const char* s) : Value(std::string(s)) {}
    Value(ValueList list);
    Value(Range r) : v_(r) {}
    Value(FunctionValue f) : v_(std::make_shared<const FunctionValue>(std::move(f))) {}

    Type type() const { return static_cast<Type>(v_.index()); }
    bool isUndef() const { return type() == Type::Undef; }
    bool isBool() const { return type() == Type::Bool; }
    bool isNumber() const { return type() == Type::Number; }
    bool isString() const { return type() == Type::String; }
    bool isVector() const { return type() == Type::Vector; }
    bool isRange() const { return type() == Type::Range; }
    bool isFunction() const { return type() == Type::Function; }

    // Accessors; only valid for the matching type.
    bool asBool() const { return std::get<bool>(v_); }
    double number() const { return std::get<double>(v_); }
    const std::string& string() const { return *std::get<StringPtr>(v_); }
    const ValueList& list() const { return std::get<ListPtr>(v_)->items; }
    const Range& range() const { return std::get<Range>(v_); }
    const FunctionValue& function() const { return *std::get<FunctionPtr>(v_); }

    // How deeply lists nest in this value: 0 for a non-list, 1 for [1, 2], 2 for [[1]].
    uint32_t depth() const { return isVector() ? std::get<ListPtr>(v_)->depth : 0; }

    // OpenSCAD truthiness: false, 0, "", [], undef are false; NaN is... true (as OpenSCAD).
    bool truthy() const;

    // How echo() shows it: strings quoted inside and at top level ("a").
    std::string repr() const;
    // How str() shows it: top-level strings bare, nested ones quoted.
    std::string toString() const;
    // The same within a budget; the text is cut short when the budget runs out.
    std::string repr(WorkBudget& budget) const;
    std::string toString(WorkBudget& budget) const;
    // repr() for a message: at most about maxChars characters, "..." when cut.
    std::string brief(size_t maxChars = 60) const;

    bool operator==(const Value& other) const;
    // == within a budget (one unit per element compared); false when the budget runs out.
    bool equals(const Value& other, WorkBudget& budget) const;

    static const char* typeName(Type t);
    const char* typeName() const { return typeName(type()); }

private:
    using StringPtr = std::shared_ptr<const std::string>;
    // A list knows its nesting depth, so the evaluator can refuse lists nested deeper than
    // its recursive walks (printing, comparing, freeing) can follow.
    struct ListData {
        ValueList items;
        uint32_t depth;
    };
    using ListPtr = std::shared_ptr<const ListData>;
    using FunctionPtr = std::shared_ptr<const FunctionValue>;
    std::variant<std::monostate, bool, double, StringPtr, ListPtr, Range, FunctionPtr> v_;
};

// OpenSCAD's number format: %g with 6 significant digits and a short exponent
// (1e+6, 1.23457e-7); -0 prints as 0.
std::string formatNumber(double d);
// Appends s in double quotes with OpenSCAD's escapes (\" \\ \n \t \r), as echo() shows it.
void appendQuoted(std::string& out, const std::string& s);

}  // namespace io
