// Expressions printed back as OpenSCAD 2021 prints them (src/expression.cc, the print()
// methods): what str() and echo() show of a function literal's value. Every binary and ternary
// operation is parenthesized, unary plus is dropped, a call of anything but a name puts the
// callee in parentheses, and a comprehension's for/if/let/each wrap their bodies in
// parentheses the way OpenSCAD's list-comprehension nodes do.
#pragma once

#include <string>

#include "io/Ast.h"

namespace io {

// The operator as written: "+", "<=", "&&" and so on.
const char* binaryOpSymbol(BinaryOp op);

// Appends e as OpenSCAD prints it.
void appendExpr(std::string& out, const Expr& e);

// Appends "function(a, b = default) body", a function value as OpenSCAD prints it.
void appendFunctionLiteral(std::string& out, const FunctionLiteralExpr& f);

}  // namespace io
