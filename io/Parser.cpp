// Recursive descent over OpenSCAD 2021.01's grammar. Precedence, loosest first:
//   ?:   ||   &&   == !=   < <= > >=   + -   * / %   unary + - !   ^ (right operand unary)
//   postfix: call (), index [], member .x
#include "io/Parser.h"

#include <algorithm>

namespace io {

void Body::add(StmtPtr statement) {
    Stmt* s = statement.get();
    switch (s->kind) {
        case StmtKind::Assignment: {
            // OpenSCAD: the last assignment of a name wins, evaluated at the first one's place.
            auto* a = static_cast<AssignmentStmt*>(s);
            auto [slot, isNew] = assignmentSlots.try_emplace(a->name, assignments.size());
            if (isNew)
                assignments.push_back(a);
            else
                assignments[slot->second] = a;
            break;
        }
        case StmtKind::ModuleDef: {
            auto* m = static_cast<ModuleDefStmt*>(s);
            modules[m->name] = m;
            break;
        }
        case StmtKind::FunctionDef: {
            auto* f = static_cast<FunctionDefStmt*>(s);
            functions[f->name] = f;
            break;
        }
        case StmtKind::Instantiation:
        case StmtKind::If:
            instantiations.push_back(s);
            break;
    }
    statements.push_back(std::move(statement));
}

namespace {

struct ParseError {
    Loc loc;
    std::string message;
};

// Files being included, to stop include cycles.
constexpr int kMaxIncludeDepth = 64;

class Parser {
public:
    Parser(SourceFiles& sources, uint32_t fileIndex, std::vector<Diagnostic>& diagnostics,
           int includeDepth)
        : sources_(sources),
          file_(fileIndex),
          diagnostics_(diagnostics),
          includeDepth_(includeDepth),
          lexer_(sources.text(fileIndex), fileIndex) {
        cur_ = lexer_.next();
        next_ = lexer_.next();
        checkLexError();
    }

    // The statements of the whole file go into `into` (an including file's body).
    void parseFileInto(ParsedFile& into) {
        while (cur_.kind != Tok::End) parseStatement(into.body, &into);
    }

    ExprPtr parseWholeExpression() {
        ExprPtr e = parseExpr();
        if (cur_.kind != Tok::End) fail(cur_.loc, std::string("unexpected ") + describe(cur_));
        return e;
    }

private:
    // ---- tokens ----
    void checkLexError() {
        if (cur_.kind == Tok::Error) throw ParseError{cur_.loc, cur_.text};
    }
    void advance() {
        cur_ = std::move(next_);
        next_ = cur_.kind == Tok::End ? Token{Tok::End, cur_.loc, {}, 0.0} : lexer_.next();
        checkLexError();
    }
    bool accept(Tok kind) {
        if (cur_.kind != kind) return false;
        advance();
        return true;
    }
    static std::string describe(const Token& t) {
        if (t.kind == Tok::Identifier) return "identifier '" + t.text + "'";
        return tokenName(t.kind);
    }
    [[noreturn]] void fail(Loc loc, std::string message) {
        throw ParseError{loc, std::move(message)};
    }
    Loc expect(Tok kind, const char* context) {
        if (cur_.kind != kind)
            fail(cur_.loc, std::string("expected ") + tokenName(kind) + " " + context + ", found " +
                               describe(cur_));
        const Loc l = cur_.loc;
        advance();
        return l;
    }
    std::string expectIdentifier(const char* context) {
        if (cur_.kind != Tok::Identifier)
            fail(cur_.loc, std::string("expected a name ") + context + ", found " + describe(cur_));
        std::string name = std::move(cur_.text);
        advance();
        return name;
    }

    // Bounds recursion: every nested construct goes through one of these guards.
    struct Nest {
        Parser& p;
        Nest(Parser& parser, Loc loc) : p(parser) {
            if (++p.nesting_ > kMaxNesting)
                p.fail(loc, "nesting is too deep (more than " + std::to_string(kMaxNesting) +
                                " levels)");
        }
        ~Nest() { --p.nesting_; }
    };

    // Records the height of a new node from its children and bounds it.
    ExprPtr finish(ExprPtr e, std::initializer_list<const Expr*> children) {
        uint32_t h = 0;
        for (const Expr* c : children)
            if (c) h = std::max(h, c->depth);
        e->depth = h + 1;
        if (e->depth > kMaxExpressionDepth)
            fail(e->loc, "expression is too deeply nested (more than " +
                             std::to_string(kMaxExpressionDepth) + " levels)");
        return e;
    }
    uint32_t argumentsDepth(const Arguments& args) {
        uint32_t h = 0;
        for (const Argument& a : args)
            if (a.value) h = std::max(h, a.value->depth);
        return h;
    }

