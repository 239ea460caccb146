#!/usr/bin/env python3
"""The smoke pass of a Google Benchmark program (bench/CMakeLists.txt): runs the benchmarks
FILTER matches once, briefly, and fails unless exactly COUNT of them ran and none reported an
error. The program's exit status alone proves nothing: it exits 0 when the filter matches
nothing and when a benchmark calls SkipWithError (a query that found no hit, a scene that did
not load).

  bench/benchmark_smoke.py EXE FILTER COUNT
"""
import json
import subprocess
import sys
import tempfile


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    exe, pattern, count = sys.argv[1], sys.argv[2], int(sys.argv[3])
    with tempfile.NamedTemporaryFile(suffix=".json") as out:
        subprocess.run([exe, "--benchmark_min_time=0.001", f"--benchmark_filter={pattern}",
                        f"--benchmark_out={out.name}", "--benchmark_out_format=json"],
                       check=True, stdout=subprocess.DEVNULL)
        text = open(out.name).read()
    if not text.strip():
        sys.exit(f"no benchmark ran: {pattern} matched nothing")
    runs = json.loads(text)["benchmarks"]
    names = [r["name"] for r in runs]
    errors = [r["name"] + ": " + r.get("error_message", "") for r in runs
              if r.get("error_occurred")]
    print(f"{len(runs)} benchmarks ran: {' '.join(names)}")
    if errors:
        sys.exit("benchmarks that reported an error: " + "; ".join(errors))
    if len(runs) != count:
        sys.exit(f"expected {count} benchmarks to run, {len(runs)} did")


if __name__ == "__main__":
    main()
