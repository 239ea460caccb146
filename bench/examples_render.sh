#!/usr/bin/env bash
# Loading and rendering every OpenSCAD example Debian ships, at 800x600: `csgray render` against
# OpenSCAD 2021's `openscad --render -o x.png` (CGAL's evaluation, then its OpenGL image, drawn
# on one Xvfb server started here so that no run pays for a server of its own). Each part is run
# REPS times by each (interleaved), and the medians of wall time are printed as a Markdown table
# with their ratio, then the sums and the median ratio. A run that fails or passes the time
# limit is marked so and left out of the sums.
#
#   bench/examples_render.sh [REPS]          default 3; TIMEOUT=seconds per run (default 300)
#
# Needs a built csgray (CSGRAY=path, default build/viewer/csgray), Debian's openscad and Xvfb
# (both installed by scripts/install-deps.sh). Not a timed test: look at `uptime` first.
set -euo pipefail

here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
reps="${1:-3}"
limit="${TIMEOUT:-300}"
csgray="${CSGRAY:-$root/build/viewer/csgray}"
[ -x "$csgray" ] || { echo "no csgray at $csgray (build it, or set CSGRAY)" >&2; exit 1; }
command -v openscad >/dev/null || { echo "no openscad (scripts/install-deps.sh)" >&2; exit 1; }
command -v Xvfb >/dev/null || { echo "no Xvfb (scripts/install-deps.sh)" >&2; exit 1; }

work="$(mktemp -d)"
display=":$((100 + $$ % 800))"
Xvfb "$display" -screen 0 1024x768x24 -nolisten tcp >/dev/null 2>&1 &
xvfb=$!
trap 'kill "$xvfb" 2>/dev/null; rm -rf "$work"' EXIT
sleep 1

median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }

# Wall seconds of one run (appended to file $1), or nothing when it failed or timed out.
run() {
    local file="$1"
    shift
    if /usr/bin/time -f %e -o "$work/t" timeout -k 10 "$limit" "$@" >"$work/log" 2>&1; then
        cat "$work/t" >>"$file"
    fi
}

echo "| part | csgray render (s) | openscad --render (s) | openscad / csgray |"
echo "|---|---:|---:|---:|"
sum_c=0
sum_o=0
: >"$work/ratios"
for part in /usr/share/openscad/examples/*/*.scad; do
    name="$(basename "$(dirname "$part")")/$(basename "$part" .scad)"
    : >"$work/c"
    : >"$work/o"
    for _ in $(seq "$reps"); do
        run "$work/c" "$csgray" render "$part" -o "$work/c.png" --size 800x600 --quiet
        run "$work/o" env DISPLAY="$display" openscad --render -o "$work/o.png" \
            --imgsize=800,600 "$part"
    done
    c="$( [ -s "$work/c" ] && median <"$work/c" || echo failed)"
    o="$( [ -s "$work/o" ] && median <"$work/o" || echo failed)"
    ratio="n/a"
    if [ "$c" != failed ] && [ "$o" != failed ]; then
        ratio="$(awk -v c="$c" -v o="$o" 'BEGIN { printf "%.2f", (c > 0 ? o / c : 0) }')"
        echo "$ratio" >>"$work/ratios"
        sum_c="$(awk -v a="$sum_c" -v b="$c" 'BEGIN { print a + b }')"
        sum_o="$(awk -v a="$sum_o" -v b="$o" 'BEGIN { print a + b }')"
    fi
    echo "| $name | $c | $o | $ratio |"
done
echo
echo "Sums over the parts both rendered: csgray $sum_c s, openscad $sum_o s;" \
    "median ratio $(median <"$work/ratios") over $(wc -l <"$work/ratios") parts."
