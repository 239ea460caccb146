#!/usr/bin/env bash
# Peer comparison: POV-Ray against csgray on the scenes of ../shared/peers, at the same size,
# thread count and no anti-aliasing, in one run. Prints wall time and CPU time (user + sys)
# of each and their ratios, and the fraction of pixels whose object differs: both renderers
# draw every object in its own flat colour for that (POV-Ray from a generated copy of the
# scene, csgray with -D flat=true), and pixels are compared by object, not by shade.
#
#   bench/peer_render.sh [SIZE] [THREADS]     defaults: 1600 (a SIZE x SIZE image), nproc
#
# The glass torus (torus_glass) is rendered at SIZE/2 by both. RUNS=N (default 1) times each
# scene N times, POV-Ray and csgray in turn, prints every run and then a "NAME median" line: the
# median of each time and of the per-run ratios (the machine's load moves POV-Ray's time, and
# so the ratio, more than csgray's).
#
# Needs a built csgray (CSGRAY=path, default build/viewer/csgray) and POV-Ray (Debian
# `povray`; installed by `scripts/install-deps.sh povray` when missing: benchmarks are not part
# of the test set-up). Not a timed test: run it on an idle machine and look at `uptime` first.
set -euo pipefail

here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
peers="${PEERS:-$root/../shared/peers}"
[ -d "$peers" ] || peers=/work/shared/peers
size="${1:-1600}"
threads="${2:-$(nproc)}"
runs="${RUNS:-1}"
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || { echo "RUNS must be a positive integer, not '$runs'" >&2; exit 1; }
csgray="${CSGRAY:-$root/build/viewer/csgray}"
[ -x "$csgray" ] || { echo "no csgray at $csgray (build it, or set CSGRAY)" >&2; exit 1; }

command -v povray >/dev/null || "$root/scripts/install-deps.sh" povray

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

echo "load: $(uptime | sed 's/.*load average: //')   size ${size}x${size}   threads $threads"

# Runs a command and prints "wall cpu" (seconds; cpu = user + sys of the command).
timed() {
    /usr/bin/time -f "%e %U %S" -o "$work/time" "$@" >"$work/log" 2>&1 ||
        { cat "$work/log" >&2; return 1; }
    awk '{ printf "%.3f %.3f\n", $1, $2 + $3 }' "$work/time"
}

# The flat-colour copy of a POV scene: every object's texture replaced by an ambient-only
# pigment of linear ((I+1)/10, (J+1)/10, (K+1)/10), on a black background.
pov_flat_grid() {
    sed -e 's/background {[^}]*}/background { color rgb 0 }/' \
        -e '/pigment { color rgb <0.8,0.3,0.2> }/d' \
        -e '/finish { ambient 0.1 diffuse 0.7/d' \
        -e 's|object { Part rotate <I\*13, J\*17, K\*7> translate <I, J, K> }|object { Part rotate <I*13, J*17, K*7> translate <I, J, K> pigment { color rgb <(I+1)/10, (J+1)/10, (K+1)/10> } finish { ambient 1 diffuse 0 specular 0 } }|' \
        "$1"
}

# The torus scene's flat copy: the plane linear 0.2, the torus 1, no reflection, on black.
pov_flat_torus() {
    sed -e 's/background {[^}]*}/background { color rgb 0 }/' \
        -e 's/pigment { checker color rgb 1 color rgb 0.1 }/pigment { color rgb 0.2 }/' \
        -e 's/pigment { color rgb <0.9,0.9,0.9> }/pigment { color rgb 1 }/' \
        -e 's/finish {[^}]*}/finish { ambient 1 diffuse 0 specular 0 }/' \
        "$1"
}

# The glass torus's flat copy: as the mirror torus's, the glass opaque in colour 1.
pov_flat_glass() {
    sed -e 's/background {[^}]*}/background { color rgb 0 }/' \
        -e 's/pigment { checker color rgb 1 color rgb 0.1 }/pigment { color rgb 0.2 }/' \
        -e 's/pigment { color rgbf <0.95,0.95,1,0.9> }/pigment { color rgb 1 }/' \
        -e 's/finish {[^}]*}/finish { ambient 1 diffuse 0 specular 0 }/' \
        "$1"
}

