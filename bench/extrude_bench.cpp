// What an exact extrusion costs a ray (issue 19): rays per second of `spans` through OpenSCAD
// parts drawn in 2-D and extruded, each against the same shape as OpenSCAD 2021 exports it
// (its STL, imported by csgray as a polygon mesh), measured in the same run. Scenes:
//   star/<n>/exact, star/<n>/mesh  linear_extrude(height = 2) of a star polygon of n vertices
//                                  (radii 1 and 0.6 alternating), n = 125 .. 2000 doubling
//   vase/exact, vase/mesh          rotate_extrude of a 40-vertex vase profile; OpenSCAD's mesh
//                                  with $fn = 128
//   text/exact, text/mesh          linear_extrude(height = 2) of 20 characters of text() in
//                                  Liberation Sans, its glyphs' quadratic curves exact; the
//                                  mesh is OpenSCAD's (its glyph flattening)
// Each scene is seen by a 128 x 128 camera framing its bounds from a slanted view (the text
// from above). The mesh
// scenes need `openscad` on the PATH (they are skipped without it).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "bench/BenchScenes.h"
#include "io/Evaluate.h"

namespace csg::bench {
namespace {

constexpr int kStarSizes[] = {125, 250, 500, 1000, 2000};

std::string starPart(int n) {
    std::string points;
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * 3.14159265358979323846 * i / n;
        const double r = i % 2 ? 0.97 : 1.0;
        points += (i ? "," : "") + std::string("[") + std::to_string(r * std::cos(a)) + "," +
                  std::to_string(r * std::sin(a)) + "]";
    }
    return "linear_extrude(height = 2) polygon([" + points + "]);\n";
}

std::string vasePart(bool faceted) {
    std::string points = "[0,0]";
    for (int i = 0; i <= 38; ++i) {
        const double z = 4.0 * i / 38;
        points += ",[" + std::to_string(1.0 + 0.4 * std::sin(1.7 * z) + 0.1 * z) + "," +
                  std::to_string(z) + "]";
    }
    points += ",[0,4]";
    return std::string("rotate_extrude(") + (faceted ? "$fn = 128" : "") + ") polygon([" + points +
           "]);\n";
}

// Twenty characters in four lines of five (so that the text fills a square view): capitals,
// lower case, digits and punctuation, glyphs with holes (a, e, 8, B, @) and many curves.
const char* const kTextPart =
    "linear_extrude(height = 2) for (line = [[0, \"Rays,\"], [1, \"2026:\"], [2, \"B8 @q\"],\n"
    "    [3, \"exact\"]]) translate([0, -14 * line[0]]) text(line[1], size = 10);\n";

struct ExtrudeScene {
    Scene scene;
    std::vector<Ray> rays;
};

// The scene's part as csgray reads it, or OpenSCAD's STL of it read back as a mesh.
std::string partText(const std::string& key, bool& mesh) {
    mesh = key.ends_with("/mesh");
    if (key.starts_with("star/")) return starPart(std::stoi(key.substr(5)));
    if (key.starts_with("vase/")) return vasePart(mesh);
    if (key.starts_with("text/")) return kTextPart;
    throw std::invalid_argument("no extrusion benchmark scene named " + key);
}

std::unique_ptr<ExtrudeScene> buildScene(const std::string& key) {
    bool mesh = false;
    std::string text = partText(key, mesh);
    if (mesh) {
        const std::filesystem::path dir =
            std::filesystem::temp_directory_path() / "csgray_extrude_bench";
        std::filesystem::create_directories(dir);
        std::string name = key;
        for (char& c : name)
            if (c == '/') c = '_';
        const std::filesystem::path scad = dir / (name + ".scad"), stl = dir / (name + ".stl");
        std::ofstream(scad) << text;
        const std::string command = "openscad --export-format binstl -o '" + stl.string() + "' '" +
                                    scad.string() + "' >/dev/null 2>&1";
        if (std::system(command.c_str()) != 0) return nullptr;
        text = "import(\"" + stl.string() + "\");\n";
    }
    io::EvaluateResult result = io::evaluateString(text, key, io::EvaluateOptions{});
    if (!result.ok()) throw std::runtime_error("cannot evaluate the scene " + key);
    auto scene = std::make_unique<ExtrudeScene>();
    scene->scene = Scene::compile(result.model->root);
    const Bounds3 b = scene->scene.bounds();
    PinholeCamera camera;
    camera.lookAt = b.center();
    // Text is flat: seen from above (slightly tilted) it fills the view.
    const Vec3 view = key.starts_with("text/") ? Vec3(0.0, -0.5, 1.6) : Vec3(1.2, -2.0, 1.6);
    camera.eye = b.center() + view * glm::length(b.extent());
    camera.up = Vec3(0.0, 0.0, 1.0);
    camera.horizontalFovDegrees = 30.0;
    scene->rays = camera.pixelRays(128, 128);
    return scene;
}

const ExtrudeScene* cachedScene(const std::string& key) {
    static std::map<std::string, std::unique_ptr<ExtrudeScene>> cache;
    auto it = cache.find(key);
    if (it == cache.end()) it = cache.emplace(key, buildScene(key)).first;
    return it->second.get();
}

void spansBenchmark(benchmark::State& state, const std::string& key) {
    const ExtrudeScene* scene = cachedScene(key);
    if (!scene) {
        state.SkipWithError("openscad is not installed: no mesh to compare with");
        return;
    }
    QueryContext context;
    size_t found = 0;
    for (auto _ : state)
        for (const Ray& ray : scene->rays) {
            const std::span<const Span> spans = scene->scene.spans(ray, context);
            benchmark::DoNotOptimize(spans.data());
            found += spans.size();
        }
    const double rays = static_cast<double>(context.stats.rays);
    state.SetItemsProcessed(static_cast<int64_t>(context.stats.rays));
    state.counters["spans/ray"] = static_cast<double>(found) / rays;
}

void registerAll() {
    std::vector<std::string> keys;
    for (int n : kStarSizes)
        for (const char* kind : {"exact", "mesh"})
            keys.push_back("star/" + std::to_string(n) + "/" + kind);
    keys.push_back("vase/exact");
    keys.push_back("vase/mesh");
    keys.push_back("text/exact");
    keys.push_back("text/mesh");
    for (const std::string& key : keys)
        benchmark::RegisterBenchmark(("spans/" + key).c_str(), [key](benchmark::State& state) {
            spansBenchmark(state, key);
        });
}

}  // namespace
}  // namespace csg::bench

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    csg::bench::registerAll();
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
