// The evaluator's internals (not a public header): contexts with OpenSCAD's two kinds of
// scoping, and the Evaluator that turns an AST into csg nodes and Model extras.
//
// Scoping, as OpenSCAD 2021 does it:
//   plain names   resolve lexically: lexicalParent is the scope the code was written in;
//   $-names       resolve dynamically: dynamicParent is the scope that called this one;
//   a scope       evaluates all its assignments first, in order (a name assigned twice keeps
//                 its first position and takes the last value), then its instantiations.
// Errors are thrown as EvalError inside io/ and become diagnostics at the entry point.
#pragma once

#include <memory>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "io/Ast.h"
#include "io/Evaluate.h"
#include "io/SourceFiles.h"
#include "io/Value.h"

namespace io {

struct EvalError {
    Loc loc;
    std::string message;
};

struct Context;
using ContextPtr = std::shared_ptr<Context>;

struct Context {
    ContextPtr lexicalParent;
    ContextPtr dynamicParent;
    const Body* body = nullptr;  // the definitions visible from here
    std::vector<std::pair<std::string, Value>> variables;

    // A user module's call: the children written at the call site and the scope they were
    // written in (children() evaluates them there).
    bool isModuleCall = false;
    const Body* children = nullptr;
    ContextPtr childrenContext;

    // A file's top scope: the files it uses (their top scopes), searched after its own body.
    std::vector<ContextPtr> usedFiles;

    static ContextPtr make(ContextPtr lexical, ContextPtr dynamic, const Body* scopeBody) {
        auto c = std::make_shared<Context>();
        c->lexicalParent = std::move(lexical);
        c->dynamicParent = std::move(dynamic);
        c->body = scopeBody;
        return c;
    }
    // Sets a variable in this scope (replacing one of the same name).
    void set(std::string_view name, Value value);
    const Value* findLocal(std::string_view name) const;
};

// Top-down state of geometry evaluation: where we are (for # and % records), which material
// applies (inner color/material wins) and the module path for source tags.
struct GeomState {
    csg::Mat4 worldFromHere{1.0};
    uint32_t material = 0;    // index into Model::materials
    uint32_t modulePath = 0;  // index into Model::modulePaths
};

// A module instantiation's result: nothing (echo, camera, an empty group — OpenSCAD drops
// those from booleans), or a node, where a null NodePtr is the empty solid (cube(0)).
using Instance = std::optional<csg::NodePtr>;

// Evaluated call arguments: name empty when positional.
struct ArgValue {
    std::string name;
    Value value;
    Loc loc;
};
using ArgValues = std::vector<ArgValue>;

class Evaluator;
// OpenSCAD's search() (Search.cpp).
Value builtinSearch(Evaluator& e, const ArgValues& args, Loc loc);

class Evaluator {
public:
    Evaluator(SourceFiles& sources, Model& model, std::vector<Diagnostic>& diagnostics,
              const EvaluateOptions& options);
    ~Evaluator();
    Evaluator(const Evaluator&) = delete;
    Evaluator& operator=(const Evaluator&) = delete;

    // Evaluates a parsed main file into model_.root (and the extras).
    void run(const ParsedFile& file);

    // ---- limits: work, stack and list nesting ----
    // Spends steps of EvaluateOptions::maxSteps; past the budget, an error at loc.
    void spend(Loc loc, uint64_t steps = 1) {
        steps_ += steps;
        if (steps_ > options_.maxSteps) failWorkLimit(loc);
    }
    // What is left of the budget, for walks over values; settle() charges what they spent.
    WorkBudget budget() const {
        return WorkBudget{steps_ < options_.maxSteps ? options_.maxSteps - steps_ : 0};
    }
    void settle(const WorkBudget& used, Loc loc) {
        steps_ = options_.maxSteps - used.left;
        if (used.exhausted) failWorkLimit(loc);
    }
    [[noreturn]] void failWorkLimit(Loc loc);
    // The evaluator recurses on the C++ stack (expressions, statements, calls); `top` is the
    // frame evaluation starts from and `bytes` how much stack it may use below it.
    void setStackLimit(const char* top, size_t bytes) {
        stackTop_ = top;
        stackBytes_ = bytes;
    }
    // An error at loc when the stack is nearly used up (hostile nesting, deep recursion).
    void checkStack(Loc loc) {
        const char here = 0;
        if (stackTop_ && static_cast<size_t>(stackTop_ - &here) > stackBytes_) failStack(loc);
    }
    [[noreturn]] void failStack(Loc loc);
    // A list built from evaluated items: an error when it nests deeper than kMaxListDepth.
    Value makeList(ValueList items, Loc loc);
    // v as echo() (quoted) or str() shows it, within the work budget and kMaxStringBytes; an
    // error at loc past either (a list sharing a big list a thousand times prints huge).
    std::string printed(const Value& v, bool quoted, Loc loc);

