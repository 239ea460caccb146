#include "io/BoundArgs.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace io {

void BoundArgs::bad(Evaluator& e, size_t i, std::string_view what) const {
    e.fail(locs[i], call.name + "(): '" + std::string(names[i]) + "' must be " + std::string(what) +
                        ", got " + values[i].brief() + "; expected " + std::string(form));
}

void BoundArgs::unknownChoice(Evaluator& e, size_t i, std::string_view what,
                              const std::string& choices) const {
    e.fail(locs[i], call.name + "(): unknown " + std::string(what) + " " + values[i].brief() +
                        "; expected one of " + choices);
}

BoundArgs bindArgs(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                   std::initializer_list<std::string_view> names, std::string_view form,
                   std::initializer_list<RefusedParam> refused) {
    if (names.size() > kMaxBuiltinParams)
        throw std::length_error("bindArgs: more parameters than kMaxBuiltinParams");
    for (const Argument& a : s.args)
        for (const RefusedParam& r : refused)
            if (a.name == r.name) e.fail(a.loc, std::string(r.message));
    BoundArgs b{s, form, {}, {}, {}, {}, e.evalArgs(s.args, ctx)};
    b.names.count = b.values.count = b.locs.count = b.exprs.count = names.size();
    std::copy(names.begin(), names.end(), b.names.items.begin());
    b.locs.items.fill(s.loc);
    size_t positional = 0;
    // evalArgs gives one value per argument of the call, in order.
    for (size_t i = 0; i < b.all.size(); ++i) {
        const ArgValue& a = b.all[i];
        size_t k = 0;
        if (a.name.empty()) {
            k = positional++;
            if (k >= names.size())
                e.fail(a.loc,
                       "too many arguments to " + s.name + "(); expected " + std::string(b.form));
        } else {
            if (a.name[0] == '$') continue;
            while (k < b.names.size() && b.names[k] != a.name) ++k;
            if (k == b.names.size()) {
                e.warn(a.loc, "unknown parameter '" + a.name + "' of " + s.name + "(); expected " +
                                  std::string(b.form));
                continue;
            }
        }
        b.values[k] = a.value;
        b.locs[k] = a.loc;
        b.exprs[k] = s.args[i].value.get();
    }
    return b;
}

double numberArg(Evaluator& e, const BoundArgs& b, size_t i, double dflt) {
    if (!b.given(i)) return dflt;
    if (!b[i].isNumber() || !std::isfinite(b[i].number())) b.bad(e, i, "a finite number");
    return b[i].number();
}

bool boolArg(Evaluator& e, const BoundArgs& b, size_t i, bool dflt) {
    if (!b.given(i)) return dflt;
    if (!b[i].isBool()) b.bad(e, i, "true or false");
    return b[i].asBool();
}

Instance childrenGroup(Evaluator& e, const BoundArgs& b, const ContextPtr& ctx,
                       const GeomState& state, uint32_t* tagOut) {
    GeomState inner = state;
    inner.modulePath = e.childPath(state, b.call.name);
    bool any = false;
    auto parts = e.instantiateChildren(b.call, ctx, inner, b.all, any);
    const uint32_t tag = any ? e.sourceTag(b.call.loc, inner.modulePath) : 0;
    if (tagOut) *tagOut = tag;
    return e.group(std::move(parts), any, tag);
}

}  // namespace io
