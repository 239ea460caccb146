// OpenSCAD's grammar (parser.y of OpenSCAD 2021.01) as a recursive-descent parser producing
// io/Ast.h. Nesting is bounded (kMaxNesting), so hostile input gives an error, not a stack
// overflow. The first syntax error stops the file, as in OpenSCAD.
#pragma once

#include <memory>
#include <vector>

#include "io/Ast.h"
#include "io/Diagnostic.h"
#include "io/SourceFiles.h"

namespace io {

// Deepest nesting of brackets, calls and blocks the parser accepts.
inline constexpr uint32_t kMaxNesting = 1000;
// Tallest expression tree (a+a+a+... is as tall as it is long) the parser accepts.
inline constexpr uint32_t kMaxExpressionDepth = 10000;

// Parses file `fileIndex` of sources. include <f> files are loaded through sources and
// spliced in place. Null (with an error appended to diagnostics) on a syntax error, invalid
// UTF-8, or an include that cannot be read.
std::unique_ptr<ParsedFile> parseFile(SourceFiles& sources, uint32_t fileIndex,
                                      std::vector<Diagnostic>& diagnostics);

// Parses text that must be exactly one expression (a -D value); null on error.
ExprPtr parseExpression(SourceFiles& sources, uint32_t fileIndex,
                        std::vector<Diagnostic>& diagnostics);

}  // namespace io