    // ---- expressions (ExpressionEval.cpp) ----
    Value eval(const Expr& e, const ContextPtr& ctx);
    // The variable's value; undef with a warning when no scope has it, or silently.
    Value lookupVariable(const std::string& name, const ContextPtr& ctx, Loc loc,
                         bool silent = false);
    ArgValues evalArgs(const Arguments& args, const ContextPtr& ctx);
    Value callFunctionExpr(const CallExpr& call, const ContextPtr& ctx);
    void warn(Loc loc, std::string message);
    [[noreturn]] void fail(Loc loc, std::string message) {
        throw EvalError{loc, std::move(message)};
    }

    // ---- built-in functions (Builtins.cpp) ----
    using BuiltinFunction = Value (*)(Evaluator&, const ArgValues&, Loc);
    const BuiltinFunction* findBuiltinFunction(const std::string& name) const;
    std::mt19937& random() { return random_; }

    // The echo line of a list of arguments: "ECHO: a = 1, 2".
    void echo(const ArgValues& args);

    // The names of the user modules being instantiated, outermost first: OpenSCAD's stack
    // behind $parent_modules and parent_module(n) (built-in modules are not on it).
    const std::vector<std::string_view>& moduleStack() const { return moduleStack_; }

private:
    // ---- expression helpers ----
    Value evalBinary(const BinaryExpr& e, const ContextPtr& ctx);
    Value evalVector(const VectorExpr& e, const ContextPtr& ctx);
    void evalElement(const Expr& e, const ContextPtr& ctx, ValueList& out);
    Value evalRange(const RangeExpr& e, const ContextPtr& ctx);
    ContextPtr letContext(const Arguments& assignments, const ContextPtr& ctx);
    void checkAssert(const AssertOrEchoExpr& e, const ContextPtr& ctx);
    Value callUserFunction(const Parameters* params, const Expr* body, ContextPtr definition,
                           ArgValues args, const ContextPtr& caller, Loc loc,
                           const std::string& name);
    ContextPtr bindParameters(const Parameters& params, const ArgValues& args,
                              ContextPtr definition, ContextPtr caller, Loc loc,
                              const std::string& what);
    struct FunctionRef {
        const Parameters* params = nullptr;
        const Expr* body = nullptr;
        ContextPtr definition;
    };
    std::optional<FunctionRef> findFunction(const std::string& name, const ContextPtr& ctx);

public:
    // ---- statements (StatementEval.cpp) ----
    // Evaluates a scope: its assignments, then its instantiations into `out`.
    void evalScope(const ContextPtr& ctx, const Body& body, const GeomState& state,
                   std::vector<csg::NodePtr>& out);
    Instance instantiate(const Stmt& s, const ContextPtr& ctx, const GeomState& state);
    // The children of a built-in operator call, evaluated in a scope of their own.
    std::vector<csg::NodePtr> instantiateChildren(const InstantiationStmt& s, const ContextPtr& ctx,
                                                  const GeomState& state, const ArgValues& args,
                                                  bool& anyPresent);

    // ---- tree building helpers ----
    uint32_t sourceTag(Loc loc, uint32_t modulePath);
    uint32_t childPath(const GeomState& state, std::string_view name);
    uint32_t internMaterial(const Material& m);
    // Union of present children: nothing when there are none, else a node (null if empty).
    Instance group(std::vector<csg::NodePtr> parts, bool anyPresent, uint32_t tag);
    // Drops (nulls) the parts whose dimension differs from the first non-empty one's, with
    // OpenSCAD's warning at tag's source.
    void keepOneDimension(std::vector<csg::NodePtr>& parts, uint32_t tag);
    Model& model() { return model_; }
    const std::string& fileName(uint32_t file) const { return sources_.name(file); }
    // Where a file's data files (material textures) resolve from, and whether reading any
    // is allowed (EvaluateOptions::allowFiles).
    const std::filesystem::path& filePath(uint32_t file) const { return sources_.path(file); }
    bool filesAllowed() const { return options_.allowFiles; }
    // What cylinder() and sphere() become (EvaluateOptions::curves).
    CurveMode curveMode() const { return options_.curves; }
    // What cylinder(), sphere() and rotate_extrude() become: curveMode(), except among the
    // children of hull(), where they are faceted as OpenSCAD's whatever the mode: a hull is
    // the hull of vertices, and a curved solid's are OpenSCAD's faceted ones (io/Hull.cpp).
    CurveMode solidCurveMode() const { return hullDepth_ > 0 ? CurveMode::OpenScad : curveMode(); }
    // While one lives, solids are evaluated as the children of a hull().
    class HullChildren {
    public:
        explicit HullChildren(Evaluator& e) : e_(e) { ++e_.hullDepth_; }
        ~HullChildren() { --e_.hullDepth_; }
        HullChildren(const HullChildren&) = delete;
        HullChildren& operator=(const HullChildren&) = delete;

    private:
        Evaluator& e_;
    };

