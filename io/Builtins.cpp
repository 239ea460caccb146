// OpenSCAD's built-in functions. Trigonometry is in degrees; functions given arguments of the
// wrong type return undef with a warning, as OpenSCAD does.
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "io/Degrees.h"
#include "io/DxfModules.h"
#include "io/Evaluator.h"
#include "io/Lexer.h"

namespace io {

namespace {

using Args = ArgValues;

std::optional<double> number(const Args& a, size_t i) {
    if (i < a.size() && a[i].value.isNumber()) return a[i].value.number();
    return std::nullopt;
}

Value badArgument(Evaluator& e, Loc loc, const char* name) {
    e.warn(loc, std::string(name) + "() parameter could not be converted");
    return Value();
}

template <double (*F)(double)>
Value unary(Evaluator& e, const Args& a, Loc loc, const char* name) {
    auto x = number(a, 0);
    if (!x || a.size() != 1) return badArgument(e, loc, name);
    return F(*x);
}

double sign(double x) {
    return x < 0 ? -1.0 : x > 0 ? 1.0 : 0.0;
}
double sqrtOf(double x) {
    return std::sqrt(x);
}
double expOf(double x) {
    return std::exp(x);
}
double lnOf(double x) {
    return std::log(x);
}
double absOf(double x) {
    return std::fabs(x);
}
double floorOf(double x) {
    return std::floor(x);
}
double ceilOf(double x) {
    return std::ceil(x);
}
double roundOf(double x) {
    return std::round(x);
}  // half away from zero, as OpenSCAD

#define UNARY(fn, name) [](Evaluator& e, const Args& a, Loc l) { return unary<fn>(e, a, l, name); }

Value minMax(Evaluator& e, const Args& a, Loc loc, bool isMax) {
    const char* name = isMax ? "max" : "min";
    // One vector argument: its elements; otherwise the arguments themselves.
    std::vector<Value> items;
    if (a.size() == 1 && a[0].value.isVector())
        items = a[0].value.list();
    else
        for (const auto& x : a) items.push_back(x.value);
    if (items.empty()) return badArgument(e, loc, name);
    e.spend(loc, items.size());
    double best = isMax ? -INFINITY : INFINITY;
    for (const Value& v : items) {
        if (!v.isNumber()) return badArgument(e, loc, name);
        best = isMax ? std::max(best, v.number()) : std::min(best, v.number());
    }
    return best;
}

size_t codePoints(const std::string& s) {
    size_t n = 0;
    for (char c : s)
        if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) ++n;
    return n;
}

// Spends a unit per value visited: nested lists may share their elements.
void appendChr(Evaluator& e, Loc loc, std::string& out, const Value& v) {
    e.spend(loc);
    if (out.size() > kMaxStringBytes)
        e.fail(loc, "string too long (more than " + std::to_string(kMaxStringBytes) + " bytes)");
    if (v.isNumber()) {
        const double d = v.number();
        if (d >= 1 && d <= 0x10FFFF && d == std::floor(d) && !(d >= 0xD800 && d <= 0xDFFF))
            appendUtf8(out, static_cast<uint32_t>(d));
    } else if (v.isVector()) {
        for (const Value& x : v.list()) appendChr(e, loc, out, x);
    } else if (v.isRange()) {
        const Range& r = v.range();
        const double n = std::min(r.count(), kMaxIterations);
        for (double i = 0; i < n; ++i) appendChr(e, loc, out, Value(r.begin + i * r.step));
    }
}

Value lookup(Evaluator& e, const Args& a, Loc loc) {
    auto key = number(a, 0);
    if (!key || a.size() < 2 || !a[1].value.isVector()) return badArgument(e, loc, "lookup");
    // Nearest entries at or below and at or above the key; clamped outside the table.
    const ValueList* low = nullptr;
    const ValueList* high = nullptr;
    const ValueList* lowest = nullptr;
    const ValueList* highest = nullptr;
    e.spend(loc, a[1].value.list().size());
    for (const Value& entry : a[1].value.list()) {
        if (!entry.isVector() || entry.list().size() < 2 || !entry.list()[0].isNumber() ||
            !entry.list()[1].isNumber())
            continue;
        const ValueList* p = &entry.list();
        const double k = (*p)[0].number();
        if (!lowest || k < (*lowest)[0].number()) lowest = p;
        if (!highest || k > (*highest)[0].number()) highest = p;
        if (k <= *key && (!low || k > (*low)[0].number())) low = p;
        if (k >= *key && (!high || k < (*high)[0].number())) high = p;
    }
    if (!lowest) return Value();
    if (!low) return (*lowest)[1];
    if (!high) return (*highest)[1];
    const double k0 = (*low)[0].number(), k1 = (*high)[0].number();
    const double v0 = (*low)[1].number(), v1 = (*high)[1].number();
    if (k1 == k0) return v0;
    return v0 + (v1 - v0) * (*key - k0) / (k1 - k0);
}

// The seed's integer part modulo 2^32 (what converting an in-range integer does); 0 for a
// seed that is not finite. Converting a huge double straight to an integer is undefined.
unsigned int seedBits(double seed) {
    if (!std::isfinite(seed)) return 0;
    double bits = std::fmod(std::trunc(seed), 4294967296.0);
    if (bits < 0) bits += 4294967296.0;
    return static_cast<unsigned int>(bits);
}

Value rands(Evaluator& e, const Args& a, Loc loc) {
    auto lo = number(a, 0), hi = number(a, 1), count = number(a, 2);
    if (!lo || !hi || !count || !(*count >= 0 && *count <= kMaxIterations))
        return badArgument(e, loc, "rands");
    std::mt19937 seeded;
    std::mt19937* generator = &e.random();  // without a seed: one fixed sequence per run
    if (auto seed = number(a, 3)) {
        seeded.seed(seedBits(*seed));
        generator = &seeded;
    }
    ValueList out;
    const size_t n = static_cast<size_t>(*count);
    e.spend(loc, n);
    out.reserve(n);
    if (*lo == *hi) {
        out.assign(n, Value(*lo));
        return out;
    }
    std::uniform_real_distribution<double> distribution(std::min(*lo, *hi), std::max(*lo, *hi));
    for (size_t i = 0; i < n; ++i) out.push_back(distribution(*generator));
    return out;
}

Value cross(Evaluator& e, const Args& a, Loc loc) {
    if (a.size() != 2 || !a[0].value.isVector() || !a[1].value.isVector())
        return badArgument(e, loc, "cross");
    const ValueList &u = a[0].value.list(), &v = a[1].value.list();
    auto numbers = [](const ValueList& l) {
        return std::all_of(l.begin(), l.end(), [](const Value& x) { return x.isNumber(); });
    };
    if (u.size() != v.size() || !numbers(u) || !numbers(v)) return badArgument(e, loc, "cross");
    if (u.size() == 2) return u[0].number() * v[1].number() - u[1].number() * v[0].number();
    if (u.size() != 3) return badArgument(e, loc, "cross");
    const double x = u[1].number() * v[2].number() - u[2].number() * v[1].number();
    const double y = u[2].number() * v[0].number() - u[0].number() * v[2].number();
    const double z = u[0].number() * v[1].number() - u[1].number() * v[0].number();
    return ValueList{x, y, z};
}

// parent_module(n = 1): the name of the user module n levels up the module stack from the one
// being instantiated (0: that one), as OpenSCAD 2021 (func.cc, builtin_parent_module): n is
// truncated; a non-number is undef; a negative or too big n is undef with OpenSCAD's warning
// (NaN and 1e10 count as negative, as 2021's x86 builds take them).
Value parentModule(Evaluator& e, const Args& a, Loc loc) {
    if (a.size() > 1) {
        e.warn(loc, "parent_module() number of parameters does not match");
        return Value();
    }
    double d = 1.0;
    if (a.size() == 1) {
        if (!a[0].value.isNumber()) return Value();
        d = a[0].value.number();
    }
    const auto& stack = e.moduleStack();
    // OpenSCAD converts to int: on x86, NaN and values out of int's range become INT_MIN.
    double t = std::trunc(d);
    if (!(t >= -2147483648.0 && t <= 2147483647.0)) t = -2147483648.0;
    const std::string n = std::to_string(static_cast<long>(t));
    if (t < 0) {
        e.warn(loc, "Negative parent module index (" + n + ") not allowed");
        return Value();
    }
    if (t >= static_cast<double>(stack.size())) {
        e.warn(loc,
               "Parent module index (" + n + ") greater than the number of modules on the stack");
        return Value();
    }
    return std::string(stack[stack.size() - 1 - static_cast<size_t>(t)]);
}

const std::unordered_map<std::string, Evaluator::BuiltinFunction>& table() {
    static const std::unordered_map<std::string, Evaluator::BuiltinFunction> functions = {
        // OpenSCAD 2021's own degree trigonometry, bit for bit (io/Degrees.h): sin(45) is
        // sqrt(1/2) and tan(30) sqrt(1/3) exactly, as BOSL2's tests expect.
        {"sin", UNARY(openscadSinDegrees, "sin")},
        {"cos", UNARY(openscadCosDegrees, "cos")},
        {"tan", UNARY(openscadTanDegrees, "tan")},
        {"asin", UNARY(openscadAsinDegrees, "asin")},
        {"acos", UNARY(openscadAcosDegrees, "acos")},
        {"atan", UNARY(openscadAtanDegrees, "atan")},
        {"atan2",
         [](Evaluator& e, const Args& a, Loc l) -> Value {
             auto y = number(a, 0), x = number(a, 1);
             if (!y || !x) return badArgument(e, l, "atan2");
             return openscadAtan2Degrees(*y, *x);
         }},
        {"sqrt", UNARY(sqrtOf, "sqrt")},
        {"exp", UNARY(expOf, "exp")},
        {"ln", UNARY(lnOf, "ln")},
        {"abs", UNARY(absOf, "abs")},
        {"sign", UNARY(sign, "sign")},
        {"floor", UNARY(floorOf, "floor")},
        {"ceil", UNARY(ceilOf, "ceil")},
        {"round", UNARY(roundOf, "round")},
        {"pow",
         [](Evaluator& e, const Args& a, Loc l) -> Value {
             auto b = number(a, 0), x = number(a, 1);
             if (!b || !x) return badArgument(e, l, "pow");
             return std::pow(*b, *x);
         }},
        {"log",
         [](Evaluator& e, const Args& a, Loc l) -> Value {
             // log(x) is base 10; log(b, x) is base b.
             if (a.size() == 2) {
                 auto b = number(a, 0), x = number(a, 1);
                 if (!b || !x) return badArgument(e, l, "log");
                 return std::log(*x) / std::log(*b);
             }
             auto x = number(a, 0);
             if (!x || a.size() != 1) return badArgument(e, l, "log");
             return std::log10(*x);
         }},
        {"min", [](Evaluator& e, const Args& a, Loc l) { return minMax(e, a, l, false); }},
        {"max", [](Evaluator& e, const Args& a, Loc l) { return minMax(e, a, l, true); }},
        {"norm",
         [](Evaluator& e, const Args& a, Loc l) -> Value {
             if (a.size() != 1 || !a[0].value.isVector()) return badArgument(e, l, "norm");
             e.spend(l, a[0].value.list().size());
             double sum = 0.0;
             for (const Value& x : a[0].value.list()) {
                 if (!x.isNumber()) return badArgument(e, l, "norm");
                 sum += x.number() * x.number();
             }
             return std::sqrt(sum);
         }},
        {"cross", cross},
        {"len",
         [](Evaluator& e, const Args& a, Loc l) -> Value {
             if (a.size() == 1 && a[0].value.isVector())
                 return static_cast<double>(a[0].value.list().size());
             if (a.size() == 1 && a[0].value.isString()) {
                 e.spend(l, a[0].value.string().size());
                 return static_cast<double>(codePoints(a[0].value.string()));
             }
             return badArgument(e, l, "len");
         }},
        {"concat",
         [](Evaluator& e, const Args& a, Loc l) -> Value {
             ValueList out;
             for (const ArgValue& x : a) {
                 if (x.value.isVector()) {
                     e.spend(l, x.value.list().size());
                     out.insert(out.end(), x.value.list().begin(), x.value.list().end());
                 } else {
                     out.push_back(x.value);
                 }
             }
             return e.makeList(std::move(out), l);
         }},
        {"lookup", lookup},
        {"str",
         [](Evaluator& e, const Args& a, Loc l) -> Value {
             std::string out;
             for (const ArgValue& x : a) {
                 out += e.printed(x.value, false, l);
                 if (out.size() > kMaxStringBytes)
                     e.fail(l, "string too long (more than " + std::to_string(kMaxStringBytes) +
                                   " bytes)");
             }
             return out;
         }},
        {"chr",
         [](Evaluator& e, const Args& a, Loc l) -> Value {
             std::string out;
             for (const ArgValue& x : a) appendChr(e, l, out, x.value);
             return out;
         }},
        {"ord",
         [](Evaluator& e, const Args& a, Loc l) -> Value {
             if (a.size() != 1 || !a[0].value.isString()) return badArgument(e, l, "ord");
             const std::string& s = a[0].value.string();
             if (s.empty() || codePoints(s) != 1) return Value();
             const auto c = static_cast<unsigned char>(s[0]);
             uint32_t cp = c < 0x80 ? c : c < 0xE0 ? c & 0x1F : c < 0xF0 ? c & 0x0F : c & 0x07;
             for (size_t i = 1; i < s.size(); ++i) cp = (cp << 6) | (s[i] & 0x3F);
             return static_cast<double>(cp);
         }},
        {"rands", rands},
        {"search", builtinSearch},
        {"parent_module", parentModule},
        {"is_undef",
         [](Evaluator&, const Args& a, Loc) -> Value {
             return a.size() == 1 && a[0].value.isUndef();
         }},
        {"is_num",
         [](Evaluator&, const Args& a, Loc) -> Value {
             return a.size() == 1 && a[0].value.isNumber() && !std::isnan(a[0].value.number());
         }},
        {"is_bool",
         [](Evaluator&, const Args& a, Loc) -> Value {
             return a.size() == 1 && a[0].value.isBool();
         }},
        {"is_string",
         [](Evaluator&, const Args& a, Loc) -> Value {
             return a.size() == 1 && a[0].value.isString();
         }},
        {"is_list",
         [](Evaluator&, const Args& a, Loc) -> Value {
             return a.size() == 1 && a[0].value.isVector();
         }},
        {"is_function",
         [](Evaluator&, const Args& a, Loc) -> Value {
             return a.size() == 1 && a[0].value.isFunction();
         }},
        {"version",
         [](Evaluator&, const Args&, Loc) -> Value {
             return ValueList{2021, 1, 0};
         }},
        {"version_num", [](Evaluator&, const Args&, Loc) -> Value { return 20210100.0; }},
        {"dxf_dim", dxfDimFunction},
        {"dxf_cross", dxfCrossFunction},
    };
    return functions;
}

}  // namespace

const Evaluator::BuiltinFunction* Evaluator::findBuiltinFunction(const std::string& name) const {
    const auto& t = table();
    auto it = t.find(name);
    return it == t.end() ? nullptr : &it->second;
}

}  // namespace io
