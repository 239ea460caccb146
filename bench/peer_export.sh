#!/usr/bin/env bash
# Peer comparison of mesh export: Manifold (npm `manifold-3d`, OpenSCAD's current CSG engine,
# WebAssembly, one thread) against csgray on the same parts, in one run, and OpenSCAD 2021
# (CGAL) when asked. Manifold gets each part's leaves vertex for vertex as csgray has them
# (bench/csg_to_manifold: convex leaves as hulls of their vertices, meshes as meshes), so both
# mesh the same polyhedron. Both meshes are then measured by `csgray compare` against the part.
# Prints, per part and exporter: the median wall time and CPU time (user + sys) of RUNS runs,
# triangles, both one-sided distances and the volume.
#
#   bench/peer_export.sh [RUNS] [PART.scad ...]     defaults: 3, ../shared/peers/csg_grid3.scad
#   OPENSCAD=1 bench/peer_export.sh ...             adds OpenSCAD 2021 (one run: minutes)
#
# Manifold is installed by this script into build/bench/manifold (npm, the registry's
# `manifold-3d` at the version in bench/manifold/package.json). Needs a built csgray and
# csg_to_manifold (CSGRAY=path, default build/viewer/csgray). Not a timed test: run it on an
# idle machine and look at `uptime` first. Manifold's time counts from its first leaf to its
# final mesh (hulls, booleans and getMesh: it evaluates lazily); csgray's is the whole command
# (reading the part, the mesh, its own two-sided check and the file).
set -euo pipefail

here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
peers="${PEERS:-$root/../shared/peers}"
[ -d "$peers" ] || peers=/work/shared/peers
runs="${1:-3}"
shift || true
parts=("$@")
[ ${#parts[@]} -gt 0 ] || parts=("$peers/csg_grid3.scad")
csgray="${CSGRAY:-$root/build/viewer/csgray}"
dumper="$(dirname "$(dirname "$csgray")")/bench/csg_to_manifold"
[ -x "$csgray" ] || { echo "no csgray at $csgray (build it, or set CSGRAY)" >&2; exit 1; }
[ -x "$dumper" ] || { echo "no csg_to_manifold at $dumper (build it)" >&2; exit 1; }

manifold="$(dirname "$(dirname "$csgray")")/bench/manifold"
if [ ! -d "$manifold/node_modules/manifold-3d" ]; then
    mkdir -p "$manifold"
    cp "$here/manifold/package.json" "$manifold/"
    (cd "$manifold" && npm install --no-audit --no-fund --loglevel=error >/dev/null)
fi
cp "$here/manifold/export.mjs" "$manifold/"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

echo "load: $(uptime | sed 's/.*load average: //')   runs $runs   $(nproc) cores"

median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }

# Runs a command, appends "wall cpu" to $work/times.
timed() {
    /usr/bin/time -f "%e %U %S" -o "$work/time" "$@" >"$work/log" 2>&1 ||
        { cat "$work/log" >&2; return 1; }
    awk '{ printf "%.3f %.3f\n", $1, $2 + $3 }' "$work/time" >>"$work/times"
}

# "triangles mesh->surface surface->mesh volume" of a mesh file against the part.
measure() {
    "$csgray" compare "$1" "$2" --json >"$work/compare.json" 2>/dev/null || true
    python3 - "$work/compare.json" <<'EOF'
import json, sys
j = json.load(open(sys.argv[1]))
print(j["triangles"], "%.3g" % j["meshToSurface"]["max"], "%.3g" % j["surfaceToMesh"]["max"],
      "%.7g" % j["volume"]["mesh"])
EOF
}

printf "%-14s %-10s %8s %8s %10s %12s %12s %12s\n" part exporter wall cpu triangles \
    mesh→surface surface→mesh volume
for part in "${parts[@]}"; do
    name="$(basename "$part" .scad)"
    "$dumper" "$part" >"$work/tree.json"
    : >"$work/times"
    for _ in $(seq "$runs"); do
        node "$manifold/export.mjs" "$work/tree.json" "$work/manifold.stl" >"$work/m.json"
        python3 -c "import json; print('%.3f' % json.load(open('$work/m.json'))['seconds'])" \
            >>"$work/mseconds"
        timed "$csgray" export "$part" -o "$work/csgray.glb" --quiet
    done
    mwall="$(median <"$work/mseconds")"
    cwall="$(awk '{ print $1 }' "$work/times" | median)"
    ccpu="$(awk '{ print $2 }' "$work/times" | median)"
    read -r mt mto mfrom mvol <<<"$(measure "$part" "$work/manifold.stl")"
    read -r ct cto cfrom cvol <<<"$(measure "$part" "$work/csgray.glb")"
    printf "%-14s %-10s %8s %8s %10s %12s %12s %12s\n" "$name" manifold "$mwall" "$mwall" "$mt" \
        "$mto" "$mfrom" "$mvol"
    printf "%-14s %-10s %8s %8s %10s %12s %12s %12s\n" "$name" csgray "$cwall" "$ccpu" "$ct" \
        "$cto" "$cfrom" "$cvol"
    echo "$name: csgray wall / Manifold = $(awk -v c="$cwall" -v m="$mwall" 'BEGIN { printf "%.2f", c / m }')"
    if [ -n "${OPENSCAD:-}" ]; then
        : >"$work/times"
        timed openscad -o "$work/openscad.stl" "$part"
        read -r ow oc <"$work/times"
        read -r ot oto ofrom ovol <<<"$(measure "$part" "$work/openscad.stl")"
        printf "%-14s %-10s %8s %8s %10s %12s %12s %12s\n" "$name" openscad "$ow" "$oc" "$ot" \
            "$oto" "$ofrom" "$ovol"
        echo "$name: OpenSCAD wall / csgray = $(awk -v c="$cwall" -v o="$ow" 'BEGIN { printf "%.1f", o / c }')"
    fi
    rm -f "$work/mseconds"
done
