#!/usr/bin/env bash
# Installs every Debian package csgray needs to build, test and benchmark.
# Usage: scripts/install-deps.sh [PACKAGE...]   (with packages: only those)
# Idempotent: when everything is present it prints nothing and exits 0.
set -euo pipefail

packages=(
    build-essential cmake ninja-build pkg-config
    libglm-dev            # vector/matrix math, through primitives/base/Math.h only
    libopenmesh-dev       # mesh structure and OBJ IO (mesh export)
    libtinygltf-dev nlohmann-json3-dev libstb-dev  # glTF/GLB writer and its JSON/image deps
    libpng-dev libdeflate-dev  # PNG: reading textures (libpng), writing images (libdeflate)
    libpolyclipping-dev   # Clipper: polygon booleans of projection() (csg/section)
    libjemalloc-dev       # csgray's heap, on transparent huge pages (viewer/cli/HeapConfig.cpp)
    libopenexr-dev        # OpenEXR output (render --format exr)
    libsdl2-dev           # `csgray view`: the interactive window
    xvfb xdotool          # viewer_test: a virtual X server and the input it sends the window
    libgtest-dev libgmock-dev  # tests
    libbenchmark-dev      # bench/
    python3               # bench/teapot_probe_agreement.py and bench/benchmark_smoke.py, run by ctest
    libfreetype-dev libharfbuzz-dev libfontconfig-dev  # text(): outlines, shaping, font lookup
    fonts-liberation2     # text()'s default font, Liberation Sans, the file Debian's openscad opens
    libpolyclipping-dev   # Clipper 6.4: offset() as OpenSCAD 2021 computes it (csg/derived/)
    libtinyxml2-dev       # TinyXML-2: the XML of import("drawing.svg") (io/SvgFile.cpp)
    libqhull-dev          # qhull (reentrant libqhull_r): 3-D hull() (csg/derived/Hull3D.cpp)
    libboost-dev          # Boost.Multiprecision: 50-digit references (tests, csgray bench accuracy)
    libgmp-dev            # GMP rationals (gmpxx.h): the exact Groebner basis (primitives/patch/GroebnerExact.cpp)
    openscad              # CLI tests: samples load in OpenSCAD and round-trip through its .csg
    openscad-mcad         # MCAD, the library OpenSCAD's examples and users include (use <MCAD/...>)
    libopenmpi-dev openmpi-bin  # MPI: csgray under mpirun/srun (viewer/cli/dist/), its tests' mpirun
)

# cli_mesh_test runs the Khronos glTF validator (npm gltf-validator) under Node. Any Node with
# npm will do; only when there is none is Debian's installed.
command -v npm >/dev/null 2>&1 || packages+=(nodejs npm)

# With arguments, just those packages instead (scripts/fuzz.sh: clang and its sanitizer runtime).
[ $# -eq 0 ] || packages=("$@")

missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
echo "install-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq >/dev/null
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