    // ---- statements ----
    void parseStatement(Body& body, ParsedFile* file) {
        Nest nest(*this, cur_.loc);
        const Loc loc = cur_.loc;
        switch (cur_.kind) {
            case Tok::Semicolon:
                advance();
                return;
            case Tok::LBrace:
                // A bare block at statement level belongs to the enclosing scope (OpenSCAD).
                advance();
                while (cur_.kind != Tok::RBrace) {
                    if (cur_.kind == Tok::End) fail(loc, "unterminated '{' (missing '}')");
                    parseStatement(body, file);
                }
                advance();
                return;
            case Tok::KwModule:
                body.add(parseModuleDef());
                return;
            case Tok::KwFunction:
                body.add(parseFunctionDef());
                return;
            case Tok::IncludePath: {
                Token t = std::move(cur_);
                advance();
                include(t, body, file);
                return;
            }
            case Tok::UsePath:
                if (!file) fail(loc, "'use' is only allowed at the top level of a file");
                file->uses.emplace_back(cur_.text, loc);
                advance();
                return;
            case Tok::Identifier:
                if (next_.kind == Tok::Assign) {
                    std::string name = std::move(cur_.text);
                    advance();
                    advance();
                    ExprPtr value = parseExpr();
                    expect(Tok::Semicolon, "after an assignment");
                    body.add(
                        std::make_unique<AssignmentStmt>(loc, std::move(name), std::move(value)));
                    return;
                }
                break;
            default:
                break;
        }
        body.add(parseInstantiation());
    }

    void include(const Token& t, Body& body, ParsedFile* file) {
        if (includeDepth_ >= kMaxIncludeDepth)
            fail(t.loc, "include nesting too deep (an include cycle?) at '" + t.text + "'");
        std::string error;
        const auto path = sources_.resolve(t.text, file_);
        auto index = sources_.load(path, error);
        if (!index) fail(t.loc, "cannot include '" + t.text + "': " + error);
        if (auto bad = findInvalidUtf8(sources_.text(*index)))
            throw ParseError{{*index, bad->line, bad->col}, "file is not valid UTF-8"};
        Parser inner(sources_, *index, diagnostics_, includeDepth_ + 1);
        // Included statements join this scope; its use<> lines join this file's.
        ParsedFile scratch;
        scratch.fileIndex = *index;
        inner.parseFileInto(scratch);
        for (auto& s : scratch.body.statements) body.add(std::move(s));
        if (file)
            for (auto& u : scratch.uses) file->uses.push_back(std::move(u));
        sources_.releaseText(*index);
    }

    StmtPtr parseModuleDef() {
        const Loc loc = expect(Tok::KwModule, "");
        auto m = std::make_unique<ModuleDefStmt>(loc, expectIdentifier("after 'module'"));
        expect(Tok::LParen, "after the module name");
        m->params = parseParameters();
        parseChildStatement(m->body);
        return m;
    }

    StmtPtr parseFunctionDef() {
        const Loc loc = expect(Tok::KwFunction, "");
        auto f = std::make_unique<FunctionDefStmt>(loc, expectIdentifier("after 'function'"));
        expect(Tok::LParen, "after the function name");
        f->params = parseParameters();
        expect(Tok::Assign, "before a function's body");
        f->body = parseExpr();
        expect(Tok::Semicolon, "after a function definition");
        return f;
    }

    // After '(' : name [= default], ... ')'
    Parameters parseParameters() {
        Parameters params;
        while (cur_.kind != Tok::RParen) {
            Parameter p;
            p.loc = cur_.loc;
            p.name = expectIdentifier("in a parameter list");
            if (accept(Tok::Assign)) p.defaultValue = parseExpr();
            params.push_back(std::move(p));
            if (!accept(Tok::Comma)) break;
        }
        expect(Tok::RParen, "to close the parameter list");
        return params;
    }

    // ';' | '{' statements '}' | one instantiation
    void parseChildStatement(Body& body) {
        Nest nest(*this, cur_.loc);
        if (accept(Tok::Semicolon)) return;
        if (cur_.kind == Tok::LBrace) {
            const Loc open = cur_.loc;
            advance();
            while (cur_.kind != Tok::RBrace) {
                if (cur_.kind == Tok::End) fail(open, "unterminated '{' (missing '}')");
                parseStatement(body, nullptr);
            }
            advance();
            return;
        }
        body.add(parseInstantiation());
    }