# Fraction of pixels whose object differs, from POV-Ray's linear PPM and csgray's PFM.
compare_ids() {
    python3 - "$1" "$2" <<'PY'
import struct, sys
def ppm(path):
    data = open(path, 'rb').read()
    parts, pos = [], 0
    while len(parts) < 4:  # magic, width, height, maxval; '#' starts a comment line
        while data[pos:pos + 1].isspace(): pos += 1
        if data[pos:pos + 1] == b'#':
            pos = data.index(b'\n', pos)
            continue
        end = pos
        while not data[end:end + 1].isspace(): end += 1
        parts.append(data[pos:end]); pos = end
    pos += 1
    w, h, maxval = int(parts[1]), int(parts[2]), int(parts[3])
    step = 2 if maxval > 255 else 1
    px = []
    for i in range(w * h):
        rgb = []
        for c in range(3):
            o = pos + (i * 3 + c) * step
            v = data[o] if step == 1 else (data[o] << 8 | data[o + 1])
            rgb.append(v / maxval)
        px.append(rgb)
    return w, h, px
def pfm(path):
    data = open(path, 'rb').read()
    lines = data.split(b'\n', 3)
    w, h = map(int, lines[1].split()); scale = float(lines[2])
    fmt = '<' if scale < 0 else '>'
    floats = struct.unpack(fmt + '%df' % (w * h * 3), lines[3][:w * h * 12])
    px = [None] * (w * h)
    for row in range(h):  # PFM rows run bottom to top
        for x in range(w):
            o = ((h - 1 - row) * w + x) * 3
            px[row * w + x] = floats[o:o + 3]
    return w, h, px
def ident(rgb):
    if max(rgb) < 0.05: return None  # background
    return tuple(int(round(c * 10)) for c in rgb)
w1, h1, a = ppm(sys.argv[1]); w2, h2, b = pfm(sys.argv[2])
assert (w1, h1) == (w2, h2), ((w1, h1), (w2, h2))
differ = sum(1 for p, q in zip(a, b) if ident(p) != ident(q))
print('%.4f' % (differ / len(a)))
PY
}

# run_scene NAME POV SCAD [csgray options...]
run_scene() {
    local name="$1" pov="$2" scad="$3"
    shift 3
    # POV-Ray options: no display, no pause, no AA, the size and threads.
    local pov_common=(-D -P -A +W"$size" +H"$size" +WT"$threads")
    if ! "$csgray" info "$scad" >/dev/null 2>"$work/info.err"; then
        echo "$name: skipped, csgray cannot load $scad: $(head -1 "$work/info.err")"
        return 0
    fi
    # Timed runs: the scenes as they are (shading, shadows), PNG output for both; one line of
    # times (POV wall, POV cpu, csgray wall, csgray cpu) per run in $work/$name.times.
    : >"$work/$name.times"
    for ((run = 0; run < runs; ++run)); do
        read -r pov_wall pov_cpu < <(timed povray "${pov_common[@]}" +I"$pov" \
            +O"$work/$name.pov.png" +FN)
        read -r cs_wall cs_cpu < <(timed "$csgray" render "$scad" -o "$work/$name.csgray.png" \
            --size "${size}x${size}" --threads "$threads" --quiet "$@")
        echo "$pov_wall $pov_cpu $cs_wall $cs_cpu" >>"$work/$name.times"
    done
    # Silhouettes: flat colours, linear output.
    pov_flat_"$name" "$pov" >"$work/$name.flat.pov"
    povray "${pov_common[@]}" +I"$work/$name.flat.pov" +O"$work/$name.flat.ppm" +FP \
        File_Gamma=1.0 >"$work/log" 2>&1 || { cat "$work/log" >&2; return 1; }
    "$csgray" render "$scad" -D flat=true -o "$work/$name.flat.pfm" --size "${size}x${size}" \
        --threads "$threads" --quiet "$@"
    local differ
    differ="$(compare_ids "$work/$name.flat.ppm" "$work/$name.flat.pfm")"
    awk -v n="$name" -v sz="$size" -v d="$differ" -v runs="$runs" '
        function line(label, pw, pc, cw, cc, wr, cr) {
            printf "%-6s %5d  POV-Ray wall %7.2f s cpu %7.2f s | csgray wall %7.2f s cpu %7.2f s | ", label, sz, pw, pc, cw, cc
            printf "wall ratio %5.2fx cpu ratio %5.2fx | objects differ %.2f%% of pixels\n", wr, cr, 100 * d
        }
        function median(a, k,   i, j, t) {  # insertion sort of a[1..k], then its middle
            for (i = 2; i <= k; ++i)
                for (j = i; j > 1 && a[j - 1] > a[j]; --j) { t = a[j]; a[j] = a[j - 1]; a[j - 1] = t }
            return k % 2 ? a[(k + 1) / 2] : (a[k / 2] + a[k / 2 + 1]) / 2
        }
        { pw[NR] = $1; pc[NR] = $2; cw[NR] = $3; cc[NR] = $4; wr[NR] = $1 / $3; cr[NR] = $2 / $4
          line(n, $1, $2, $3, $4, wr[NR], cr[NR]) }
        END { if (runs > 1) line(n " median", median(pw, NR), median(pc, NR), median(cw, NR),
                                 median(cc, NR), median(wr, NR), median(cr, NR)) }' "$work/$name.times"
}

run_scene grid "$peers/csg_grid.pov" "$here/scenes/csg_grid.scad"
if [ -f "$here/scenes/torus_mirror.scad" ]; then
    # POV's max_trace_level 5 counts the primary ray: 4 bounces.
    run_scene torus "$peers/torus_mirror.pov" "$here/scenes/torus_mirror.scad" --max-depth 4
else
    echo "torus: skipped, bench/scenes/torus_mirror.scad is not written yet"
fi
# POV's max_trace_level 8 counts the primary ray: 7 bounces. Rendered at half SIZE (800x800 for
# the default 1600), as issue 21 measured it.
size=$((size / 2)) run_scene glass "$peers/torus_glass.pov" "$here/scenes/torus_glass.scad" --max-depth 7
