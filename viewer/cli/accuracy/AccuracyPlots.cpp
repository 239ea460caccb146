// Notation: a panel maps log10 of the data onto a rectangle of the SVG canvas (y grows down);
// a series is one solver's points in the order they are drawn.
#include "viewer/cli/accuracy/AccuracyPlots.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace csg {
namespace {

constexpr double kErrorFloor = 1e-17;  // errors of exactly 0, drawn on a log axis
constexpr double kUlpsFloor = 0.01;    // the same for errors in ulps
const char* const kColors[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                               "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};

std::string num(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.1f", v);
    return b;
}

// The solvers in order of first appearance, each with its colour.
std::vector<std::string> solversOf(const std::vector<AccuracyRow>& rows) {
    std::vector<std::string> out;
    for (const AccuracyRow& r : rows)
        if (std::find(out.begin(), out.end(), r.solver) == out.end()) out.push_back(r.solver);
    return out;
}
const char* colorOf(const std::vector<std::string>& solvers, const std::string& s) {
    const size_t i = size_t(std::find(solvers.begin(), solvers.end(), s) - solvers.begin());
    return kColors[i % (sizeof kColors / sizeof *kColors)];
}

struct Panel {
    double x, y, w, h;          // canvas rectangle
    double xLo, xHi, yLo, yHi;  // data range, log10 when the axis is logarithmic
    bool xLog = true, yLog = true;

    double px(double v) const {
        const double t = xLog ? std::log10(v) : v;
        return x + w * (t - xLo) / (xHi - xLo);
    }
    double py(double v) const {
        const double t = yLog ? std::log10(v) : v;
        return y + h - h * (t - yLo) / (yHi - yLo);
    }
};

// Fits a log axis range around the values (whole decades, at least one wide).
void logRange(const std::vector<double>& values, double& lo, double& hi) {
    lo = 1e300, hi = -1e300;
    for (double v : values)
        if (v > 0.0) lo = std::min(lo, std::log10(v)), hi = std::max(hi, std::log10(v));
    if (lo > hi) lo = 0.0, hi = 1.0;
    lo = std::floor(lo), hi = std::ceil(hi);
    if (hi <= lo) hi = lo + 1.0;
}

// Frame, decade grid and tick labels, axis titles and the panel's title.
void drawAxes(std::ostringstream& svg, const Panel& p, const std::string& title,
              const std::string& xTitle, const std::string& yTitle) {
    svg << "<rect x='" << num(p.x) << "' y='" << num(p.y) << "' width='" << num(p.w) << "' height='"
        << num(p.h) << "' fill='none' stroke='#444'/>\n";
    const int xStep = p.xLog ? std::max(1, int(p.xHi - p.xLo) / 6) : 2;
    for (double t = p.xLo; t <= p.xHi + 1e-9; t += xStep) {
        const double cx = p.x + p.w * (t - p.xLo) / (p.xHi - p.xLo);
        svg << "<line x1='" << num(cx) << "' y1='" << num(p.y) << "' x2='" << num(cx) << "' y2='"
            << num(p.y + p.h) << "' stroke='#ddd'/>\n<text x='" << num(cx) << "' y='"
            << num(p.y + p.h + 12) << "' font-size='9' text-anchor='middle'>"
            << (p.xLog ? "1e" + std::to_string(int(t)) : std::to_string(int(t))) << "</text>\n";
    }
    const int yStep = std::max(1, int(p.yHi - p.yLo) / 6);
    for (double t = p.yLo; t <= p.yHi + 1e-9; t += yStep) {
        const double cy = p.y + p.h - p.h * (t - p.yLo) / (p.yHi - p.yLo);
        svg << "<line x1='" << num(p.x) << "' y1='" << num(cy) << "' x2='" << num(p.x + p.w)
            << "' y2='" << num(cy) << "' stroke='#ddd'/>\n<text x='" << num(p.x - 3) << "' y='"
            << num(cy + 3) << "' font-size='9' text-anchor='end'>1e" << int(t) << "</text>\n";
    }
    svg << "<text x='" << num(p.x + p.w / 2) << "' y='" << num(p.y - 5)
        << "' font-size='11' font-weight='bold' text-anchor='middle'>" << title << "</text>\n"
        << "<text x='" << num(p.x + p.w / 2) << "' y='" << num(p.y + p.h + 24)
        << "' font-size='9' text-anchor='middle'>" << xTitle << "</text>\n"
        << "<text transform='translate(" << num(p.x - 32) << ',' << num(p.y + p.h / 2)
        << ") rotate(-90)' font-size='9' text-anchor='middle'>" << yTitle << "</text>\n";
}

void drawLine(std::ostringstream& svg, const std::vector<std::pair<double, double>>& pts,
              const char* color, double width) {
    if (pts.size() < 2) return;
    svg << "<polyline fill='none' stroke='" << color << "' stroke-width='" << width << "' points='";
    for (auto [x, y] : pts) svg << num(x) << ',' << num(y) << ' ';
    svg << "'/>\n";
}

void drawLegend(std::ostringstream& svg, const std::vector<std::string>& solvers, double x,
                double y, const std::string& note) {
    for (size_t i = 0; i < solvers.size(); ++i) {
        const double cy = y + 14.0 * double(i);
        svg << "<line x1='" << num(x) << "' y1='" << num(cy) << "' x2='" << num(x + 18) << "' y2='"
            << num(cy) << "' stroke='" << colorOf(solvers, solvers[i])
            << "' stroke-width='2'/>\n<text x='" << num(x + 22) << "' y='" << num(cy + 3)
            << "' font-size='10'>" << solvers[i] << "</text>\n";
    }
    svg << "<text x='" << num(x) << "' y='" << num(y + 14.0 * double(solvers.size()) + 6)
        << "' font-size='9'>" << note << "</text>\n";
}

std::string classLabel(const AccuracyRow& r) {
    return r.surfaceClass == "shells" ? "shells " + std::to_string(r.degree) : r.surfaceClass;
}

}  // namespace

std::string paretoSvg(const std::vector<AccuracyRow>& input, bool ulps) {
    // A series is a solver, or with ulps a solver with its polisher.
    std::vector<AccuracyRow> rows = input;
    if (ulps)
        for (AccuracyRow& r : rows)
            if (r.polisher != "none") r.solver += "+" + r.polisher;
    const auto errorOf = [ulps](const AccuracyRow& r) {
        return ulps ? std::max(kUlpsFloor, r.maxUlps) : std::max(kErrorFloor, r.p99Error);
    };
    std::vector<std::string> classes;
    for (const AccuracyRow& r : rows)
        if (r.surfaceClass != "degree-sweep" &&
            std::find(classes.begin(), classes.end(), classLabel(r)) == classes.end())
            classes.push_back(classLabel(r));
    const std::vector<std::string> solvers = solversOf(rows);
    const int cols = 4, rowsOfPanels = int(classes.size() + cols) / cols;  // + the legend cell
    const double cellW = 300, cellH = 250, width = cols * cellW, height = rowsOfPanels * cellH;
    std::ostringstream svg;
    svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << width << "' height='" << height
        << "' font-family='sans-serif'>\n<rect width='100%' height='100%' fill='white'/>\n";
    for (size_t k = 0; k < classes.size(); ++k) {
        std::vector<const AccuracyRow*> mine;
        std::vector<double> xs, ys;
        for (const AccuracyRow& r : rows)
            if (r.surfaceClass != "degree-sweep" && classLabel(r) == classes[k] &&
                r.raysPerSecond > 0.0) {
                mine.push_back(&r);
                xs.push_back(1e9 / r.raysPerSecond);
                ys.push_back(errorOf(r));
            }
        Panel p{double(k % cols) * cellW + 50,
                double(k / cols) * cellH + 25,
                cellW - 70,
                cellH - 70,
                0,
                0,
                0,
                0};
        logRange(xs, p.xLo, p.xHi);
        logRange(ys, p.yLo, p.yHi);
        drawAxes(svg, p, classes[k], "ns per ray (solve only)",
                 ulps ? "max error in ulps of t" : "p99 relative error");
        // Step 1: each solver's line through its tolerances, coarse to full precision (timings
        // are noisy, so ordering by time would zigzag); a cross marks wrong counts.
        std::vector<std::pair<double, double>> clean;  // (ns, error) without wrong counts
        for (const std::string& s : solvers) {
            std::vector<const AccuracyRow*> line;
            for (const AccuracyRow* r : mine)
                if (r->solver == s) line.push_back(r);
            std::sort(line.begin(), line.end(), [](const AccuracyRow* a, const AccuracyRow* b) {
                const double ka = a->relTol > 0 ? -a->relTol : 1.0;
                const double kb = b->relTol > 0 ? -b->relTol : 1.0;
                return ka < kb;
            });
            std::vector<std::pair<double, double>> pts;
            for (const AccuracyRow* r : line) {
                const double ns = 1e9 / r->raysPerSecond, e = errorOf(*r);
                const double cx = p.px(ns), cy = p.py(e);
                pts.push_back({cx, cy});
                if (r->wrongCounts > 0)
                    svg << "<path d='M" << num(cx - 4) << ' ' << num(cy - 4) << "l8 8m0 -8l-8 8'"
                        << " stroke='" << colorOf(solvers, s) << "' stroke-width='1.5'/>\n";
                else
                    clean.push_back({ns, e});
                svg << "<circle cx='" << num(cx) << "' cy='" << num(cy) << "' r='2' fill='"
                    << colorOf(solvers, s) << "'/>\n";
            }
            drawLine(svg, pts, colorOf(solvers, s), 1.0);
        }
        // Step 2: the Pareto front, as steps through the settings nothing beats in both.
        std::sort(clean.begin(), clean.end());
        std::vector<std::pair<double, double>> front;
        double best = 1e300;
        for (auto [ns, e] : clean)
            if (e < best) {
                if (!front.empty()) front.push_back({p.px(ns), front.back().second});
                front.push_back({p.px(ns), p.py(e)});
                best = e;
            }
        drawLine(svg, front, "black", 1.5);
    }
    drawLegend(svg, solvers, double(classes.size() % cols) * cellW + 30,
               double(classes.size() / cols) * cellH + 30,
               "x = wrong root counts; black = Pareto front");
    svg << "</svg>\n";
    return svg.str();
}

std::string degreeSweepSvg(const std::vector<AccuracyRow>& rows) {
    std::vector<AccuracyRow> sweep;
    for (const AccuracyRow& r : rows)
        if (r.surfaceClass == "degree-sweep" && r.raysPerSecond > 0.0) sweep.push_back(r);
    const std::vector<std::string> solvers = solversOf(sweep);
    std::vector<double> rates, errors;
    int dLo = 16, dHi = 2;
    for (const AccuracyRow& r : sweep) {
        rates.push_back(r.raysPerSecond);
        errors.push_back(std::max(kErrorFloor, r.maxError));
        dLo = std::min(dLo, r.degree), dHi = std::max(dHi, r.degree);
    }
    std::ostringstream svg;
    svg << "<svg xmlns='http://www.w3.org/2000/svg' width='1000' height='330' "
           "font-family='sans-serif'>\n<rect width='100%' height='100%' fill='white'/>\n";
    Panel speed{50, 25, 340, 260, double(dLo), double(dHi), 0, 0, false, true};
    Panel error{460, 25, 340, 260, double(dLo), double(dHi), 0, 0, false, true};
    logRange(rates, speed.yLo, speed.yHi);
    logRange(errors, error.yLo, error.yHi);
    drawAxes(svg, speed, "speed, roots to full precision", "degree", "rays per second");
    drawAxes(svg, error, "max error vs the 50-digit roots", "degree", "max relative error");
    for (const std::string& s : solvers) {
        std::vector<std::pair<double, double>> a, b;
        for (const AccuracyRow& r : sweep)
            if (r.solver == s) {
                a.push_back({speed.px(r.degree), speed.py(r.raysPerSecond)});
                b.push_back({error.px(r.degree), error.py(std::max(kErrorFloor, r.maxError))});
            }
        drawLine(svg, a, colorOf(solvers, s), 1.2);
        drawLine(svg, b, colorOf(solvers, s), 1.2);
    }
    drawLegend(svg, solvers, 830, 40, "");
    svg << "</svg>\n";
    return svg.str();
}

}  // namespace csg
