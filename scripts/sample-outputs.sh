#!/usr/bin/env bash
# Writes every sample's and bench scene's outputs into OUTDIR with the given csgray binary: a
# 160x120 PNG, a 96x72 PFM with --aa 2, info JSON (and its stderr), two probes and a GLB
# (--max-cells 500000). A refactoring that promises "same outputs" is checked by running this
# before and after and comparing: diff -r BEFORE AFTER.
# Usage: scripts/sample-outputs.sh CSGRAY OUTDIR
set -u
[ $# -eq 2 ] || { echo "usage: $0 CSGRAY OUTDIR" >&2; exit 2; }
csgray=$(realpath "$1")
out=$(realpath -m "$2")
mkdir -p "$out"
cd "$(dirname "$0")/.."
for f in samples/*.scad bench/scenes/*.scad; do
    n=$(basename "$f" .scad)
    [[ $f == bench/* ]] && n=bench_$n  # bench/scenes/csg_grid.scad is not samples/csg_grid.scad
    "$csgray" render "$f" -o "$out/$n.png" --size 160x120 2>/dev/null
    "$csgray" render "$f" -o "$out/$n.pfm" --size 96x72 --aa 2 2>/dev/null
    "$csgray" info "$f" >"$out/$n.info.json" 2>"$out/$n.info.err"
    "$csgray" probe "$f" --origin 3,-4,2 --dir -3,4,-2 >"$out/$n.probe.json" 2>&1
    "$csgray" probe "$f" --origin -7,5,3 --dir 7,-5,-3 >>"$out/$n.probe.json" 2>&1
    timeout 120 "$csgray" export "$f" -o "$out/$n.glb" --max-cells 500000 2>/dev/null
done
