#!/usr/bin/env bash
# Set-up command 1: installs, builds and runs the main job on a bundled sample: renders the CSG
# emblem to emblem.png and prints the span list of one ray through it.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
build/viewer/csgray render samples/emblem.scad -o emblem.png --size 640x480
echo "wrote emblem.png" >&2
build/viewer/csgray probe samples/emblem.scad --origin 3,-4,2 --dir -3,4,-2
