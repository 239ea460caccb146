// Statements: scopes, modifiers, user modules, children(), for/intersection_for, if, let,
// echo and assert as modules, and the bookkeeping of source tags, module paths and materials.
#include <algorithm>

#include "io/Evaluator.h"
#include "io/Parser.h"
#include "io/Shapes2D.h"

namespace io {

Evaluator::Evaluator(SourceFiles& sources, Model& model, std::vector<Diagnostic>& diagnostics,
                     const EvaluateOptions& options)
    : sources_(sources), model_(model), diagnostics_(diagnostics), options_(options) {
    root_ = Context::make(nullptr, nullptr, nullptr);
    root_->set("PI", Value(3.14159265358979323846));
    root_->set("$fn", Value(0.0));
    root_->set("$fa", Value(12.0));
    root_->set("$fs", Value(2.0));
    root_->set("$t", Value(options.time));
    root_->set("$preview", Value(false));
    root_->set("$vpr", Value(ValueList{55.0, 0.0, 25.0}));
    root_->set("$vpt", Value(ValueList{0.0, 0.0, 0.0}));
    root_->set("$vpd", Value(140.0));
    root_->set("$vpf", Value(22.5));
}

Evaluator::~Evaluator() {
    // Break closure cycles (scope -> variable -> function value -> scope) so nothing leaks.
    std::vector<ContextPtr> pending;
    for (const auto& weak : closures_)
        if (ContextPtr c = weak.lock()) pending.push_back(std::move(c));
    closures_.clear();
    while (!pending.empty()) {
        ContextPtr c = std::move(pending.back());
        pending.pop_back();
        if (c->variables.empty() && !c->lexicalParent && !c->dynamicParent) continue;
        std::vector<std::pair<std::string, Value>> variables;
        variables.swap(c->variables);
        if (c->lexicalParent) pending.push_back(std::move(c->lexicalParent));
        if (c->dynamicParent) pending.push_back(std::move(c->dynamicParent));
        if (c->childrenContext) pending.push_back(std::move(c->childrenContext));
        for (auto& used : c->usedFiles) pending.push_back(std::move(used));
        c->usedFiles.clear();
        // variables (and any closures in them) are released here, after the walk moved on.
    }
}

void Evaluator::loadUses(const ParsedFile& file, const ContextPtr& fileContext) {
    for (const auto& [written, loc] : file.uses) {
        // From the file the use<> is written in, which an included file's is not.
        const auto path = sources_.resolve(written, loc.file);
        const std::string key = std::filesystem::weakly_canonical(path).string();
        auto known = usedFileContexts_.find(key);
        if (known != usedFileContexts_.end()) {
            fileContext->usedFiles.push_back(known->second);
            continue;
        }
        std::string error;
        auto index = sources_.load(path, error);
        if (!index) fail(loc, "cannot use '" + written + "': " + error);
        std::vector<Diagnostic> parseDiagnostics;
        auto parsed = parseFile(sources_, *index, parseDiagnostics);
        for (auto& d : parseDiagnostics) diagnostics_.push_back(std::move(d));
        if (!parsed) throw EvalError{loc, "errors in used file '" + written + "'"};
        sources_.releaseText(*index);
        // A used file contributes its functions and modules, which see its own top-level
        // variables; its geometry is ignored (OpenSCAD's use<>).
        ContextPtr c = Context::make(root_, root_, &parsed->body);
        usedFileContexts_[key] = c;
        loadUses(*parsed, c);
        for (const AssignmentStmt* a : parsed->body.assignments)
            c->set(a->name, eval(*a->value, c));
        fileContext->usedFiles.push_back(c);
        usedFiles_.push_back(std::move(parsed));
    }
}

void Evaluator::run(const ParsedFile& file) {
    ContextPtr fileContext = Context::make(root_, root_, &file.body);
    loadUses(file, fileContext);
    std::vector<csg::NodePtr> parts;
    evalScope(fileContext, file.body, GeomState{}, parts);
    if (rootOverride_) {
        model_.root = *rootOverride_;
    } else {
        std::vector<csg::NodePtr> solids;
        keepOneDimension(parts, 0);
        for (auto& p : parts)
            if (p) solids.push_back(std::move(p));
        // The implicit top-level union is tagged with the file itself (line 0: no statement).
        model_.root = csg::uniteAll(solids, {sourceTag(Loc{file.fileIndex, 0, 0}, 0), 0});
    }
    // A 2-D part is shown as OpenSCAD previews it: the shape 1 unit thick about z = 0.
    if (dimensionOf(model_.root) == 2) {
        model_.twoD = true;
        model_.shape2D = model_.root;
        model_.root = liftLeaves(model_.root, [](const csg::Extrusion& leaf) {
            return leaf.linear(-0.5, 0.5, csg::Vec2(1.0));
        });
    }
}

void Evaluator::evalScope(const ContextPtr& ctx, const Body& body, const GeomState& state,
                          std::vector<csg::NodePtr>& out) {
    for (const AssignmentStmt* a : body.assignments) ctx->set(a->name, eval(*a->value, ctx));
    for (const Stmt* s : body.instantiations)
        if (Instance i = instantiate(*s, ctx, state)) out.push_back(std::move(*i));
}

bool Evaluator::definesNames(const Body& body) {
    return !body.assignments.empty() || !body.modules.empty() || !body.functions.empty();
}

uint32_t Evaluator::sourceTag(Loc loc, uint32_t modulePath) {
    model_.sources.push_back({loc.file, loc.line, loc.col, modulePath});
    return static_cast<uint32_t>(model_.sources.size() - 1);
}

uint32_t Evaluator::childPath(const GeomState& state, std::string_view name) {
    // A path is one step below its parent, stored once per distinct (parent, name) in first-use
    // order; its text is built only when a client asks (Model::modulePathText), so neither
    // time nor memory grows with the square of the nesting depth.
    if (auto known = childPaths_.find(ChildPathKeyView{state.modulePath, name});
        known != childPaths_.end())
        return known->second;
    const auto index = static_cast<uint32_t>(model_.modulePaths.size());
    model_.modulePaths.push_back({state.modulePath, std::string(name)});
    childPaths_.emplace(ChildPathKey{state.modulePath, std::string(name)}, index);
    return index;
}

uint32_t Evaluator::internMaterial(const Material& m) {
    // Parts use few materials; a short linear search keeps the table free of duplicates.
    const size_t n = model_.materials.size();
    for (size_t i = n > 256 ? n - 256 : 0; i < n; ++i)
        if (model_.materials[i] == m) return static_cast<uint32_t>(i);
    model_.materials.push_back(m);
    return static_cast<uint32_t>(n);
}

void Evaluator::keepOneDimension(std::vector<csg::NodePtr>& parts, uint32_t tag) {
    int dimension = 0;
    for (const csg::NodePtr& p : parts)
        if ((dimension = dimensionOf(p)) != 0) break;
    const auto other = [&](const csg::NodePtr& p) {
        const int d = dimensionOf(p);
        return d != 0 && d != dimension;
    };
    const auto end = std::remove_if(parts.begin(), parts.end(), other);
    if (end == parts.end()) return;
    parts.erase(end, parts.end());
    const SourceInfo& at = model_.source(tag);
    warn(Loc{at.fileIndex, at.line, at.col},
         std::string("Mixing 2D and 3D objects is not supported: the ") +
             (dimension == 2 ? "3-D" : "2-D") + " ones are ignored, as in OpenSCAD");
}

Instance Evaluator::group(std::vector<csg::NodePtr> parts, bool anyPresent, uint32_t tag) {
    if (!anyPresent) return std::nullopt;
    std::vector<csg::NodePtr> solids;
    solids.reserve(parts.size());
    keepOneDimension(parts, tag);
    for (auto& p : parts)
        if (p) solids.push_back(std::move(p));
    return csg::uniteAll(solids, {tag, 0});
}

Instance Evaluator::instantiate(const Stmt& s, const ContextPtr& ctx, const GeomState& state) {
    spend(s.loc, kStatementSteps);
    checkStack(s.loc);
    const Modifier modifier = s.kind == StmtKind::If
                                  ? static_cast<const IfStmt&>(s).modifier
                                  : static_cast<const InstantiationStmt&>(s).modifier;
    if (modifier == Modifier::Disable) return std::nullopt;  // * : not even evaluated
    Instance result;
    if (s.kind == StmtKind::If) {
        const auto& i = static_cast<const IfStmt&>(s);
        const Body& branch = eval(*i.condition, ctx).truthy() ? i.ifTrue : i.ifFalse;
        std::vector<csg::NodePtr> parts;
        evalScope(Context::make(ctx, ctx, &branch), branch, state, parts);
        const bool any = !parts.empty();
        result = group(std::move(parts), any, any ? sourceTag(s.loc, state.modulePath) : 0);
    } else {
        result = instantiateCall(static_cast<const InstantiationStmt&>(s), ctx, state);
    }
    switch (modifier) {
        case Modifier::Root:
            // ! : this subtree alone is the model, without its parents' transforms (as
            // OpenSCAD renders it); the first one wins.
            if (!rootOverride_) rootOverride_ = result.value_or(nullptr);
            return result;
        case Modifier::Highlight:
            if (result && *result)
                model_.highlighted.push_back({csg::transformed(state.worldFromHere, *result),
                                              sourceTag(s.loc, state.modulePath)});
            return result;
        case Modifier::Background:
            // % : drawn for reference, never part of the solid.
            if (result && *result)
                model_.backgroundParts.push_back({csg::transformed(state.worldFromHere, *result),
                                                  sourceTag(s.loc, state.modulePath)});
            return std::nullopt;
        default:
            return result;
    }
}

std::vector<csg::NodePtr> Evaluator::instantiateChildren(const InstantiationStmt& s,
                                                         const ContextPtr& ctx,
                                                         const GeomState& state,
                                                         const ArgValues& args, bool& anyPresent) {
    std::vector<csg::NodePtr> parts;
    anyPresent = false;
    if (s.children.empty()) return parts;
    bool dollarArgs = false;
    for (const ArgValue& a : args) dollarArgs |= !a.name.empty() && a.name[0] == '$';
    if (!dollarArgs && !definesNames(s.children)) {
        // An empty scope would look every name up exactly as ctx does: skip making it.
        evalScope(ctx, s.children, state, parts);
    } else {
        ContextPtr c = Context::make(ctx, ctx, &s.children);
        for (const ArgValue& a : args)  // translate(v, $fn = 8) { ... }: children see $fn
            if (!a.name.empty() && a.name[0] == '$') c->set(a.name, a.value);
        evalScope(c, s.children, state, parts);
    }
    anyPresent = !parts.empty();
    return parts;
}

Instance Evaluator::instantiateCall(const InstantiationStmt& s, const ContextPtr& ctx,
                                    const GeomState& state) {
    const std::string& name = s.name;
    if (name == "for") return instantiateForLoop(s, ctx, state, false);
    if (name == "intersection_for") return instantiateForLoop(s, ctx, state, true);
    if (name == "children") return instantiateChildrenCall(s, ctx, state);
    // assign() is OpenSCAD's deprecated spelling of let().
    if (name == "let" || name == "assign" || name == "echo" || name == "assert") {
        ContextPtr c = ctx;
        ArgValues noArgs;
        if (name == "let" || name == "assign") {
            c = Context::make(ctx, ctx, nullptr);
            for (const Argument& a : s.args) {
                if (a.name.empty())
                    fail(a.loc, "let() takes assignments; expected let(name = value)");
                c->set(a.name, eval(*a.value, c));
            }
        } else if (name == "echo") {
            echo(evalArgs(s.args, ctx));
        } else {
            ArgValues args = evalArgs(s.args, ctx);
            if (args.empty())
                fail(s.loc, "assert() needs a condition; expected assert(condition, message)");
            if (!args[0].value.truthy()) {
                std::string message = "assertion failed";
                if (args.size() > 1) message += ": " + printed(args[1].value, false, s.loc);
                fail(s.loc, message);
            }
        }
        bool any = false;
        auto parts = instantiateChildren(s, c, state, noArgs, any);
        return group(std::move(parts), any, any ? sourceTag(s.loc, state.modulePath) : 0);
    }
    // User modules shadow built-ins, as in OpenSCAD. The walk holds a pointer to each
    // ContextPtr rather than a copy: no reference-count traffic per level.
    for (const ContextPtr* c = &ctx; *c; c = &(*c)->lexicalParent) {
        if ((*c)->body) {
            auto it = (*c)->body->modules.find(name);
            if (it != (*c)->body->modules.end())
                return callUserModule(*it->second, *c, s, ctx, state);
        }
        for (const ContextPtr& used : (*c)->usedFiles) {
            auto it = used->body->modules.find(name);
            if (it != used->body->modules.end())
                return callUserModule(*it->second, used, s, ctx, state);
        }
    }
    if (const BuiltinModule* b = findBuiltinModule(name)) return (*b)(*this, s, ctx, state);
    // OpenSCAD warns and goes on (MCAD's regular_shapes.scad calls a module it never defines).
    warn(s.loc, "Ignoring unknown module '" + name + "'");
    return std::nullopt;
}

Instance Evaluator::callUserModule(const ModuleDefStmt& def, const ContextPtr& definition,
                                   const InstantiationStmt& s, const ContextPtr& ctx,
                                   const GeomState& state) {
    DepthGuard guard(*this, s.loc, def.name);
    // On the module stack from before its arguments are evaluated, as in OpenSCAD:
    // m(parent_module(0)) passes "m".
    struct StackEntry {
        std::vector<std::string_view>& stack;
        ~StackEntry() { stack.pop_back(); }
    } entry{moduleStack_};
    moduleStack_.push_back(def.name);
    ContextPtr m =
        bindParameters(def.params, evalArgs(s.args, ctx), definition, ctx, s.loc, def.name);
    m->isModuleCall = true;
    m->children = &s.children;
    m->childrenContext = ctx;
    m->set("$children", Value(static_cast<double>(s.children.instantiations.size())));
    m->set("$parent_modules", Value(static_cast<double>(moduleStack_.size())));
    GeomState inner = state;
    inner.modulePath = childPath(state, def.name + "()");
    std::vector<csg::NodePtr> parts;
    evalScope(Context::make(m, m, &def.body), def.body, inner, parts);
    const bool any = !parts.empty();
    return group(std::move(parts), any, any ? sourceTag(s.loc, inner.modulePath) : 0);
}

Instance Evaluator::instantiateChildrenCall(const InstantiationStmt& s, const ContextPtr& ctx,
                                            const GeomState& state) {
    const Context* module = ctx.get();
    while (module && !module->isModuleCall) module = module->lexicalParent.get();
    if (!module) {
        warn(s.loc, "children() outside a module does nothing");
        return std::nullopt;
    }
    const Body& children = *module->children;
    const size_t count = children.instantiations.size();
    // Which children: all, one index, a vector of indices or a range.
    std::vector<size_t> selected;
    ArgValues args = evalArgs(s.args, ctx);
    if (args.size() > 1)
        fail(s.loc,
             "too many arguments; expected children(), children(index), "
             "children([indices]) or children([begin:end])");
    if (args.empty()) {
        for (size_t i = 0; i < count; ++i) selected.push_back(i);
    } else {
        const Value& v = args[0].value;
        if (!v.isNumber() && !v.isVector() && !v.isRange())
            fail(args[0].loc, std::string("children() index must be a number, vector or range, "
                                          "got ") +
                                  v.typeName());
        forEachItem(v, args[0].loc, [&](const Value& item) {
            const double k = item.isNumber() ? item.number() : -1.0;
            if (k >= 0 && k < static_cast<double>(count))
                selected.push_back(static_cast<size_t>(k));
            else
                warn(args[0].loc, "children() index " + item.brief() + " out of range (" +
                                      std::to_string(count) + " children)");
            return true;
        });
    }
    DepthGuard guard(*this, s.loc, "children");
    // Children are evaluated where they were written; $-variables come from here.
    ContextPtr c = Context::make(module->childrenContext, ctx, &children);
    for (const AssignmentStmt* a : children.assignments) c->set(a->name, eval(*a->value, c));
    std::vector<csg::NodePtr> parts;
    for (size_t i : selected)
        if (Instance inst = instantiate(*children.instantiations[i], c, state))
            parts.push_back(std::move(*inst));
    const bool any = !parts.empty();
    return group(std::move(parts), any, any ? sourceTag(s.loc, state.modulePath) : 0);
}

Instance Evaluator::instantiateForLoop(const InstantiationStmt& s, const ContextPtr& ctx,
                                       const GeomState& state, bool intersect) {
    GeomState inner = state;
    inner.modulePath = childPath(state, s.name);
    std::vector<csg::NodePtr> parts;       // for: everything, united
    std::vector<csg::NodePtr> iterations;  // intersection_for: one union per iteration
    bool anyIteration = false;
    // for (a = A, b = B): nested loops, a outermost; B may use a.
    auto loop = [&](auto& self, size_t index, const ContextPtr& c) -> void {
        if (index == s.args.size()) {
            // The body's own scope only when it defines names (see instantiateChildren).
            const ContextPtr body = definesNames(s.children) ? Context::make(c, c, &s.children) : c;
            if (!intersect) {
                evalScope(body, s.children, inner, parts);
                return;
            }
            std::vector<csg::NodePtr> own;
            evalScope(body, s.children, inner, own);
            if (own.empty()) return;
            anyIteration = true;
            iterations.push_back(*group(std::move(own), true, 0));
            return;
        }
        const Argument& a = s.args[index];
        const Value items = eval(*a.value, c);
        forEachItem(items, a.loc, [&](const Value& item) {
            ContextPtr next = Context::make(c, c, nullptr);
            if (!a.name.empty()) next->set(a.name, item);
            self(self, index + 1, next);
            return true;
        });
    };
    if (s.args.empty()) fail(s.loc, "expected " + s.name + "(name = values)");
    loop(loop, 0, ctx);
    if (!intersect) {
        const bool any = !parts.empty();
        return group(std::move(parts), any, any ? sourceTag(s.loc, inner.modulePath) : 0);
    }
    if (!anyIteration) return std::nullopt;
    for (const auto& p : iterations)
        if (!p) return csg::NodePtr();  // intersecting with nothing gives nothing
    return csg::intersectAll(iterations, {sourceTag(s.loc, inner.modulePath), 0});
}

}  // namespace io
