#!/usr/bin/env python3
"""Plot bench/export_sweep.sh's CSV: triangles against distance to the exact part, log-log, one
polyline per exporter (csgray at T halving, Manifold at OpenSCAD's faceting made finer), each
point labelled with its seconds. Two panels per part: x = the larger one-sided distance (the
figure the issue asks for), and x = surface->mesh alone (a Euclidean distance to the nearest
triangle; mesh->surface is an upper bound along lines, loose where a line grazes a face, so it
can hide how close a mesh is).

    bench/export_sweep.sh PART.scad... > bench/reports/export_pareto.csv
    bench/export_pareto.py bench/reports/export_pareto.csv bench/reports/export_pareto.svg

Python's standard library only. The drawing follows the C++ plots of `csgray bench accuracy`
(viewer/cli/accuracy/AccuracyPlots.cpp: decade grid, 1eN labels, the same colours); those are
C++ over their own rows, so this is a small writer of the same look rather than a call into
them.
"""
import csv
import math
import sys

COLORS = {"csgray": "#1f77b4", "manifold": "#ff7f0e", "csgray-faceted": "#2ca02c"}
NAMES = {"csgray": "csgray, exact part, T halving",
         "manifold": "Manifold 3.5.4, OpenSCAD faceting made finer",
         "csgray-faceted": "csgray, Manifold's faceted input"}
CELL_W, CELL_H = 460, 430


def read(path, column):
    """{part: {exporter: [(distance, triangles, seconds, setting)]}} of the rows with figures,
    the distance from `column`."""
    series = {}
    with open(path) as f:
        rows = csv.DictReader(line for line in f if not line.startswith("#"))
        for r in rows:
            if not r[column] or not r["triangles"]:
                continue
            series.setdefault(r["part"], {}).setdefault(r["exporter"], []).append(
                (max(float(r[column]), 1e-9), int(r["triangles"]), float(r["seconds"]), r["setting"]))
    return series


def decades(values):
    lo = math.floor(math.log10(min(values)))
    hi = math.ceil(math.log10(max(values)))
    return lo, max(hi, lo + 1)


def panel(svg, x0, y0, part, lines, xtitle):
    w, h = CELL_W - 90, CELL_H - 130
    left, top = x0 + 60, y0 + 30
    xs = [p[0] for pts in lines.values() for p in pts]
    ys = [p[1] for pts in lines.values() for p in pts]
    xlo, xhi = decades(xs)
    ylo, yhi = decades(ys)

    def px(v):
        return left + w * (math.log10(v) - xlo) / (xhi - xlo)

    def py(v):
        return top + h - h * (math.log10(v) - ylo) / (yhi - ylo)

    svg.append(f"<rect x='{left}' y='{top}' width='{w}' height='{h}' fill='none' stroke='#444'/>")
    for t in range(xlo, xhi + 1):
        cx = px(10.0 ** t)
        svg.append(f"<line x1='{cx:.1f}' y1='{top}' x2='{cx:.1f}' y2='{top + h}' stroke='#ddd'/>")
        svg.append(f"<text x='{cx:.1f}' y='{top + h + 12}' font-size='9' "
                   f"text-anchor='middle'>1e{t}</text>")
    for t in range(ylo, yhi + 1):
        cy = py(10.0 ** t)
        svg.append(f"<line x1='{left}' y1='{cy:.1f}' x2='{left + w}' y2='{cy:.1f}' stroke='#ddd'/>")
        svg.append(f"<text x='{left - 3}' y='{cy + 3:.1f}' font-size='9' "
                   f"text-anchor='end'>1e{t}</text>")
    svg.append(f"<text x='{left + w / 2}' y='{top - 10}' font-size='12' font-weight='bold' "
               f"text-anchor='middle'>{part}</text>")
    svg.append(f"<text x='{left + w / 2}' y='{top + h + 26}' font-size='10' text-anchor='middle'>"
               f"{xtitle}</text>")
    svg.append(f"<text transform='translate({left - 38},{top + h / 2}) rotate(-90)' "
               "font-size='10' text-anchor='middle'>triangles</text>")
    for k, (exporter, pts) in enumerate(sorted(lines.items())):
        color = COLORS.get(exporter, "#2ca02c")
        coords = " ".join(f"{px(d):.1f},{py(t):.1f}" for d, t, _, _ in pts)
        svg.append(f"<polyline fill='none' stroke='{color}' stroke-width='1.5' points='{coords}'/>")
        for d, t, s, setting in pts:
            svg.append(f"<circle cx='{px(d):.1f}' cy='{py(t):.1f}' r='2.5' fill='{color}'>"
                       f"<title>{setting}: {t} triangles, {d:.3g}, {s:.3f} s</title></circle>")
            # Series k's labels sit k lines lower, so points the series share stay readable.
            svg.append(f"<text x='{px(d) + 4:.1f}' y='{py(t) - 4 + 9 * k:.1f}' font-size='8' "
                       f"fill='{color}'>{s:.3g} s</text>")
        ly = top + h + 42 + 14 * k  # the legend, under the axis title
        svg.append(f"<line x1='{left + 8}' y1='{ly}' x2='{left + 26}' y2='{ly}' stroke='{color}' "
                   "stroke-width='2'/>")
        svg.append(f"<text x='{left + 30}' y='{ly + 3}' font-size='10'>"
                   f"{NAMES.get(exporter, exporter)}</text>")


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: bench/export_pareto.py SWEEP.csv OUT.svg")
    metrics = [("distance", "max distance to the exact part, both ways (csgray compare)"),
               ("surface_to_mesh", "surface->mesh distance alone (csgray compare)")]
    parts = list(read(sys.argv[1], "distance"))
    width, height = CELL_W * max(1, len(parts)), CELL_H * len(metrics)
    svg = [f"<svg xmlns='http://www.w3.org/2000/svg' width='{width}' height='{height}' "
           "font-family='sans-serif'>", "<rect width='100%' height='100%' fill='white'/>"]
    for j, (column, title) in enumerate(metrics):
        series = read(sys.argv[1], column)
        for i, part in enumerate(parts):
            if part in series:
                panel(svg, i * CELL_W, j * CELL_H, part, series[part], title)
    svg.append("</svg>")
    with open(sys.argv[2], "w") as f:
        f.write("\n".join(svg) + "\n")


if __name__ == "__main__":
    main()
