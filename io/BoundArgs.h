// A built-in module call's arguments matched to its parameter names, by OpenSCAD's rules:
// positional arguments in order, then named ones; $-arguments ($fn, $fa, $fs) are left to the
// children; an unknown name is a warning, one positional argument too many an error.
#pragma once

#include <array>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "io/Evaluator.h"
#include "primitives/base/NamedChoice.h"

namespace io {

// Most parameters a built-in module has (material() has 12).
inline constexpr size_t kMaxBuiltinParams = 12;

// One entry per parameter, stored inline: bindArgs runs once per module call, and four
// vectors were four heap allocations there.
template <class T>
struct ParamArray {
    std::array<T, kMaxBuiltinParams> items{};
    size_t count = 0;
    T& operator[](size_t i) { return items[i]; }
    const T& operator[](size_t i) const { return items[i]; }
    size_t size() const { return count; }
};

struct BoundArgs {
    const InstantiationStmt& call;
    // The expected form, for messages: "cube(size, center)". A view of text that outlives
    // every call (a literal or a static), as the parameter names are.
    std::string_view form;
    ParamArray<std::string_view> names;
    ParamArray<Value> values;       // undef where not given
    ParamArray<Loc> locs;           // the call's location where not given
    ParamArray<const Expr*> exprs;  // the expression each came from; null where not given
    ArgValues all;                  // every argument as evaluated, $-arguments included

    const Value& operator[](size_t i) const { return values[i]; }
    bool given(size_t i) const { return !values[i].isUndef(); }
    Loc loc(size_t i) const { return locs[i]; }

    // "name(): 'param' must be <what>, got <value>; expected <form>" at the argument.
    [[noreturn]] void bad(Evaluator& e, size_t i, std::string_view what) const;
    // "name(): unknown <what> <value>; expected one of <choices>" at the argument.
    [[noreturn]] void unknownChoice(Evaluator& e, size_t i, std::string_view what,
                                    const std::string& choices) const;
};

// The choice argument i names (a solver, a polisher, a patch method: a member of `all` as
// nameOf spells it), or fallback when it is not given; an error naming every choice otherwise.
template <class E, size_t N, class NameOf>
E choiceArg(Evaluator& e, const BoundArgs& b, size_t i, std::string_view what, const E (&all)[N],
            NameOf nameOf, E fallback) {
    if (!b.given(i)) return fallback;
    E choice = fallback;
    if (!b.values[i].isString() ||
        !csg::choiceFromName(b.values[i].string().c_str(), all, nameOf, &choice))
        b.unknownChoice(e, i, what, csg::choiceNames(all, nameOf));
    return choice;
}

// A parameter OpenSCAD's module of the same name has that this one refuses, and the error to
// give at an argument of that name (the whole message). Both are views of text that outlives
// every call (literals, statics): bindArgs runs once per module call.
struct RefusedParam {
    std::string_view name;
    std::string_view message;
};

// names are the parameters in positional order (at most kMaxBuiltinParams); form is quoted
// in every message and must outlive the result. A named argument whose name is refused is an
// error at that argument, before any argument is evaluated.
BoundArgs bindArgs(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                   std::initializer_list<std::string_view> names, std::string_view form,
                   std::initializer_list<RefusedParam> refused = {});

// Argument i as a finite number (dflt when not given); anything else is an error at it.
double numberArg(Evaluator& e, const BoundArgs& b, size_t i, double dflt);
// Argument i as true or false (dflt when not given); anything else is an error at it.
bool boolArg(Evaluator& e, const BoundArgs& b, size_t i, bool dflt);

// The children of a built-in operator call as one group (see Evaluator::group), evaluated one
// module-path step below state; *tagOut receives the group's source tag.
Instance childrenGroup(Evaluator& e, const BoundArgs& b, const ContextPtr& ctx,
                       const GeomState& state, uint32_t* tagOut = nullptr);

}  // namespace io