    StmtPtr parseInstantiation() {
        Nest nest(*this, cur_.loc);
        const Loc loc = cur_.loc;
        Modifier modifier = Modifier::None;
        switch (cur_.kind) {
            case Tok::Star:
                modifier = Modifier::Disable;
                break;
            case Tok::Bang:
                modifier = Modifier::Root;
                break;
            case Tok::Hash:
                modifier = Modifier::Highlight;
                break;
            case Tok::Percent:
                modifier = Modifier::Background;
                break;
            default:
                break;
        }
        if (modifier != Modifier::None) {
            advance();
            StmtPtr inner = parseInstantiation();
            // Nested modifiers: the outer one wins, except that a disabled subtree stays off.
            Modifier& m = inner->kind == StmtKind::If
                              ? static_cast<IfStmt*>(inner.get())->modifier
                              : static_cast<InstantiationStmt*>(inner.get())->modifier;
            if (m != Modifier::Disable) m = modifier;
            return inner;
        }
        if (cur_.kind == Tok::KwIf) {
            advance();
            auto s = std::make_unique<IfStmt>(loc);
            expect(Tok::LParen, "after 'if'");
            s->condition = parseExpr();
            expect(Tok::RParen, "after the condition of 'if'");
            parseChildStatement(s->ifTrue);
            if (accept(Tok::KwElse)) parseChildStatement(s->ifFalse);
            return s;
        }
        std::string name;
        if (cur_.kind == Tok::Identifier) {
            name = std::move(cur_.text);
        } else if (cur_.kind == Tok::KwFor || cur_.kind == Tok::KwLet || cur_.kind == Tok::KwEach) {
            name = tokenName(cur_.kind);
            name = name.substr(1, name.size() - 2);  // the keyword without its quotes
        } else {
            fail(loc, "expected a statement, found " + describe(cur_));
        }
        advance();
        auto s = std::make_unique<InstantiationStmt>(loc, std::move(name));
        expect(Tok::LParen, ("after '" + s->name + "'").c_str());
        s->args = parseArguments();
        parseChildStatement(s->children);
        return s;
    }

    // After '(' : [name =] expr, ... ')'
    Arguments parseArguments() {
        Arguments args;
        while (cur_.kind != Tok::RParen) {
            Argument a;
            a.loc = cur_.loc;
            if (cur_.kind == Tok::Identifier && next_.kind == Tok::Assign) {
                a.name = std::move(cur_.text);
                advance();
                advance();
            }
            a.value = parseExpr();
            args.push_back(std::move(a));
            if (!accept(Tok::Comma)) break;
        }
        expect(Tok::RParen, "to close the argument list");
        return args;
    }

    // name = expr, ... (let, for): every entry must be named. The list may be empty, and a
    // ';' ends it too: the parts of a C-style for, `for (; cond; )`, may be empty.
    Arguments parseAssignments(Tok closer) {
        Arguments args;
        while (cur_.kind != closer && cur_.kind != Tok::Semicolon) {
            Argument a;
            a.loc = cur_.loc;
            a.name = expectIdentifier("in an assignment list");
            expect(Tok::Assign, "after the name");
            a.value = parseExpr();
            args.push_back(std::move(a));
            if (!accept(Tok::Comma)) break;
        }
        return args;
    }

    // ---- expressions ----
    bool startsExpression() const {
        switch (cur_.kind) {
            case Tok::Semicolon:
            case Tok::Comma:
            case Tok::RParen:
            case Tok::RBracket:
            case Tok::RBrace:
            case Tok::Colon:
            case Tok::End:
                return false;
            default:
                return true;
        }
    }

