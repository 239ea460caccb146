#include "io/BoundArgs.h"

namespace io {

void BoundArgs::bad(Evaluator& e, size_t i, std::string_view what) const {
    e.fail(locs[i], call.name + "(): '" + std::string(names[i]) + "' must be " + std::string(what) +
                        ", got " + values[i].brief() + "; expected " + form);
}

BoundArgs bindArgs(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                   std::initializer_list<std::string_view> names, std::string form,
                   std::initializer_list<RefusedParam> refused) {
    for (const Argument& a : s.args)
        for (const RefusedParam& r : refused)
            if (a.name == r.name) e.fail(a.loc, std::string(r.message));
    BoundArgs b{s,
                std::move(form),
                names,
                std::vector<Value>(names.size()),
                std::vector<Loc>(names.size(), s.loc),
                std::vector<const Expr*>(names.size(), nullptr),
                e.evalArgs(s.args, ctx)};
    size_t positional = 0;
    // evalArgs gives one value per argument of the call, in order.
    for (size_t i = 0; i < b.all.size(); ++i) {
        const ArgValue& a = b.all[i];
        size_t k = 0;
        if (a.name.empty()) {
            k = positional++;
            if (k >= names.size())
                e.fail(a.loc, "too many arguments to " + s.name + "(); expected " + b.form);
        } else {
            if (a.name[0] == '$') continue;
            while (k < b.names.size() && b.names[k] != a.name) ++k;
            if (k == b.names.size()) {
                e.warn(a.loc, "unknown parameter '" + a.name + "' of " + s.name + "(); expected " +
                                  b.form);
                continue;
            }
        }
        b.values[k] = a.value;
        b.locs[k] = a.loc;
        b.exprs[k] = s.args[i].value.get();
    }
    return b;
}

}  // namespace io
