// import() of SVG files: see io/SvgModule.h, and ../shared/OPENSCAD.md §2 for the OpenSCAD
// 2021 behaviour followed (src/import.cc, src/import_svg.cc).
#include "io/SvgModule.h"

#include <cmath>
#include <filesystem>

#include "io/DataFiles.h"
#include "io/SvgFile.h"
#include "primitives/Extrusion.h"

namespace io {

namespace {

// Evaluation steps charged per segment (EvaluateOptions::maxSteps, ~5 bytes a step): a
// segment keeps 100 bytes, its share of the outline's hierarchy and what reading made.
constexpr uint64_t kSegmentSteps = 50;

}  // namespace

bool isSvgFile(std::string_view name) {
    return lowerExtension(name) == ".svg";
}

Instance importSvg(Evaluator& e, const BoundArgs& b, const GeomState& state) {
    if (b.given(2) && !b[2].isNumber()) b.bad(e, 2, "a number (a preview hint, ignored)");
    SvgOptions options;
    // OpenSCAD 2021: center must be a boolean and dpi a number >= 0.001, else the defaults.
    if (b.given(5)) {
        if (b[5].isBool())
            options.center = b[5].asBool();
        else
            e.warn(b.loc(5), "import(): center = " + b[5].brief() +
                                 " is not a boolean; false is used, as in OpenSCAD");
    }
    if (b.given(6)) {
        if (!b[6].isNumber() || !std::isfinite(b[6].number()))
            e.warn(b.loc(6), "import(): dpi = " + b[6].brief() +
                                 " is not a number; 72 is used, as in OpenSCAD");
        else if (b[6].number() < 0.001)
            e.warn(b.loc(6), "import(): dpi = " + formatNumber(b[6].number()) +
                                 " is below 0.001; 72 is used, as in OpenSCAD");
        else
            options.dpi = b[6].number();
    }
    options.faceted = e.curveMode() == CurveMode::OpenScad;
    options.maxSegments = e.budget().left / kSegmentSteps;
    if (!e.filesAllowed()) e.fail(b.loc(0), "import(): reading files is not allowed here");

    const std::string& written = b[0].string();
    const std::filesystem::path path = lookupDataFile(e, b.call.loc, b.loc(0), written);
    SvgReadResult read = readSvgFile(path, options);
    const auto where = [&](uint32_t line) {
        return path.string() + (line > 0 ? ":" + std::to_string(line) : "");
    };
    if (!read.drawing) e.fail(b.loc(0), "import(): " + where(read.line) + ": " + read.error);
    e.spend(b.call.loc, kSegmentSteps * read.drawing->segments);
    for (const SvgWarning& w : read.drawing->warnings)
        e.warn(b.call.loc, "import(): " + where(w.line) + ": " + w.message);
    const uint32_t tag = e.sourceTag(b.call.loc, e.childPath(state, b.call.name));
    std::vector<csg::NodePtr> leaves;
    for (csg::Outline& outline : read.drawing->shapes)
        leaves.push_back(csg::leaf(
            csg::Extrusion::plane(std::make_shared<csg::Outline>(std::move(outline)), "import"),
            {tag, state.material}));
    return csg::uniteAll(leaves, {tag, 0});
}

}  // namespace io