    ExprPtr parseExpr() {
        Nest nest(*this, cur_.loc);
        const Loc loc = cur_.loc;
        if (cur_.kind == Tok::KwFunction && next_.kind == Tok::LParen) {
            advance();
            advance();
            auto f = std::make_unique<FunctionLiteralExpr>(loc);
            f->params = parseParameters();
            f->body = parseExpr();
            const Expr* b = f->body.get();
            return finish(std::move(f), {b});
        }
        if (cur_.kind == Tok::KwLet) {
            advance();
            auto e = std::make_unique<LetExpr>(ExprKind::Let, loc);
            expect(Tok::LParen, "after 'let'");
            e->assignments = parseAssignments(Tok::RParen);
            expect(Tok::RParen, "to close 'let'");
            e->body = parseExpr();
            e->depth = argumentsDepth(e->assignments);
            const Expr* b = e->body.get();
            return finishWithArgs(std::move(e), b);
        }
        if (cur_.kind == Tok::Identifier && (cur_.text == "assert" || cur_.text == "echo") &&
            next_.kind == Tok::LParen) {
            const ExprKind kind = cur_.text == "assert" ? ExprKind::Assert : ExprKind::Echo;
            advance();
            advance();
            auto e = std::make_unique<AssertOrEchoExpr>(kind, loc);
            e->args = parseArguments();
            if (startsExpression()) e->body = parseExpr();
            e->depth = argumentsDepth(e->args);
            const Expr* b = e->body.get();
            return finishWithArgs(std::move(e), b);
        }
        ExprPtr condition = parseBinary(0);
        if (cur_.kind != Tok::Question) return condition;
        advance();
        auto t = std::make_unique<TernaryExpr>(loc);
        t->condition = std::move(condition);
        t->ifTrue = parseExpr();
        expect(Tok::Colon, "in a '?:' expression");
        t->ifFalse = parseExpr();
        const Expr *a = t->condition.get(), *b = t->ifTrue.get(), *c = t->ifFalse.get();
        return finish(std::move(t), {a, b, c});
    }

    // e->depth holds the arguments' height on entry.
    ExprPtr finishWithArgs(ExprPtr e, const Expr* body) {
        const uint32_t argsDepth = e->depth;
        e->depth = std::max(argsDepth, body ? body->depth : 0) + 1;
        if (e->depth > kMaxExpressionDepth) fail(e->loc, "expression is too deeply nested");
        return e;
    }

    // Binary operators by precedence level (0 loosest); all left-associative.
    static int precedence(Tok kind, BinaryOp& op) {
        switch (kind) {
            case Tok::Or:
                op = BinaryOp::Or;
                return 0;
            case Tok::And:
                op = BinaryOp::And;
                return 1;
            case Tok::Equal:
                op = BinaryOp::Equal;
                return 2;
            case Tok::NotEqual:
                op = BinaryOp::NotEqual;
                return 2;
            case Tok::Less:
                op = BinaryOp::Less;
                return 3;
            case Tok::LessEqual:
                op = BinaryOp::LessEqual;
                return 3;
            case Tok::Greater:
                op = BinaryOp::Greater;
                return 3;
            case Tok::GreaterEqual:
                op = BinaryOp::GreaterEqual;
                return 3;
            case Tok::Plus:
                op = BinaryOp::Add;
                return 4;
            case Tok::Minus:
                op = BinaryOp::Subtract;
                return 4;
            case Tok::Star:
                op = BinaryOp::Multiply;
                return 5;
            case Tok::Slash:
                op = BinaryOp::Divide;
                return 5;
            case Tok::Percent:
                op = BinaryOp::Modulo;
                return 5;
            default:
                return -1;
        }
    }

    ExprPtr parseBinary(int level) {
        if (level > 5) return parseUnary();
        ExprPtr left = parseBinary(level + 1);
        BinaryOp op = BinaryOp::Add;
        while (precedence(cur_.kind, op) == level) {
            const Loc loc = cur_.loc;
            advance();
            ExprPtr right = parseBinary(level + 1);
            const Expr *a = left.get(), *b = right.get();
            left = finish(std::make_unique<BinaryExpr>(loc, op, std::move(left), std::move(right)),
                          {a, b});
        }
        return left;
    }

    ExprPtr parseUnary() {
        Nest nest(*this, cur_.loc);
        const Loc loc = cur_.loc;
        UnaryOp op;
        switch (cur_.kind) {
            case Tok::Minus:
                op = UnaryOp::Negate;
                break;
            case Tok::Plus:
                op = UnaryOp::Plus;
                break;
            case Tok::Bang:
                op = UnaryOp::Not;
                break;
            default:
                return parsePower();
        }
        advance();
        ExprPtr operand = parseUnary();
        const Expr* a = operand.get();
        return finish(std::make_unique<UnaryExpr>(loc, op, std::move(operand)), {a});
    }

