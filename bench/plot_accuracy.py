#!/usr/bin/python3
"""Plots of accuracy_report's DIR/accuracy.csv (matplotlib from Debian: python3-matplotlib).

    bench/plot_accuracy.py bench/reports     writes accuracy_pareto.png, degree_sweep.png

accuracy_pareto.png: per surface class, time per ray (solve() only) against the 99th
percentile error, one line per solver through its tolerance settings; the black steps are the
Pareto front (nothing is both faster and more accurate); a cross marks a setting with wrong
root counts. degree_sweep.png: rays per second and max error against degree, per solver.
Debian's /usr/bin/python3 is used on purpose: matplotlib is installed there by apt, not in a
pyenv or virtualenv interpreter.
"""
import csv
import os
import subprocess
import sys

try:
    import matplotlib
except ImportError:  # install the Debian package once, as scripts/install-deps.sh would
    sudo = [] if os.geteuid() == 0 else ["sudo"]
    subprocess.run(sudo + ["apt-get", "install", "-y", "python3-matplotlib"], check=True)
    import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

FLOOR = 1e-17  # errors of exactly 0 drawn here, so a log axis can show them


def load(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def label(row):
    return row["class"] if row["class"] == "degree-sweep" else f"{row['class']} {row['degree']}" \
        if row["class"] == "shells" else row["class"]


def pareto(points):
    """The points (time, error) no other point beats in both; sorted by time."""
    front, best = [], float("inf")
    for t, e in sorted(points):
        if e < best:
            front.append((t, e))
            best = e
    return front


def plot_classes(rows, out):
    classes = []
    for r in rows:
        if r["class"] != "degree-sweep" and label(r) not in classes:
            classes.append(label(r))
    solvers = sorted({r["solver"] for r in rows})
    colors = {s: plt.cm.tab10(i) for i, s in enumerate(solvers)}
    cols = 4
    fig, axes = plt.subplots((len(classes) + cols - 1) // cols, cols, figsize=(16, 7.5),
                             squeeze=False)
    for ax, cls in zip(axes.flat, classes):
        mine = [r for r in rows if label(r) == cls]
        points = []
        for s in solvers:
            # In tolerance order (coarse to fine, 0 = full double last): timings are noisy,
            # so sorting by time would zigzag.
            tol = [r for r in mine if r["solver"] == s]
            tol.sort(key=lambda r: -float(r["rel_tol"]) if float(r["rel_tol"]) else 1.0)
            pts = [(1e9 / float(r["rays_per_second"]), max(FLOOR, float(r["p99_error"])),
                    int(r["wrong_counts"])) for r in tol]
            if not pts:
                continue
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", ms=3, lw=1,
                    color=colors[s], label=s)
            for t, e, wrong in pts:
                if wrong:
                    ax.plot(t, e, "x", ms=9, color=colors[s])
                else:
                    points.append((t, e))
        front = pareto(points)
        if front:
            ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="black",
                    lw=1.5, alpha=0.6)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(cls)
        ax.set_xlabel("ns per ray (solve only)")
        ax.set_ylabel("p99 relative error")
        ax.grid(True, which="major", alpha=0.3)
    for ax in list(axes.flat)[len(classes):]:
        ax.axis("off")
    handles, names = axes.flat[0].get_legend_handles_labels()
    fig.legend(handles, names, loc="lower right", ncol=2, fontsize=9,
               title="x = wrong root counts; black = Pareto front")
    fig.tight_layout()
    fig.savefig(out, dpi=60)


def plot_degrees(rows, out):
    sweep = [r for r in rows if r["class"] == "degree-sweep"]
    solvers = sorted({r["solver"] for r in sweep})
    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.5))
    for i, s in enumerate(solvers):
        pts = sorted((int(r["degree"]), float(r["rays_per_second"]),
                      max(FLOOR, float(r["max_error"])))
                     for r in sweep if r["solver"] == s)
        a.plot([p[0] for p in pts], [p[1] for p in pts], "o-", ms=3, color=plt.cm.tab10(i),
               label=s)
        b.plot([p[0] for p in pts], [p[2] for p in pts], "o-", ms=3, color=plt.cm.tab10(i),
               label=s)
    a.set_yscale("log")
    a.set_xlabel("degree")
    a.set_ylabel("rays per second")
    a.set_title("speed, roots to double precision")
    b.set_yscale("log")
    b.set_xlabel("degree")
    b.set_ylabel("max relative error")
    b.set_title("error vs the 50-digit roots of the same polynomial")
    for ax in (a, b):
        ax.grid(True, alpha=0.3)
    a.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=60)


def main():
    directory = sys.argv[1] if len(sys.argv) > 1 else "accuracy"
    rows = load(os.path.join(directory, "accuracy.csv"))
    plot_classes(rows, os.path.join(directory, "accuracy_pareto.png"))
    plot_degrees(rows, os.path.join(directory, "degree_sweep.png"))
    print(f"wrote {directory}/accuracy_pareto.png and {directory}/degree_sweep.png")


if __name__ == "__main__":
    main()
