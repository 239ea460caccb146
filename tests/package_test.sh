#!/usr/bin/env bash
# The Debian package (issue 22): cpack builds the .deb from this build tree, dpkg -x unpacks it
# into a scratch root, and the csgray in it runs --help, then renders a sample on two MPI ranks
# (so it finds its MPI module where the package put it); its Depends must name Open MPI's
# library. Usage: package_test.sh BUILD_DIR SCRATCH_DIR SAMPLE
set -euo pipefail
build=$1
scratch=$2
sample=$3
rm -rf "$scratch"
mkdir -p "$scratch"
trap 'rm -rf "$scratch"' EXIT
cpack --config "$build/CPackConfig.cmake" -G DEB -B "$scratch/pkg" >"$scratch/cpack.log" 2>&1 ||
    { cat "$scratch/cpack.log"; exit 1; }
deb=$(ls "$scratch"/pkg/csgray_*.deb)
echo "built $(basename "$deb"): $(du -h "$deb" | cut -f1)"
depends=$(dpkg-deb -f "$deb" Depends)
echo "Depends: $depends"
[[ $depends == *libopenmpi* ]] || { echo "Depends does not name libopenmpi"; exit 1; }
dpkg -x "$deb" "$scratch/root"
"$scratch/root/usr/bin/csgray" --help | grep -q '^usage: csgray COMMAND' ||
    { echo "the packaged csgray --help failed"; exit 1; }
echo "the packaged csgray runs --help"
mpirun=(mpirun -np 2 --oversubscribe --mca btl_vader_single_copy_mechanism none)
[ "$(id -u)" -ne 0 ] || mpirun+=(--allow-run-as-root)
timeout 120 "${mpirun[@]}" "$scratch/root/usr/bin/csgray" render "$sample" -o "$scratch/two.png" \
    --size 64x48 --quiet || { echo "the packaged csgray failed under mpirun"; exit 1; }
"$scratch/root/usr/bin/csgray" render "$sample" -o "$scratch/one.png" --size 64x48 --quiet
cmp "$scratch/one.png" "$scratch/two.png"
echo "the packaged csgray renders on two MPI ranks, the same bytes as alone"