    // call '^' unary: right-associative, binds tighter than unary minus (-2^2 = -4).
    ExprPtr parsePower() {
        ExprPtr base = parsePostfix();
        if (cur_.kind != Tok::Caret) return base;
        const Loc loc = cur_.loc;
        advance();
        ExprPtr exponent = parseUnary();
        const Expr *a = base.get(), *b = exponent.get();
        return finish(std::make_unique<BinaryExpr>(loc, BinaryOp::Power, std::move(base),
                                                   std::move(exponent)),
                      {a, b});
    }

    ExprPtr parsePostfix() {
        ExprPtr e = parsePrimary();
        for (;;) {
            const Loc loc = cur_.loc;
            if (accept(Tok::LParen)) {
                auto c = std::make_unique<CallExpr>(loc);
                c->args = parseArguments();
                c->depth = argumentsDepth(c->args);
                c->callee = std::move(e);
                const Expr* callee = c->callee.get();
                e = finishWithArgs(std::move(c), callee);
            } else if (accept(Tok::LBracket)) {
                auto i = std::make_unique<IndexExpr>(loc);
                i->object = std::move(e);
                i->index = parseExpr();
                expect(Tok::RBracket, "to close an index");
                const Expr *a = i->object.get(), *b = i->index.get();
                e = finish(std::move(i), {a, b});
            } else if (accept(Tok::Dot)) {
                auto m = std::make_unique<MemberExpr>(loc);
                m->object = std::move(e);
                m->member = expectIdentifier("after '.'");
                const Expr* a = m->object.get();
                e = finish(std::move(m), {a});
            } else {
                return e;
            }
        }
    }

    ExprPtr parsePrimary() {
        Nest nest(*this, cur_.loc);
        const Loc loc = cur_.loc;
        switch (cur_.kind) {
            case Tok::Number: {
                const double v = cur_.number;
                advance();
                return std::make_unique<NumberExpr>(loc, v);
            }
            case Tok::String: {
                auto e = std::make_unique<StringExpr>(loc, std::move(cur_.text));
                advance();
                return e;
            }
            case Tok::KwTrue:
                advance();
                return std::make_unique<BoolExpr>(loc, true);
            case Tok::KwFalse:
                advance();
                return std::make_unique<BoolExpr>(loc, false);
            case Tok::KwUndef:
                advance();
                return std::make_unique<Expr>(ExprKind::Undef, loc);
            case Tok::Identifier: {
                auto e = std::make_unique<IdentifierExpr>(loc, std::move(cur_.text));
                advance();
                return e;
            }
            case Tok::LParen: {
                advance();
                ExprPtr e = parseExpr();
                expect(Tok::RParen, "to close '('");
                return e;
            }
            case Tok::LBracket:
                return parseVectorOrRange();
            default:
                fail(loc, "expected an expression, found " + describe(cur_));
        }
    }

    ExprPtr parseVectorOrRange() {
        const Loc loc = expect(Tok::LBracket, "");
        auto v = std::make_unique<VectorExpr>(loc);
        if (accept(Tok::RBracket)) return v;
        ExprPtr first = parseElement();
        if (cur_.kind == Tok::Colon && first->kind < ExprKind::ForElement) {
            auto r = std::make_unique<RangeExpr>(loc);
            r->begin = std::move(first);
            advance();
            ExprPtr second = parseExpr();
            if (accept(Tok::Colon)) {
                r->step = std::move(second);
                r->end = parseExpr();
            } else {
                r->end = std::move(second);
            }
            expect(Tok::RBracket, "to close a range");
            const Expr *a = r->begin.get(), *b = r->step.get(), *c = r->end.get();
            return finish(std::move(r), {a, b, c});
        }
        uint32_t h = 0;
        v->items.push_back(std::move(first));
        while (accept(Tok::Comma)) {
            if (cur_.kind == Tok::RBracket) break;  // a trailing comma
            v->items.push_back(parseElement());
        }
        expect(Tok::RBracket, "to close a vector");
        for (const auto& item : v->items) {
            h = std::max(h, item->depth);
            if (item->kind >= ExprKind::ForElement) v->hasComprehension = true;
        }
        v->depth = h;
        return finishWithArgs(std::move(v), nullptr);
    }

