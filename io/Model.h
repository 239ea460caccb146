// What evaluating a part gives its clients (the command line, the renderer): the CSG tree and
// the scene extras that OpenSCAD itself ignores (camera, lights, background, materials), plus
// the tables that turn a node's opaque csg::Tags back into a material and a source location.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "csg/Tree.h"
#include "primitives/base/Math.h"
#include "viewer/render/Look.h"

namespace io {

// The renderer's description types, filled in by the language.
using viewer::render::Camera;
using viewer::render::Light;
using viewer::render::Material;
using viewer::render::Pattern;
using viewer::render::Projection;
using viewer::render::Rgb8Image;

// Where a node came from: the statement that created it and the module call chain leading to
// it, e.g. "part() > difference > cylinder". fileIndex indexes Model::files.
struct SourceInfo {
    uint32_t fileIndex = 0;
    uint32_t line = 0;  // 1-based; 0 for the "unknown" entry 0
    uint32_t col = 0;
    uint32_t modulePathIndex = 0;  // indexes Model::modulePaths
};

// A subtree drawn by a modifier: # (highlight, also part of root) or % (background, not part
// of root). node already carries the accumulated transform: it is in world coordinates.
struct MarkedPart {
    csg::NodePtr node;
    uint32_t source = 0;  // Tags::source of the modifier's statement
};

// The scene look (camera, lights, background, materials, textures) is the renderer's
// description (viewer/render/Look.h), which the language fills in.
struct Model : viewer::render::SceneLook {
    // The solid: the implicit top-level union. nullptr is the empty solid (an empty file).
    csg::NodePtr root;
    // The part is 2-D: root is its shape extruded 1 unit thick about z = 0, as OpenSCAD
    // previews it (a 3-D export of it is an error).
    bool twoD = false;
    // A 2-D part's shape itself (Plane leaves, io/Shapes2D.h), which 2-D export draws.
    csg::NodePtr shape2D;

    std::vector<MarkedPart> highlighted;      // # subtrees, for a highlight overlay
    std::vector<MarkedPart> backgroundParts;  // % subtrees, transparent and not solid

    // Indexed by csg::Tags::source; entry 0 is "unknown" (file "", line 0).
    std::vector<SourceInfo> sources{SourceInfo{}};
    // Every file that was read (the main file first), and the interned module paths.
    std::vector<std::string> files;
    // Module paths as a tree, one step each: path i is modulePath(parent) > name. Entry 0 is
    // the top level (""). Kept as steps, not strings, so a chain of n nested calls takes O(n)
    // memory, not O(n^2).
    struct ModulePathStep {
        uint32_t parent = 0;
        std::string name;
    };
    std::vector<ModulePathStep> modulePaths{ModulePathStep{}};

    // Convenience lookups for a Tags::source value; an out-of-range tag reads as entry 0.
    const SourceInfo& source(uint32_t tag) const;
    const std::string& sourceFile(uint32_t tag) const;
    std::string modulePath(uint32_t tag) const;
    // The text of module path `path` ("part() > difference > cylinder"; "" for 0).
    std::string modulePathText(uint32_t path) const;
    // "file:line:col" of a tag (just "file" or "" when positions are unknown).
    std::string describeSource(uint32_t tag) const;
};

}  // namespace io
