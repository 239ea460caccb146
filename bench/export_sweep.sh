#!/usr/bin/env bash
# Triangles against distance for both mesh exporters, as a CSV for bench/export_pareto.py: each
# part exported by csgray at a tolerance T halved step by step, and by Manifold (npm
# `manifold-3d`, as in bench/peer_export.sh) at OpenSCAD's faceting made finer step by step.
# Every mesh is measured by `csgray compare` against the exact part, so x (the larger one-sided
# distance) is what each mesh costs in accuracy, whatever its exporter aimed at. A third series,
# csgray-faceted, is csgray's export of Manifold's input (the same faceting).
#
#   bench/export_sweep.sh PART.scad... > sweep.csv
#   STEPS=N (default 6)   settings per exporter
#   RUNS=N (default 1)    runs per setting (the median time is kept)
#   FROM=T                csgray's first tolerance (default: 1/50 of the part's diagonal)
#   FN0=N (default 16)    Manifold's first $fn on a part with $fn set
#
# Which faceting, by the part's leaves (bench/csg_to_manifold, default curves):
# - all polyhedra under $fn (e.g. csg_grid3's `$fn = 64`): the exact part is --curves exact;
#   Manifold gets $fn = FN0, 2 FN0, ... (-D, which overrides the file's top-level $fn), csgray
#   the exact part (--curves exact) at T.
# - exact curves ($fa/$fs, OpenSCAD's defaults 12 and 2): the exact part is the part; Manifold
#   gets --curves openscad with $fa and $fs halved from 12 and 2, csgray the part at T.
# Columns: part, exporter (manifold, csgray-faceted, csgray), setting, seconds (Manifold: first leaf to mesh; csgray: the whole
# command), triangles, mesh_to_surface, surface_to_mesh, distance (the larger), closed. A
# setting that fails or times out (TIMEOUT, default 300 s) is a row with its reason.
set -euo pipefail

# shellcheck source=bench/peer_lib.sh
. "$(dirname "$0")/peer_lib.sh"

steps="${STEPS:-6}"
runs="${RUNS:-1}"
fn0="${FN0:-16}"
[ $# -gt 0 ] || { echo "usage: bench/export_sweep.sh PART.scad... > sweep.csv" >&2; exit 2; }

echo "# $(date -u '+%F %T UTC'), commit $(git -C "$root" rev-parse --short HEAD), load $(uptime | sed 's/.*load average: //' | tr ',' ' ')"
echo "part,exporter,setting,seconds,triangles,mesh_to_surface,surface_to_mesh,distance,closed"

# row NAME EXPORTER SETTING SECONDS MESH: measures the mesh against the exact part and prints
# the CSV row (or the reason there is none).
row() {
    local r
    if r="$(measure "$part" "$5" "${exact[@]}")"; then
        read -r t to from _ tol closed <<<"$r"
        echo "$1,$2,$3,$4,$t,$to,$from,$(awk -v a="$to" -v b="$from" 'BEGIN { print (a > b ? a : b) }'),$closed"
    else
        echo "$1,$2,$3,,,,,,compare failed"
    fi
}

for part in "$@"; do
    name="$(basename "$part" .scad)"
    if dump "$part"; then
        exact=(--curves exact)
        mine=(--curves exact)
        facet() { echo "-D \$fn=$((fn0 << $1))"; }
    elif [[ "$why" == *"has curved faces"* ]]; then
        exact=()
        mine=()
        facet() {
            echo "--curves openscad -D \$fa=$(awk -v k="$1" 'BEGIN { print 12 / 2 ^ k }')" \
                "-D \$fs=$(awk -v k="$1" 'BEGIN { print 2 / 2 ^ k }')"
        }
    else
        echo "$name,n/a,,,,,,,${why//,/;}"
        continue
    fi
    for k in $(seq 0 $((steps - 1))); do
        read -ra options <<<"$(facet "$k")"
        setting="$(echo "${options[*]}" | sed 's/--curves openscad //; s/-D //g')"
        echo "$name: Manifold $setting" >&2
        if ! dump "$part" "${options[@]}"; then
            echo "$name,manifold,$setting,,,,,,${why//,/;}"
            continue
        fi
        : >"$work/mseconds"
        ok=1
        for _ in $(seq "$runs"); do manifold_run || { ok=0; break; }; done
        if [ "$ok" = 0 ]; then
            echo "$name,manifold,$setting,,,,,,${why//,/;}"
            continue
        fi
        row "$name" manifold "$setting" "$(median <"$work/mseconds")" "$work/manifold.stl"
        # csgray on the very input Manifold had (its exact boundary of the same facets): how the
        # two exporters compare when neither chooses the faceting.
        echo "$name: csgray $setting" >&2
        : >"$work/times"
        ok=1
        for _ in $(seq "$runs"); do
            timed "$csgray" export "$part" -o "$work/csgray.glb" --quiet "${options[@]}" ||
                { ok=0; break; }
        done
        if [ "$ok" = 0 ]; then
            echo "$name,csgray-faceted,$setting,,,,,,${why//,/;}"
        else
            row "$name" csgray-faceted "$setting" "$(awk '{ print $1 }' "$work/times" | median)" \
                "$work/csgray.glb"
        fi
    done
    # csgray's first T: 1/50 of the diagonal (10 x compare's default tolerance, diagonal / 500).
    target="${FROM:-}"
    if [ -z "$target" ]; then
        read -r _ _ _ _ tol _ <<<"$(measure "$part" "$work/manifold.stl" "${exact[@]}")"
        target="$(awk -v t="$tol" 'BEGIN { printf "%.4g", 10 * t }')"
    fi
    for _ in $(seq "$steps"); do
        echo "$name: csgray T=$target" >&2
        : >"$work/times"
        ok=1
        for _ in $(seq "$runs"); do
            timed "$csgray" export "$part" -o "$work/csgray.glb" --quiet "${mine[@]}" \
                --tolerance "$target" || { ok=0; break; }
        done
        if [ "$ok" = 0 ]; then
            echo "$name,csgray,T=$target,,,,,,${why//,/;}"
        else
            row "$name" csgray "T=$target" "$(awk '{ print $1 }' "$work/times" | median)" \
                "$work/csgray.glb"
        fi
        target="$(awk -v t="$target" 'BEGIN { printf "%.4g", t / 2 }')"
    done
done
