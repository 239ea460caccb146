#!/usr/bin/env python3
"""Launch-to-first-frame of `csgray view` (issue 8): how long a person waits for the window's
first coarse picture.

Starts its own Xvfb, launches the viewer RUNS times on PART and, for each launch, takes the
wall-clock time just before the process is spawned and the wall-clock time the viewer prints
when it has presented its first frame ("view: first frame (...) presented at S s"). Both are
CLOCK_REALTIME on the same machine, so the difference covers everything: fork and exec,
dynamic loading, SDL start-up, window and renderer creation, part evaluation, the first
refinement level and its presentation. Prints each launch, the viewer's own phase times
(--verbose) of the median launch, and the median.

    bench/view_startup.py [PART] [RUNS] [SIZE]   defaults: samples/csg_grid.scad, 9, 800x600

Needs a built csgray (CSGRAY=path, default build/viewer/csgray) and Xvfb. Not a timed test:
the figure depends on the machine's load, so it prints `uptime` first.
"""
import os
import re
import signal
import statistics
import subprocess
import sys
import tempfile
import time

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
part = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "samples", "csg_grid.scad")
runs = int(sys.argv[2]) if len(sys.argv) > 2 else 9
size = sys.argv[3] if len(sys.argv) > 3 else "800x600"
csgray = os.environ.get("CSGRAY", os.path.join(root, "build", "viewer", "csgray"))
if not os.access(csgray, os.X_OK):
    sys.exit(f"no csgray at {csgray} (build it, or set CSGRAY)")


def start_xvfb():
    for n in range(120, 220):
        if os.path.exists(f"/tmp/.X11-unix/X{n}") or os.path.exists(f"/tmp/.X{n}-lock"):
            continue
        xvfb = subprocess.Popen(["Xvfb", f":{n}", "-screen", "0", "1024x768x24", "-nolisten",
                                 "tcp"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        for _ in range(250):
            if os.path.exists(f"/tmp/.X11-unix/X{n}"):
                return xvfb, f":{n}"
            time.sleep(0.02)
        xvfb.kill()
        xvfb.wait()
    sys.exit("no Xvfb server could be started")


def launch(display, workdir):
    env = dict(os.environ, DISPLAY=display)
    err_path = os.path.join(workdir, "stderr.txt")
    with open(err_path, "w") as err:
        t0 = time.time()
        view = subprocess.Popen([csgray, "view", part, "--size", size, "--verbose"], env=env,
                                stdout=subprocess.DEVNULL, stderr=err)
        presented = None
        deadline = time.monotonic() + 20.0
        while presented is None and time.monotonic() < deadline and view.poll() is None:
            time.sleep(0.01)
            with open(err_path) as f:
                m = re.search(r"view: first frame .* presented at ([0-9.]+) s", f.read())
            if m:
                presented = float(m.group(1))
        view.send_signal(signal.SIGTERM)
        try:
            view.wait(5)
        except subprocess.TimeoutExpired:
            view.kill()
            view.wait()
    with open(err_path) as f:
        text = f.read()
    if presented is None:
        sys.exit("the viewer showed no frame:\n" + text)
    return (presented - t0) * 1e3, text


print(f"load: {os.getloadavg()[0]:.2f} {os.getloadavg()[1]:.2f} {os.getloadavg()[2]:.2f}   "
      f"part {os.path.relpath(part, root)}   size {size}   runs {runs}")
xvfb, display = start_xvfb()
try:
    with tempfile.TemporaryDirectory() as workdir:
        results = []
        for i in range(runs):
            ms, text = launch(display, workdir)
            results.append((ms, text))
            print(f"launch {i + 1}: first frame presented {ms:.1f} ms after spawn")
        results.sort(key=lambda r: r[0])
        median_ms, median_text = results[len(results) // 2]
        print("phases of the median launch (the viewer's --verbose lines):")
        for line in median_text.splitlines():
            if line.startswith("view: startup") or line.startswith("view: first frame"):
                print("  " + line)
        print(f"median launch -> first frame presented: {statistics.median(r[0] for r in results):.1f} ms"
              f" (min {results[0][0]:.1f}, max {results[-1][0]:.1f})")
finally:
    xvfb.terminate()
    xvfb.wait()
