#!/usr/bin/env bash
# Debian's OpenSCAD examples against OpenSCAD 2021 itself, all of them (tests/examples_test.cpp
# skips the ones OpenSCAD is slow on). Per example: whether csgray loads it; OpenSCAD's STL
# export time and csgray's compare of it under --curves openscad (max surface->mesh, mean
# mesh->surface, volume ratio); and the time to render an 800x600 PNG, csgray against
# `openscad --render`.
# Usage: scripts/compare-examples.sh [BUILD_DIR] [EXAMPLE.scad ...]  (default: all 48)
set -uo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
shift || true
csgray="$build/viewer/csgray"
examples=("$@")
[ ${#examples[@]} -gt 0 ] || examples=(/usr/share/openscad/examples/*/*.scad)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

seconds() { local s=$EPOCHREALTIME; "$@" >/dev/null 2>&1; local rc=$?; echo "$rc $(echo "$EPOCHREALTIME - $s" | bc)"; }

printf '%-34s %5s %9s %10s %10s %9s %9s %9s\n' example loads "oscad-stl" "s->m max" "m->s mean" "vol" \
    "oscad-png" "csg-png"
for f in "${examples[@]}"; do
    name=$(basename "$(dirname "$f")")/$(basename "$f")
    if ! "$csgray" info "$f" --curves openscad >/dev/null 2>&1; then
        printf '%-34s %5s\n' "$name" no
        continue
    fi
    read -r rc t_stl < <(seconds timeout 600 openscad --export-format binstl -o "$out/x.stl" "$f")
    figures="-          -          -"
    if [ "$rc" = 0 ] && [ -s "$out/x.stl" ]; then
        figures=$("$csgray" compare "$f" "$out/x.stl" --json --curves openscad 2>/dev/null | python3 -c '
import json, sys
j = json.load(sys.stdin)
print("%.3g %.3g %.6f" % (j["surfaceToMesh"]["max"] or float("inf"), j["meshToSurface"]["mean"],
                          j["volume"]["part"] / j["volume"]["mesh"]))' 2>/dev/null || echo "? ? ?")
    fi
    read -r _ t_opng < <(seconds timeout 600 openscad --render --imgsize=800,600 -o "$out/o.png" "$f")
    read -r _ t_cpng < <(seconds "$csgray" render "$f" -o "$out/c.png" --size 800x600)
    # shellcheck disable=SC2086
    printf '%-34s %5s %9.2f %10s %10s %9s %9.2f %9.2f\n' "$name" yes "$t_stl" $figures "$t_opng" "$t_cpng"
    rm -f "$out/x.stl" "$out/o.png" "$out/c.png"
done
