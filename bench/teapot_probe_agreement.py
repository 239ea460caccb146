#!/usr/bin/env python3
"""Do the ray/patch methods agree on the teapot? Random lines through its bounding box,
probed once per method with `csgray probe --rays`, compared ray by ray with the first method.

Rays: the origin is a uniform point on the sphere around the box (centre: the box centre,
radius: the box diagonal), so it lies outside the teapot and every crossing has t > 0; the
direction points at a uniform point of the box. Seeded, so a run repeats exactly.

  bench/teapot_probe_agreement.py --csgray build/viewer/csgray [--rays 20000] [--seed 1]
      [--methods clip,newton,resultant] [--threads 2]

Prints, per method after the first: rays whose crossing count differs from the first
method's, and over the rays with equal counts the largest |t - t_first| / max(1, |t_first|)
(t is a distance: the probe's directions are unit length).

With --max-differ N and --max-rel X (ctest's teapot_probe_agreement runs so) it exits 1 when a
method differs from the first on more than N rays or by more than X, or when the first method
finds no crossing at all (then there is nothing to agree on).
"""
import argparse
import json
import math
import random
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TEAPOT = ROOT / "samples" / "teapot.scad"


def teapot_box(csgray):
    info = subprocess.run([csgray, "info", str(TEAPOT)], check=True,
                          capture_output=True, text=True)
    bounds = json.loads(info.stdout)["bounds"]
    return bounds["min"], bounds["max"]


def random_rays(lo, hi, count, seed):
    rng = random.Random(seed)
    centre = [(a + b) / 2 for a, b in zip(lo, hi)]
    radius = math.dist(lo, hi)
    rays = []
    for _ in range(count):
        # A uniform direction (normalized Gaussian) puts the origin on the sphere.
        g = [rng.gauss(0.0, 1.0) for _ in range(3)]
        norm = math.sqrt(sum(x * x for x in g))
        origin = [c + radius * x / norm for c, x in zip(centre, g)]
        target = [rng.uniform(a, b) for a, b in zip(lo, hi)]
        rays.append(origin + [t - o for t, o in zip(target, origin)])
    return rays


def crossings(csgray, method, rays_file, threads):
    out = subprocess.run([csgray, "probe", str(TEAPOT), "-D", f'method="{method}"', "--rays",
                          str(rays_file), "--threads", str(threads)],
                         check=True, capture_output=True, text=True).stdout
    # The teapot is a surface: each crossing is a zero-length span [t, t].
    return [[span["in"]["t"] for span in json.loads(line)["spans"]]
            for line in out.splitlines()]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--csgray", default=str(ROOT / "build" / "viewer" / "csgray"))
    parser.add_argument("--rays", type=int, default=20000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--methods", default="clip,newton,resultant")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--max-differ", type=int, default=None)
    parser.add_argument("--max-rel", type=float, default=None)
    args = parser.parse_args()

    lo, hi = teapot_box(args.csgray)
    rays = random_rays(lo, hi, args.rays, args.seed)
    methods = args.methods.split(",")
    with tempfile.TemporaryDirectory() as tmp:
        rays_file = Path(tmp) / "rays.txt"
        rays_file.write_text("".join(" ".join(repr(x) for x in r) + "\n" for r in rays))
        results = {m: crossings(args.csgray, m, rays_file, args.threads) for m in methods}

    first = results[methods[0]]
    total = sum(len(c) for c in first)
    hit = sum(1 for c in first if c)
    print(f"{args.rays} rays (seed {args.seed}) through the teapot's box {lo} .. {hi}: "
          f"{methods[0]} finds {total} crossings on {hit} rays")
    failed = args.max_differ is not None and hit == 0
    for m in methods[1:]:
        other = results[m]
        if len(other) != len(first):
            sys.exit(f"{m}: {len(other)} result lines for {len(first)} rays")
        differ = sum(1 for a, b in zip(first, other) if len(a) != len(b))
        worst = 0.0
        for a, b in zip(first, other):
            if len(a) == len(b):
                for ta, tb in zip(a, b):
                    worst = max(worst, abs(tb - ta) / max(1.0, abs(ta)))
        print(f"{m}: crossing count differs from {methods[0]} on {differ} rays; "
              f"max relative t difference {worst:.2g} on the others")
        if args.max_differ is not None and differ > args.max_differ:
            failed = True
        if args.max_rel is not None and worst > args.max_rel:
            failed = True
    if failed:
        sys.exit("teapot_probe_agreement: the methods disagree beyond the bounds given")


if __name__ == "__main__":
    main()
