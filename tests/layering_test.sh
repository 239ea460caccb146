#!/usr/bin/env bash
# The layers of DESIGN.md, lowest first: no file includes a header of a higher layer.
#   0 primitives/base/   numbers, boxes, tolerances, threads, files, JSON (nothing of csgray's)
#   1 primitives/        the leaves and their root solvers
#   2 csg/               the tree, compile, the queries, volume, meshing
#   3 viewer/render/     the renderer, its scene description (Look.h) and image files
#   4 io/                the part language (it fills in the renderer's description), mesh files
#   5 viewer/cli/, viewer/window/   the command line and the window
# tests/ and bench/ may include any library header but not the command line's (viewer/cli/).
# Usage: layering_test.sh SOURCE_DIR. Prints every offending include; exit 1 if there is one.
set -uo pipefail
cd "$1"

layer() {
    case "$1" in
        primitives/base/*) echo 0 ;;
        primitives/*) echo 1 ;;
        csg/*) echo 2 ;;
        viewer/render/*) echo 3 ;;
        io/*) echo 4 ;;
        viewer/cli/* | viewer/window/*) echo 5 ;;
        tests/* | bench/*) echo 6 ;;
        *) echo "" ;;
    esac
}

bad=0
checked=0
while IFS= read -r file; do
    from=$(layer "$file")
    [ -n "$from" ] || continue
    while IFS= read -r line; do
        header=${line#*\"}
        header=${header%%\"*}
        to=$(layer "$header")
        [ -n "$to" ] || continue  # a header beside the file (tests' helpers)
        checked=$((checked + 1))
        if [ "$from" -eq 6 ] && [[ $header == viewer/cli/* ]]; then
            echo "$file includes $header: tests and bench use libraries, not the command line"
            bad=1
        elif [ "$to" -gt "$from" ]; then
            echo "$file includes $header (layer $to above $from)"
            bad=1
        fi
    done < <(grep -h '^#include "' "$file")
done < <(git ls-files '*.h' '*.cpp' 2>/dev/null || find . -name '*.h' -o -name '*.cpp' | sed 's|^\./||')

# A check that found nothing to check would pass whatever the code does.
if [ "$checked" -lt 500 ]; then
    echo "only $checked project includes found: is $1 the source tree?"
    exit 1
fi
echo "$checked includes checked, $([ $bad -eq 0 ] && echo none || echo some) against the layers"
exit $bad
