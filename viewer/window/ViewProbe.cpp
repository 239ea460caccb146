#include "viewer/window/ViewProbe.h"

#include <cstdio>
#include <fstream>
#include <map>

#include "viewer/cli/ProbeJson.h"
#include "viewer/render/RenderCamera.h"

namespace viewer::window {

namespace {

constexpr size_t kMaxPanelSpans = 8;  // more spans are counted, not listed

std::string number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", value);
    return text;
}

// The text of one line of a source file as it is on disk now, trimmed; "" when unreadable.
// The files are read once per probe.
class SourceLines {
public:
    std::string line(const std::string& file, uint32_t number) {
        auto [it, added] = files_.try_emplace(file);
        if (added) {
            std::ifstream in(file);
            for (std::string text; std::getline(in, text);) it->second.push_back(text);
        }
        if (number == 0 || number > it->second.size()) return {};
        const std::string& text = it->second[number - 1];
        const size_t first = text.find_first_not_of(" \t");
        const size_t last = text.find_last_not_of(" \t\r");
        return first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
    }

private:
    std::map<std::string, std::vector<std::string>> files_;
};

void describeEnd(const LoadedPart& part, const csg::Hit& hit, const char* label,
                 SourceLines& sources, std::vector<std::string>& lines) {
    if (!hit.isSurface()) {
        lines.push_back(std::string("  ") + label + "  (" +
                        (std::string(label) == "in" ? "ray starts inside" : "unbounded") + ")");
        return;
    }
    const uint32_t source = part.scene.leafTags(hit.leaf).source;
    std::string text = std::string("  ") + label + "  " +
                       csg::primitiveName(part.scene.leafPrimitive(hit.leaf)) + "  " +
                       part.model.describeSource(source);
    const std::string& path = part.model.modulePath(source);
    if (!path.empty()) text += "  " + path;
    lines.push_back(text);
    const std::string code =
        sources.line(part.model.sourceFile(source), part.model.source(source).line);
    if (!code.empty()) lines.push_back("      | " + code);
}

}  // namespace

PixelProbe probePixel(const LoadedPart& part, const render::Camera& camera, int width, int height,
                      int x, int y) {
    const csg::Ray ray = render::RenderCamera(camera, width, height).ray(x + 0.5, y + 0.5);
    PixelProbe probe;
    csg::QueryContext ctx;
    const ProbeJson json(part.model, part.scene);
    json.append(probe.json, ray.o, ray.d, ctx);

    csg::Ray query = ray;
    query.tmin = 0.0;
    const std::span<const csg::Span> spans = part.scene.spans(query, ctx);
    const std::string where = "probe at pixel " + std::to_string(x) + "," + std::to_string(y);
    if (spans.empty()) {
        probe.summary = "probe: no hit";
        probe.lines.push_back(where + ": no hit");
        return probe;
    }
    const csg::Hit& first = spans.front().in;
    probe.summary = "probe: " + std::to_string(spans.size()) +
                    (spans.size() == 1 ? " span" : " spans") +
                    ", first hit t=" + std::to_string(first.t).substr(0, 8);
    if (first.isSurface()) {
        const uint32_t source = part.scene.leafTags(first.leaf).source;
        probe.summary += std::string(" ") +
                         csg::primitiveName(part.scene.leafPrimitive(first.leaf)) + " at " +
                         part.model.describeSource(source);
    }

    probe.lines.push_back(where + ": " + std::to_string(spans.size()) +
                          (spans.size() == 1 ? " span" : " spans") + " (t is distance)");
    SourceLines sources;
    for (size_t i = 0; i < spans.size() && i < kMaxPanelSpans; ++i) {
        const csg::Span& span = spans[i];
        probe.lines.push_back("span " + std::to_string(i + 1) + ": t " + number(span.in.t) +
                              " to " + number(span.out.t) + ", length " +
                              number(span.out.t - span.in.t));
        describeEnd(part, span.in, "in", sources, probe.lines);
        describeEnd(part, span.out, "out", sources, probe.lines);
    }
    if (spans.size() > kMaxPanelSpans)
        probe.lines.push_back("... " + std::to_string(spans.size() - kMaxPanelSpans) +
                              " more spans (all of them are in the JSON on stderr)");
    return probe;
}

}  // namespace viewer::window
