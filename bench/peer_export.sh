#!/usr/bin/env bash
# Peer comparison of mesh export: Manifold (npm `manifold-3d`, OpenSCAD's current CSG engine,
# WebAssembly, one thread) against csgray on the same parts, in one run, and OpenSCAD 2021
# (CGAL) when asked. Both meshes are measured by `csgray compare` against the part.
#
# What Manifold gets depends on the part's leaves (bench/csg_to_manifold):
# - all polyhedra (cubes, polyhedron(), and cylinders or spheres with $fn, which csgray facets
#   as OpenSCAD does): the leaves vertex for vertex, so both mesh the same polyhedron, and csgray
#   runs its default export.
# - exact curves (a sphere or cylinder under $fa/$fs): OpenSCAD's own faceting of the .scad
#   (--curves openscad), which is what an OpenSCAD user gets from Manifold. Both meshes are
#   measured against the exact part, and csgray exports the exact part with --tolerance T, T the
#   larger of Manifold's two measured distances: the row says what csgray needs for Manifold's
#   accuracy.
# - anything else (Bezier patches, surface(), extrusions, a 2-D top level, no solid): one line
#   "n/a: why", and the run goes on.
# Prints, per part and exporter: the median wall time and CPU time (user + sys) of RUNS runs,
# triangles, both one-sided distances, the volume and whether the mesh is closed; then one line
# with the ratios and what csgray wins, and at the end how many parts csgray wins on all of time,
# triangles and both distances.
#
#   bench/peer_export.sh [RUNS] [PART.scad ...]     defaults: 3, ../shared/peers/csg_grid3.scad
#   OPENSCAD=1 bench/peer_export.sh ...             adds OpenSCAD 2021 (one run: minutes)
#   MARKDOWN=FILE bench/peer_export.sh ...          also writes the table to FILE in Markdown,
#                                                   one row per part (bench/README.md)
#   TIMEOUT=S                                       seconds per command (default 300)
#
# Manifold is installed by this script into build/bench/manifold (npm, the registry's
# `manifold-3d` at the version in bench/manifold/package.json). Needs a built csgray and
# csg_to_manifold (CSGRAY=path, default build/viewer/csgray). Not a timed test: run it on an
# idle machine and look at `uptime` first. Manifold's time counts from its first leaf to its
# final mesh (hulls, booleans and getMesh: it evaluates lazily; not node's start, not reading
# the .scad); csgray's is the whole command (reading the part, the mesh and the file), and its
# own summary's meshing seconds (0.01 s steps) are printed beside it.
set -euo pipefail

# shellcheck source=bench/peer_lib.sh
. "$(dirname "$0")/peer_lib.sh"

