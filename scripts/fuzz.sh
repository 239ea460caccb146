#!/usr/bin/env bash
# Fuzzes the part language (parser, evaluator, compile) with libFuzzer under ASan and UBSan.
# Usage: scripts/fuzz.sh [SECONDS]   (default 600)
# Installs clang and its sanitizer runtimes if missing, builds tests/fuzz/fuzz_io in
# build-fuzz/, and runs it on the seed corpus (tests/fuzz/corpus and samples/, read only; new
# inputs go to build-fuzz/corpus). Crashes, timeouts (> 5 s per input) and leaks land in
# build-fuzz/artifacts/; copy each into tests/fuzz/corpus once it is fixed. One process, one
# thread (no -jobs/-workers: the machine is shared).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-600}"

scripts/install-deps.sh clang libclang-rt-14-dev

cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCSGRAY_FUZZ=ON \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ >/dev/null
cmake --build build-fuzz -j2 --target fuzz_io

mkdir -p build-fuzz/corpus build-fuzz/artifacts
exec build-fuzz/tests/fuzz/fuzz_io build-fuzz/corpus tests/fuzz/corpus samples \
    -dict=tests/fuzz/scad.dict -max_total_time="$seconds" -timeout=5 -rss_limit_mb=4096 \
    -max_len=4096 -print_final_stats=1 \
    -artifact_prefix=build-fuzz/artifacts/
