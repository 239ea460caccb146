#!/usr/bin/env bash
# Strong scaling of `csgray render` (or `csgray export`) over MPI ranks, and the MPI path's
# overhead at one rank (bench/README.md, "Rendering on MPI ranks"). The configurations run in
# turn, REPEATS rounds, so that a shared machine's load changes weigh on all of them alike;
# printed are the medians of wall time, of the render phase (--stats; render only) and of CPU
# time (user + system, every process). Every output is checked against a single-process
# reference, byte for byte.
# Usage: bench/mpi_scaling.sh [CSGRAY] [PART] [SIZE] [REPEATS] [render|export]
#   export: SIZE is the tolerance, e.g.
#   bench/mpi_scaling.sh build/viewer/csgray samples/scene_surfaces.scad 0.001 3 export
set -euo pipefail
csgray=${1:-build/viewer/csgray}
part=${2:-samples/teapot.scad}
size=${3:-1200x900}
repeats=${4:-7}
command=${5:-render}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
mpirun="mpirun --oversubscribe --mca btl_vader_single_copy_mechanism none"
[ "$(id -u)" -ne 0 ] || mpirun+=" --allow-run-as-root"
case "$command" in
    render) output=out.png what=(--size "$size") ;;
    export) output=out.stl what=(--tolerance "$size") ;;
    *) echo "usage: bench/mpi_scaling.sh [CSGRAY] [PART] [SIZE] [REPEATS] [render|export]" >&2; exit 2 ;;
esac

labels=("alone, --threads 1" "alone, --threads 2" "mpirun -np 1, --threads 1"
        "mpirun -np 1, --threads 2" "mpirun -np 2, --threads 1 each"
        "mpirun -np 4, --threads 1 each (oversubscribed)")
commands=("$csgray $command --threads 1" "$csgray $command --threads 2"
          "$mpirun -np 1 $csgray $command --threads 1" "$mpirun -np 1 $csgray $command --threads 2"
          "$mpirun -np 2 $csgray $command --threads 1" "$mpirun -np 4 $csgray $command --threads 1")

median() { sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }

"$csgray" "$command" "$part" "${what[@]}" -o "$scratch/reference.${output#*.}" --quiet
echo "$(nproc) cores, $command $part ${what[*]}, median of $repeats rounds, load before: $(cut -d' ' -f1-3 /proc/loadavg)"
for round in $(seq "$repeats"); do
    for i in "${!commands[@]}"; do
        stats=()
        [ "$command" = render ] && stats=(--stats "$scratch/stats.json")
        /usr/bin/time -f "%e %U %S" -o "$scratch/time" ${commands[$i]} "$part" "${what[@]}" \
            -o "$scratch/$output" "${stats[@]}" --quiet
        cmp -s "$scratch/$output" "$scratch/reference.${output#*.}" || { echo "${labels[$i]}: output differs"; exit 1; }
        read -r wall user sys <"$scratch/time"
        render=-
        [ "$command" = render ] && render=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['seconds']['render'])" "$scratch/stats.json")
        echo "$wall $render $(echo "$user + $sys" | bc)" >>"$scratch/config$i"
    done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| configuration | wall, s | render phase, s | CPU, s |"
echo "|---|---|---|---|"
for i in "${!commands[@]}"; do
    phase=$(cut -d' ' -f2 "$scratch/config$i" | median)
    [ "$phase" = - ] || phase=$(printf "%.2f" "$phase")
    printf "| %s | %.2f | %s | %.2f |\n" "${labels[$i]}" \
        "$(cut -d' ' -f1 "$scratch/config$i" | median)" "$phase" \
        "$(cut -d' ' -f3 "$scratch/config$i" | median)"
done