    // ---- built-in modules (BuiltinModules.cpp) ----
    using BuiltinModule = Instance (*)(Evaluator&, const InstantiationStmt&, const ContextPtr&,
                                       const GeomState&);
    const BuiltinModule* findBuiltinModule(const std::string& name) const;

private:
    Instance instantiateCall(const InstantiationStmt& s, const ContextPtr& ctx,
                             const GeomState& state);
    Instance callUserModule(const ModuleDefStmt& def, const ContextPtr& definition,
                            const InstantiationStmt& s, const ContextPtr& ctx,
                            const GeomState& state);
    Instance instantiateForLoop(const InstantiationStmt& s, const ContextPtr& ctx,
                                const GeomState& state, bool intersect);
    Instance instantiateChildrenCall(const InstantiationStmt& s, const ContextPtr& ctx,
                                     const GeomState& state);
    void loadUses(const ParsedFile& file, const ContextPtr& fileContext);
    // Whether a block assigns or defines anything. A block that does not needs no scope of
    // its own: an empty one (no variables, modules or functions, not a module call) between
    // it and its parent changes no lookup, lexical or dynamic.
    static bool definesNames(const Body& body);

public:
    // Iterates a for-loop value (vector items, range numbers, string characters, any other
    // defined value once); f returns false to stop.
    template <class F>
    void forEachItem(const Value& v, Loc loc, F&& f);

    // Call depth guard shared by modules and functions.
    struct DepthGuard {
        Evaluator& e;
        DepthGuard(Evaluator& ev, Loc loc, const std::string& name);
        ~DepthGuard() { --e.depth_; }
    };

private:
    SourceFiles& sources_;
    Model& model_;
    std::vector<Diagnostic>& diagnostics_;
    const EvaluateOptions& options_;
    std::mt19937 random_{0};
    uint32_t depth_ = 0;
    std::vector<std::string_view> moduleStack_;  // see moduleStack()
    uint32_t hullDepth_ = 0;                     // hull()s whose children are being evaluated
    uint32_t warnings_ = 0;
    uint64_t steps_ = 0;
    const char* stackTop_ = nullptr;
    size_t stackBytes_ = 0;
    // childPath's answers by (parent path index, child name), looked up without a string.
    struct ChildPathKey {
        uint32_t parent;
        std::string name;
    };
    struct ChildPathKeyView {
        uint32_t parent;
        std::string_view name;
    };
    struct ChildPathHash {
        using is_transparent = void;
        size_t operator()(const ChildPathKeyView& k) const {
            return std::hash<std::string_view>{}(k.name) ^
                   (size_t(k.parent) * 0x9E3779B97F4A7C15ull);
        }
        size_t operator()(const ChildPathKey& k) const {
            return (*this)(ChildPathKeyView{k.parent, k.name});
        }
    };
    struct ChildPathEqual {
        using is_transparent = void;
        template <class A, class B>
        bool operator()(const A& a, const B& b) const {
            return a.parent == b.parent && std::string_view(a.name) == std::string_view(b.name);
        }
    };
    std::unordered_map<ChildPathKey, uint32_t, ChildPathHash, ChildPathEqual> childPaths_;
    std::vector<std::unique_ptr<ParsedFile>> usedFiles_;
    std::unordered_map<std::string, ContextPtr> usedFileContexts_;
    ContextPtr root_;                           // built-in constants and the default $-variables
    std::optional<csg::NodePtr> rootOverride_;  // the first ! subtree
    // Contexts captured by function literals. A literal stored in a variable of its own
    // scope is a reference cycle; the destructor breaks those cycles by clearing variables.
    std::vector<std::weak_ptr<Context>> closures_;
};

// Steps charged for a statement (a module instance: scopes, tags, a CSG node of ~300 bytes)
// and for a user function call (a scope and its bindings), so that a step stays roughly one
// simple expression's worth of time and memory.
inline constexpr uint64_t kStatementSteps = 64;
inline constexpr uint64_t kCallSteps = 8;
// Most iterations a for loop or a range may yield (a bigger one is an error, not a hang).
inline constexpr double kMaxIterations = 1e7;
// Deepest nesting of lists ([[[...]]]) a part may build: printing, comparing and freeing a
// list recurse once per level.
inline constexpr uint32_t kMaxListDepth = 10000;
// Longest string (str(), echo and assert messages) a part may build, in bytes.
inline constexpr uint64_t kMaxStringBytes = uint64_t(1) << 27;

template <class F>
void Evaluator::forEachItem(const Value& v, Loc loc, F&& f) {
    switch (v.type()) {
        case Value::Type::Vector:
            for (const Value& item : v.list()) {
                spend(loc);
                if (!f(item)) return;
            }
            return;
        case Value::Type::Range: {
            const Range& r = v.range();
            const double n = r.count();
            if (n > kMaxIterations)
                fail(loc, "range has too many elements (" + formatNumber(n) + ")");
            for (double i = 0; i < n; ++i) {
                spend(loc);
                if (!f(Value(r.begin + i * r.step))) return;
            }
            return;
        }
        case Value::Type::String: {
            const std::string& s = v.string();
            for (size_t i = 0; i < s.size();) {
                size_t len = 1;
                while (i + len < s.size() &&
                       (static_cast<unsigned char>(s[i + len]) & 0xC0) == 0x80)
                    ++len;
                spend(loc);
                if (!f(Value(s.substr(i, len)))) return;
                i += len;
            }
            return;
        }
        case Value::Type::Undef:
            return;
        default:
            f(v);
            return;
    }
}

}  // namespace io
