// The torus's robustness sweep (bench/README.md, torus section): for tori from fat to very thin
// (r/R = 0.999 .. 1e-6), random lines, and for each line
//   - sampled points judged by the spans of Solver::Auto (the tube form) against inside(), the
//     one-line membership test: every span's middle, every gap's middle (and beyond both ends),
//     and random points of the line, leaving out points within a margin of a span end;
//   - whether Solver::ClosedForm (the quartic without the tube form) finds fewer spans of
//     positive length than Auto on the same line (a span lost to the quartic's rounding).
// A plain program: it prints one line per torus.
//
//   torus_sweep [--lines N]      N lines per torus (default 200000)
//
// Lines: half through a random point of the torus's bounds in a random direction, half aimed
// at a random point near the tube's centre circle (within 1.2 r), so thin tori are hit too.
// Notation: t is the parameter of o + t d; R, r the major and minor radii.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "primitives/Torus.h"
#include "tests/SeededRng.h"

namespace {

using namespace csg;

using csg::testing::Rng;

int solidCount(const LocalSpans& s) {
    int n = 0;
    for (int i = 0; i < s.count; ++i) n += s.entries[i].tOut > s.entries[i].tIn;
    return n;
}

struct Tally {
    long lines = 0, hitLines = 0, points = 0, disagree = 0, closedFormLost = 0;
};

// One line o + t d, t in [0, tEnd] (the bounds lie inside it).
void checkLine(const Torus& autoTorus, const Torus& quarticTorus, const Vec3& o, const Vec3& d,
               double tEnd, Rng& rng, Tally& tally) {
    LocalSpans s;
    autoTorus.spans(o, d, s);
    LocalSpans q;
    quarticTorus.spans(o, d, q);
    ++tally.lines;
    tally.hitLines += solidCount(s) > 0;
    tally.closedFormLost += solidCount(q) < solidCount(s);

    // Span ends are right to a few ulps of t; a point nearer than this to one is not judged.
    const double margin = 1e-12 * (autoTorus.majorRadius + autoTorus.minorRadius) / glm::length(d);
    auto judge = [&](double t) {
        bool inSpan = false;
        for (int j = 0; j < s.count; ++j) {
            if (std::abs(t - s.entries[j].tIn) < margin || std::abs(t - s.entries[j].tOut) < margin)
                return;
            inSpan |= t >= s.entries[j].tIn && t <= s.entries[j].tOut;
        }
        ++tally.points;
        tally.disagree += inSpan != autoTorus.inside(o + t * d);
    };
    judge(0.0);
    judge(tEnd);
    for (int j = 0; j < s.count; ++j) {
        judge(0.5 * s.entries[j].tIn + 0.5 * s.entries[j].tOut);
        if (j + 1 < s.count) judge(0.5 * s.entries[j].tOut + 0.5 * s.entries[j + 1].tIn);
    }
    for (int k = 0; k < 8; ++k) judge(rng.uniform(0.0, tEnd));
}

}  // namespace

int main(int argc, char** argv) {
    long lines = 200000;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--lines") == 0 && i + 1 < argc) {
            lines = std::atol(argv[++i]);
        } else {
            std::fprintf(stderr, "usage: torus_sweep [--lines N]\n");
            return 2;
        }
    }
    if (lines < 2) {
        std::fprintf(stderr, "torus_sweep: --lines must be at least 2\n");
        return 2;
    }
    std::printf(
        "%ld random lines per torus (R = 1); points judged by Auto's spans against "
        "inside()\n",
        lines);
    Rng rng(4242);
    for (const double r : {0.999, 0.5, 1e-2, 1e-4, 1e-6}) {
        Torus autoTorus{1.0, r};
        Torus quarticTorus = autoTorus;
        quarticTorus.solver = Solver::ClosedForm;
        const Bounds3 box = autoTorus.bounds();
        const double size = 1.0 + r;
        Tally tally;
        for (long i = 0; i < lines; ++i) {
            Vec3 p;
            if (i % 2 == 0) {
                p = rng.inBox(box.lo, box.hi);
            } else {
                const double angle = rng.uniform(0.0, 6.283185307179586);
                const double offset = 1.2 * r * rng.uniform();  // drawn first, as gcc did
                p = Vec3(std::cos(angle), std::sin(angle), 0.0) + rng.unit() * offset;
            }
            // One draw per statement (the length first, as gcc did), so that the lines do not
            // depend on the compiler's evaluation order.
            const double length = std::pow(10.0, rng.uniform(-2, 2));
            const Vec3 d = rng.unit() * length;
            // From 3 torus sizes before p to 3 after: both ends outside the bounds.
            const double reach = 3.0 * size / glm::length(d);
            checkLine(autoTorus, quarticTorus, p - reach * d, d, 2.0 * reach, rng, tally);
        }
        std::printf(
            "r/R = %-6g lines %ld, hitting %ld; points judged %ld, disagreeing with "
            "inside() %ld; lines where closed-form has fewer spans than auto %ld\n",
            r, tally.lines, tally.hitLines, tally.points, tally.disagree, tally.closedFormLost);
    }
    return 0;
}