runs="${1:-3}"
shift || true
parts=("$@")
[ ${#parts[@]} -gt 0 ] || parts=("$peers/csg_grid3.scad")
md="${MARKDOWN:-}"

echo "$(date -u '+%F %T UTC')  $(uptime)"
echo "commit $(git -C "$root" rev-parse --short HEAD)$(git -C "$root" diff --quiet HEAD -- . || echo ' (+ changes)')   runs $runs   $(nproc) cores   limit ${limit} s per command"

# A part's name: samples/x.scad -> x, an OpenSCAD example Dir/x.scad -> Dir/x.
label() {
    case "$1" in
    */examples/*/*.scad) echo "$(basename "$(dirname "$1")")/$(basename "$1" .scad)" ;;
    *) basename "$1" .scad ;;
    esac
}

row() { printf "%-26s %-10s %-9s %8s %8s %9s %12s %12s %12s %6s\n" "$@"; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { if (b > 0) printf "%.2f", a / b; else print "-" }'; }

row part leaves exporter wall cpu triangles mesh→surface surface→mesh volume closed
if [ -n "$md" ]; then
    echo "| part | leaves | Manifold wall | csgray wall (meshing) | csgray / Manifold | Manifold triangles | csgray triangles | csgray / Manifold | Manifold mesh→surface, surface→mesh | csgray mesh→surface, surface→mesh | csgray mesher | csgray wins |"
    echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---|"
fi >"${md:-/dev/null}"

# n/a PART WHY: the part has no row.
na() {
    echo "$1: n/a: $2"
    [ -z "$md" ] || echo "| $1 | n/a: $2 | | | | | | | | | | |" >>"$md"
    skipped=$((skipped + 1))
}

measured=0 wins=0 skipped=0 failed=0
for part in "${parts[@]}"; do
    name="$(label "$part")"
    kind=polyhedral
    if ! dump "$part"; then
        case "$why" in
        *"has curved faces"* | *"is a twisted linear_extrude"*)
            kind=curved
            dump "$part" --curves openscad || { na "$name" "under --curves openscad, $why"; continue; } ;;
        *) na "$name" "$why"; continue ;;
        esac
    fi
    # One Manifold run first, untimed: its mesh sets csgray's tolerance on a curved part.
    : >"$work/mseconds"
    if ! manifold_run || ! read -r mt mto mfrom mvol tol mclosed \
        <<<"$(measure "$part" "$work/manifold.stl" || echo "$why" >"$work/why")"; then
        na "$name" "Manifold: $why"
        continue
    fi
    if [ -z "$mclosed" ]; then
        case "$(cat "$work/why")" in
        *"not a 3-D object"*) na "$name" "a 2-D top level (no solid to mesh)" ;;
        *) na "$name" "Manifold: $(cat "$work/why")" ;;
        esac
        continue
    fi
    if [ "$mt" = 0 ]; then
        na "$name" "no solid (Manifold's mesh is empty)"
        continue
    fi
    # Below a thousandth of compare's default tolerance (2e-6 of the diagonal) a distance is the
    # float rounding of the mesh file: such distances count as equal.
    floor="$(awk -v t="$tol" 'BEGIN { printf "%.3g", t / 1000 }')"
    options=()
    note="default export"
    if [ "$kind" = curved ]; then
        target="$(awk -v a="$mto" -v b="$mfrom" -v f="$floor" 'BEGIN { t = a > b ? a : b; if (t < f) t = f; printf "%.3g", t }')"
        options=(--tolerance "$target")
        note="T = $target: Manifold's larger distance"
    fi
    : >"$work/mseconds"
    : >"$work/times"
    : >"$work/cmesh"
    ok=1
    for _ in $(seq "$runs"); do
        manifold_run || { ok=0; why="Manifold: $why"; break; }
        timed "$csgray" export "$part" -o "$work/csgray.glb" "${options[@]}" ||
            { ok=0; why="csgray: $why"; break; }
        # Its summary line: the meshing's own seconds (reading and writing left out, like
        # Manifold's timer) and which mesher made it.
        summary="$(grep '^csgray: export: ' "$work/log" | tail -n 1)"
        sed -E 's/.*, ([0-9.]+) s$/\1/' <<<"$summary" >>"$work/cmesh"
    done
    if [ "$ok" = 0 ]; then
        failed=$((failed + 1))
        na "$name" "$why"
        continue
    fi
    mwall="$(median <"$work/mseconds")"
    cwall="$(awk '{ print $1 }' "$work/times" | median)"
    ccpu="$(awk '{ print $2 }' "$work/times" | median)"
    cmesh="$(median <"$work/cmesh")"
    case "$summary" in
    *"faceted within"*) how="$(sed -E 's/.*(faceted within [0-9.e+-]+).*/exact boundary of its curves \1/' <<<"$summary")" ;;
    *"exact polyhedral boundary"*) how="exact boundary" ;;
    *"grid"*) how="grid" ;;
    *) how="?" ;;
    esac
    if ! read -r ct cto cfrom cvol _ cclosed <<<"$(measure "$part" "$work/csgray.glb" ||
        echo "$why" >"$work/why")" || [ -z "$cclosed" ]; then
        failed=$((failed + 1))
        na "$name" "csgray: $(cat "$work/why")"
        continue
    fi
    measured=$((measured + 1))
    # What csgray wins: time strictly, triangles and each distance when not worse.
    verdict="$(awk -v cw="$cwall" -v mw="$mwall" -v ct="$ct" -v mt="$mt" -v cto="$cto" \
        -v mto="$mto" -v cf="$cfrom" -v mf="$mfrom" -v f="$floor" -v cc="$cclosed" 'BEGIN {
        d1 = (cto <= mto || cto <= f); d2 = (cf <= mf || cf <= f)
        lost = ""
        if (!(cw < mw)) lost = lost " time"
        if (!(ct <= mt)) lost = lost " triangles"
        if (!d1) lost = lost " mesh->surface"
        if (!d2) lost = lost " surface->mesh"
        if (cc != "yes") lost = lost " closed"
        print lost == "" ? "all" : "loses on" lost }')"
    [ "$verdict" != all ] || wins=$((wins + 1))
    [ -z "$md" ] || echo "| $name | $kind | $mwall s | $cwall s ($cmesh s) | $(ratio "$cwall" "$mwall") | $mt | $ct | $(ratio "$ct" "$mt") | $mto, $mfrom | $cto, $cfrom | $how$([ "$kind" = curved ] && echo ", T = $target") | $verdict$([ "$cclosed" = yes ] || echo ' (csgray mesh not closed)')$([ "$mclosed" = yes ] || echo ' (Manifold mesh not closed)') |" >>"$md"
    row "$name" "$kind" manifold "$mwall" "$mwall" "$mt" "$mto" "$mfrom" "$mvol" "$mclosed"
    row "$name" "$kind" csgray "$cwall" "$ccpu" "$ct" "$cto" "$cfrom" "$cvol" "$cclosed"
    echo "$name: csgray / Manifold: wall $(ratio "$cwall" "$mwall"), triangles $(ratio "$ct" "$mt"); csgray's meshing $cmesh s by its own timer, $how; $note; csgray wins: $verdict"
    if [ -n "${OPENSCAD:-}" ]; then
        : >"$work/times"
        if timed openscad -o "$work/openscad.stl" "$part" &&
            read -r ot oto ofrom ovol _ oclosed <<<"$(measure "$part" "$work/openscad.stl")"; then
            read -r ow oc <"$work/times"
            row "$name" "$kind" openscad "$ow" "$oc" "$ot" "$oto" "$ofrom" "$ovol" "$oclosed"
            echo "$name: OpenSCAD wall / csgray = $(ratio "$ow" "$cwall")"
        else
            echo "$name: openscad: $why"
        fi
    fi
done
summary="csgray wins on all of time, triangles and both distances on $wins of $measured parts measured; $skipped n/a (of which $failed an exporter failed or timed out)"
echo "$summary"
echo "end $(date -u '+%F %T UTC')  $(uptime)" # the load over the run: the other end of it
[ -z "$md" ] || printf "\n%s\n" "$summary" >>"$md"
