// Notation: a piece is a dyadic sub-square [u0, u1] x [v0, v1] of [0, 1]^2 with the interval
// Bernstein coefficients b[i][j] (i along u) of F1 and F2 on it; X_i the Krawczyk box of
// crossing i. "Excludes" = one F_k's coefficients are all > 0 or all < 0 on the piece.
#include "primitives/patch/PatchCertify.h"

#include <algorithm>

#include "primitives/base/Tolerances.h"
#include "primitives/solvers/Interval.h"

namespace csg {

namespace {

using Coeffs = std::array<std::array<Interval, 4>, 4>;

// Pieces examined before the exclusion gives up, and the depth of halvings (30 per axis:
// pieces of 1e-9, the slack, where a crossing just outside an edge can no longer be told
// from one just inside).
constexpr int kMaxPieces = 4000;
constexpr int kMaxDepth = 60;
// Krawczyk radii tried, largest first: a larger box makes the exclusion cheaper.
constexpr double kRadii[] = {1e-3, 1e-5, 1e-7, 1e-9};

struct Piece {
    Coeffs f[2];
    double u0, u1, v0, v1;
    int depth;
};

struct Box {
    double ul, uh, vl, vh;
};

// De Casteljau at 1/2 on four intervals: left and right halves.
void halve(const std::array<Interval, 4>& b, std::array<Interval, 4>& l,
           std::array<Interval, 4>& r) {
    const Interval a1 = 0.5 * (b[0] + b[1]), b1 = 0.5 * (b[1] + b[2]), c1 = 0.5 * (b[2] + b[3]);
    const Interval a2 = 0.5 * (a1 + b1), b2 = 0.5 * (b1 + c1);
    const Interval a3 = 0.5 * (a2 + b2);
    l = {b[0], a1, a2, a3};
    r = {a3, b2, c1, b[3]};
}

void splitU(const Coeffs& c, Coeffs& left, Coeffs& right) {
    for (int j = 0; j < 4; ++j) {
        std::array<Interval, 4> col{c[0][j], c[1][j], c[2][j], c[3][j]}, l, r;
        halve(col, l, r);
        for (int i = 0; i < 4; ++i) {
            left[i][j] = l[i];
            right[i][j] = r[i];
        }
    }
}

void splitV(const Coeffs& c, Coeffs& left, Coeffs& right) {
    for (int i = 0; i < 4; ++i) halve(c[i], left[i], right[i]);
}

bool excludes(const Coeffs& c) {
    bool positive = true, negative = true;
    for (const auto& row : c)
        for (const Interval& x : row) {
            positive = positive && x.lo > 0.0;
            negative = negative && x.hi < 0.0;
        }
    return positive || negative;
}

// The cubic Bernstein polynomials and their derivatives over an interval of the parameter.
std::array<Interval, 4> bernstein(Interval x) {
    const Interval y = 1.0 - x;
    return {y * y * y, 3.0 * (x * (y * y)), 3.0 * ((x * x) * y), x * x * x};
}
std::array<Interval, 4> bernsteinDerivative(Interval x) {
    const Interval y = 1.0 - x;
    return {-3.0 * (y * y), 3.0 * (y * (y - 2.0 * x)), 3.0 * (x * (2.0 * y - x)), 3.0 * (x * x)};
}

Interval combine(const Coeffs& c, const std::array<Interval, 4>& bu,
                 const std::array<Interval, 4>& bv) {
    Interval s{0.0, 0.0};
    for (int i = 0; i < 4; ++i) {
        Interval row{0.0, 0.0};
        for (int j = 0; j < 4; ++j) row = row + c[i][j] * bv[j];
        s = s + bu[i] * row;
    }
    return s;
}

// F over the box U x V (natural interval extension of the Bernstein form).
Interval enclose(const Coeffs& c, Interval U, Interval V) {
    return combine(c, bernstein(U), bernstein(V));
}

// Krawczyk's test on X = [u +- r] x [v +- r]: true (and the box) when K(X) lies inside X and
// inside the square widened by the slack, so F has exactly one zero in X.
bool krawczyk(const Coeffs f[2], double u, double v, double r, Box& box) {
    const Interval U{u - r, u + r}, V{v - r, v + r};
    const Interval pu = pointInterval(u), pv = pointInterval(v);
    Interval F[2], J[2][2];
    double Jm[2][2];
    for (int k = 0; k < 2; ++k) {
        F[k] = enclose(f[k], pu, pv);
        J[k][0] = combine(f[k], bernsteinDerivative(U), bernstein(V));
        J[k][1] = combine(f[k], bernstein(U), bernsteinDerivative(V));
        Jm[k][0] = combine(f[k], bernsteinDerivative(pu), bernstein(pv)).lo;
        Jm[k][1] = combine(f[k], bernstein(pu), bernsteinDerivative(pv)).lo;
    }
    const double det = Jm[0][0] * Jm[1][1] - Jm[0][1] * Jm[1][0];
    if (!(std::abs(det) > 0.0)) return false;
    const double Y[2][2] = {{Jm[1][1] / det, -Jm[0][1] / det}, {-Jm[1][0] / det, Jm[0][0] / det}};
    const Interval dx[2] = {U - u, V - v};
    const double m[2] = {u, v};
    Interval K[2];
    for (int i = 0; i < 2; ++i) {
        Interval k = pointInterval(m[i]) - (Y[i][0] * F[0] + Y[i][1] * F[1]);
        for (int j = 0; j < 2; ++j) {
            const Interval mij = (i == j ? 1.0 : 0.0) - (Y[i][0] * J[0][j] + Y[i][1] * J[1][j]);
            k = k + mij * dx[j];
        }
        K[i] = k;
    }
    const double lo = -tol::kPatchParamSlack, hi = 1.0 + tol::kPatchParamSlack;
    if (!(K[0].lo > U.lo && K[0].hi < U.hi && K[1].lo > V.lo && K[1].hi < V.hi)) return false;
    if (!(K[0].lo >= lo && K[0].hi <= hi && K[1].lo >= lo && K[1].hi <= hi)) return false;
    box = {U.lo, U.hi, V.lo, V.hi};
    return true;
}

bool inside(const Piece& p, const Box& b) {
    return p.u0 >= b.ul && p.u1 <= b.uh && p.v0 >= b.vl && p.v1 <= b.vh;
}

// A piece on an edge of the square: F (square: its coefficients on [0, 1]^2) evaluated over
// the piece widened by the slack on its outer sides must exclude zero too, so that a crossing just
// outside the edge, which the exact method counts, is never excluded with it.
bool excludesWidened(const Piece& p, const Coeffs square[2]) {
    const double s = tol::kPatchParamSlack;
    if (p.u0 > 0.0 && p.u1 < 1.0 && p.v0 > 0.0 && p.v1 < 1.0) return true;
    const Interval U{p.u0 == 0.0 ? -s : p.u0, p.u1 == 1.0 ? up(1.0 + s) : p.u1};
    const Interval V{p.v0 == 0.0 ? -s : p.v0, p.v1 == 1.0 ? up(1.0 + s) : p.v1};
    for (int k = 0; k < 2; ++k)
        if (!enclose(square[k], U, V).containsZero()) return true;
    return false;
}

}  // namespace

bool certifyCrossings(const BezierPatch& patch, const Vec3& o, const Vec3& d,
                      const PatchCrossings& found, int n, CertifyStats* stats) {
    CertifyStats local;
    CertifyStats& st = stats ? *stats : local;
    st = CertifyStats{};
    // Step 1: the Bernstein coefficients of F1, F2 on [0, 1]^2, enclosed; n_k = e_a x d.
    int axis = 0;
    for (int c = 1; c < 3; ++c)
        if (std::abs(d[c]) > std::abs(d[axis])) axis = c;
    Piece root;
    for (int k = 0, a = 0; a < 3; ++a) {
        if (a == axis) continue;
        Vec3 nk(0.0);
        nk[(a + 1) % 3] = -d[(a + 2) % 3];
        nk[(a + 2) % 3] = d[(a + 1) % 3];
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
                Interval s{0.0, 0.0};
                for (int c = 0; c < 3; ++c)
                    if (nk[c] != 0.0) s = s + nk[c] * (pointInterval(patch.at(i, j)[c]) - o[c]);
                root.f[k][i][j] = s;
            }
        ++k;
    }
    root.u0 = root.v0 = 0.0;
    root.u1 = root.v1 = 1.0;
    root.depth = 0;
    // Step 2: each listed crossing alone in its Krawczyk box; the boxes disjoint.
    std::array<Box, kMaxPatchCrossings> boxes;
    int boxCount = 0;
    for (int c = 0; c < n; ++c) {
        Box b;
        bool proved = false;
        for (double r : kRadii)
            if ((proved = krawczyk(root.f, found[c].u, found[c].v, r, b))) break;
        if (!proved) return false;
        for (int k = 0; k < boxCount; ++k) {
            const Box& other = boxes[k];
            if (b.ul <= other.uh && other.ul <= b.uh && b.vl <= other.vh && other.vl <= b.vh)
                return false;
        }
        boxes[boxCount++] = b;
    }
    st.rootsProved = true;
    // Step 3: no other zero in the square: every piece excluded or inside a box.
    // Depth first: each level leaves at most one piece waiting, so the stack holds at most
    // kMaxDepth + 1 (no heap: ~32 KB here).
    std::array<Piece, kMaxDepth + 2> stack;
    int top = 0;
    stack[top++] = root;
    while (top > 0) {
        const Piece p = stack[--top];
        ++st.pieces;
        bool covered = false;
        for (int k = 0; k < boxCount; ++k) covered = covered || inside(p, boxes[k]);
        if (covered) continue;
        if ((excludes(p.f[0]) || excludes(p.f[1])) && excludesWidened(p, root.f)) continue;
        if (p.depth >= kMaxDepth || st.pieces > kMaxPieces) return false;
        Piece a = p, b = p;
        a.depth = b.depth = p.depth + 1;
        if (p.u1 - p.u0 >= p.v1 - p.v0) {
            const double m = 0.5 * (p.u0 + p.u1);
            for (int k = 0; k < 2; ++k) splitU(p.f[k], a.f[k], b.f[k]);
            a.u1 = b.u0 = m;
        } else {
            const double m = 0.5 * (p.v0 + p.v1);
            for (int k = 0; k < 2; ++k) splitV(p.f[k], a.f[k], b.f[k]);
            a.v1 = b.v0 = m;
        }
        stack[top++] = b;
        stack[top++] = a;
    }
    return true;
}

}  // namespace csg
