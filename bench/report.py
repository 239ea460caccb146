#!/usr/bin/env python3
"""Turn core_bench's JSON output into the Markdown tables of bench/README.md.

    core_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
               --benchmark_out=core.json --benchmark_out_format=json
    bench/report.py core.json

Only the median aggregate of each benchmark is reported: medians are what the README records,
because a shared machine's stray load inflates the mean.
"""
import json
import sys


def medians(path):
    with open(path) as f:
        data = json.load(f)
    rows = {}
    for b in data["benchmarks"]:
        if b.get("aggregate_name") == "median":
            rows[b["run_name"]] = b
        elif "aggregate_name" not in b:  # a run without repetitions
            rows.setdefault(b["run_name"], b)
    return data["context"], rows


def rate(x):
    return f"{x / 1e6:.2f} M" if x >= 1e6 else f"{x / 1e3:.0f} k"


def query_table(rows, scene):
    print("| benchmark | rays/s | ns/ray | visits/ray | prims/ray | hits or spans/ray |")
    print("|---|---:|---:|---:|---:|---:|")
    for query in ("closest", "spans"):
        for name, b in rows.items():
            parts = name.split("/")  # query/scene[/size]
            if parts[0] != query or parts[1] != scene:
                continue
            per_ray = b.get("hits/ray", b.get("spans/ray", 0.0))
            print(f"| `{name}` | {rate(b['items_per_second'])} | "
                  f"{1e9 / b['items_per_second']:.0f} | {b['visits/ray']:.2f} | "
                  f"{b['prims/ray']:.3f} | {per_ray:.3f} |")
    print()


def compile_table(rows):
    # CPU time of every thread (a large SAH build runs on several) and wall time.
    print("| benchmark | leaves | compile CPU time (ms) | compile wall time (ms) |")
    print("|---|---:|---:|---:|")
    for name, b in rows.items():
        if name.startswith("compile/"):
            assert b["time_unit"] == "ms"
            shown = name.removesuffix("/process_time")
            print(f"| `{shown}` | {b['leaves']:.0f} | {b['cpu_time']:.2f} | {b['real_time']:.2f} |")
    print()


def main():
    context, rows = medians(sys.argv[1])
    print(f"Run {context['date']} on {context['num_cpus']} CPUs at {context['mhz_per_cpu']} MHz, "
          f"load average {', '.join(f'{x:.2f}' for x in context.get('load_avg', []))}\n")
    for scene in ("sphere", "emblem_grid", "sphere_layer"):
        print(f"### {scene}\n")
        query_table(rows, scene)
    print("### compile\n")
    compile_table(rows)


if __name__ == "__main__":
    main()