    // One vector element: an expression or a list-comprehension element.
    ExprPtr parseElement() {
        Nest nest(*this, cur_.loc);
        const Loc loc = cur_.loc;
        switch (cur_.kind) {
            case Tok::KwFor: {
                advance();
                expect(Tok::LParen, "after 'for'");
                Arguments init = parseAssignments(Tok::RParen);
                if (accept(Tok::Semicolon)) {
                    auto e = std::make_unique<ForCElementExpr>(loc);
                    e->init = std::move(init);
                    e->condition = parseExpr();
                    expect(Tok::Semicolon, "after the condition of 'for'");
                    e->update = parseAssignments(Tok::RParen);
                    expect(Tok::RParen, "to close 'for'");
                    e->body = parseElement();
                    e->depth = std::max(
                        {argumentsDepth(e->init), argumentsDepth(e->update), e->condition->depth});
                    const Expr* b = e->body.get();
                    return finishWithArgs(std::move(e), b);
                }
                expect(Tok::RParen, "to close 'for'");
                auto e = std::make_unique<LetExpr>(ExprKind::ForElement, loc);
                e->assignments = std::move(init);
                e->body = parseElement();
                e->depth = argumentsDepth(e->assignments);
                const Expr* b = e->body.get();
                return finishWithArgs(std::move(e), b);
            }
            case Tok::KwIf: {
                advance();
                auto e = std::make_unique<IfElementExpr>(loc);
                expect(Tok::LParen, "after 'if'");
                e->condition = parseExpr();
                expect(Tok::RParen, "after the condition of 'if'");
                e->ifTrue = parseElement();
                if (accept(Tok::KwElse)) e->ifFalse = parseElement();
                const Expr *a = e->condition.get(), *b = e->ifTrue.get(), *c = e->ifFalse.get();
                return finish(std::move(e), {a, b, c});
            }
            case Tok::KwLet: {
                advance();
                auto e = std::make_unique<LetExpr>(ExprKind::LetElement, loc);
                expect(Tok::LParen, "after 'let'");
                e->assignments = parseAssignments(Tok::RParen);
                expect(Tok::RParen, "to close 'let'");
                e->body = parseElement();
                e->depth = argumentsDepth(e->assignments);
                const Expr* b = e->body.get();
                return finishWithArgs(std::move(e), b);
            }
            case Tok::KwEach: {
                advance();
                auto e = std::make_unique<EachElementExpr>(loc);
                e->value = parseElement();
                const Expr* a = e->value.get();
                return finish(std::move(e), {a});
            }
            case Tok::LParen:
                // ( comprehension-element ) groups an element; otherwise an expression.
                if (next_.kind == Tok::KwFor || next_.kind == Tok::KwIf ||
                    next_.kind == Tok::KwEach) {
                    advance();
                    ExprPtr e = parseElement();
                    expect(Tok::RParen, "to close '('");
                    return e;
                }
                return parseExpr();
            default:
                return parseExpr();
        }
    }

    SourceFiles& sources_;
    uint32_t file_;
    std::vector<Diagnostic>& diagnostics_;
    int includeDepth_;
    Lexer lexer_;
    Token cur_, next_;
    uint32_t nesting_ = 0;
};

void report(SourceFiles& sources, std::vector<Diagnostic>& diagnostics, const ParseError& e) {
    diagnostics.push_back(
        {sources.name(e.loc.file), e.loc.line, e.loc.col, Severity::Error, e.message});
}

}  // namespace

std::unique_ptr<ParsedFile> parseFile(SourceFiles& sources, uint32_t fileIndex,
                                      std::vector<Diagnostic>& diagnostics) {
    if (auto bad = findInvalidUtf8(sources.text(fileIndex))) {
        diagnostics.push_back({sources.name(fileIndex), bad->line, bad->col, Severity::Error,
                               "file is not valid UTF-8"});
        return nullptr;
    }
    auto file = std::make_unique<ParsedFile>();
    file->fileIndex = fileIndex;
    try {
        Parser parser(sources, fileIndex, diagnostics, 0);
        parser.parseFileInto(*file);
    } catch (const ParseError& e) {
        report(sources, diagnostics, e);
        return nullptr;
    }
    return file;
}

ExprPtr parseExpression(SourceFiles& sources, uint32_t fileIndex,
                        std::vector<Diagnostic>& diagnostics) {
    if (auto bad = findInvalidUtf8(sources.text(fileIndex))) {
        diagnostics.push_back({sources.name(fileIndex), bad->line, bad->col, Severity::Error,
                               "text is not valid UTF-8"});
        return nullptr;
    }
    try {
        Parser parser(sources, fileIndex, diagnostics, 0);
        return parser.parseWholeExpression();
    } catch (const ParseError& e) {
        report(sources, diagnostics, e);
        return nullptr;
    }
}

}  // namespace io
