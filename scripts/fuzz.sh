#!/usr/bin/env bash
# Fuzzes with libFuzzer under ASan and UBSan: the part language (parser, evaluator, compile;
# target `part`, the default) or the file readers (compare's and import()'s OBJ, STL, OFF, 3MF,
# GLB, glTF, and the DXF and SVG drawings, and the checks on what they read; target `mesh`).
# Usage: scripts/fuzz.sh [SECONDS] [part|mesh]   (default 600 part)
# Installs clang and its sanitizer runtimes if missing, builds the target in build-fuzz/, and
# runs it on its seed corpus (part: tests/fuzz/corpus and samples/; mesh: tests/fuzz/mesh_corpus;
# read only; new inputs go to build-fuzz/corpus-TARGET). Crashes, timeouts (> 5 s per input)
# and leaks land in build-fuzz/artifacts/; copy each into the target's corpus once it is
# fixed. One process, one thread (no -jobs/-workers: the machine is shared).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-600}"
target="${2:-part}"
case "$target" in
    part) binary=fuzz_io seeds=(tests/fuzz/corpus samples) dict=tests/fuzz/scad.dict ;;
    mesh) binary=fuzz_mesh seeds=(tests/fuzz/mesh_corpus) dict=tests/fuzz/mesh.dict ;;
    *) echo "usage: scripts/fuzz.sh [SECONDS] [part|mesh]" >&2; exit 2 ;;
esac
scripts/install-deps.sh clang libclang-rt-14-dev
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCSGRAY_FUZZ=ON \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ >/dev/null
cmake --build build-fuzz -j2 --target "$binary"
mkdir -p "build-fuzz/corpus-$target" build-fuzz/artifacts
# Leaks that are not csgray's (each with its reason) are suppressed; any other leak fails.
export LSAN_OPTIONS="suppressions=$PWD/tests/fuzz/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
exec "build-fuzz/tests/fuzz/$binary" "build-fuzz/corpus-$target" "${seeds[@]}" \
    -dict="$dict" -max_total_time="$seconds" -timeout=5 -rss_limit_mb=4096 \
    -max_len=4096 -print_final_stats=1 \
    -artifact_prefix=build-fuzz/artifacts/
