# shellcheck shell=bash
# Helpers shared by bench/peer_export.sh (the per-part table) and bench/export_sweep.sh (the
# triangles-against-distance sweep): finding the binaries, installing Manifold, running a command
# under a time limit, turning a part into Manifold's tree, and measuring a mesh against the part.
# Sourced, not run. Sets: root, peers, csgray, dumper, manifold, work (removed on exit), limit.
#
# Every helper that can fail returns non-zero and leaves its reason in $why (one line), so the
# caller can print "n/a: $why" and go on to the next part instead of stopping the whole run.

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
peers="${PEERS:-$root/../shared/peers}"
[ -d "$peers" ] || peers=/work/shared/peers
csgray="${CSGRAY:-$root/build/viewer/csgray}"
dumper="$(dirname "$(dirname "$csgray")")/bench/csg_to_manifold"
[ -x "$csgray" ] || { echo "no csgray at $csgray (build it, or set CSGRAY)" >&2; exit 1; }
[ -x "$dumper" ] || { echo "no csg_to_manifold at $dumper (build it)" >&2; exit 1; }
# Seconds one command may take (each run of each exporter, each measurement): a part that hangs
# one exporter costs at most this, and its row says so.
limit="${TIMEOUT:-300}"
why=""

manifold="$(dirname "$(dirname "$csgray")")/bench/manifold"
if [ ! -d "$manifold/node_modules/manifold-3d" ]; then
    mkdir -p "$manifold"
    cp "$here/manifold/package.json" "$manifold/"
    (cd "$manifold" && npm install --no-audit --no-fund --loglevel=error >/dev/null)
fi
cp "$here/manifold/export.mjs" "$manifold/"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }

# A command's first error line (else its last line) as a reason, paths cut to their file names.
reason_of() { { grep -m 1 'error: ' "$1" || tail -n 1 "$1"; } | sed -E -e 's|/[^ :]*/([^/ :]+)|\1|g' -e 's/^csg_to_manifold: //' -e 's/^error: //' -e 's/^[^ ]+\.scad: //' | cut -c 1-160; }

# Fails with $why set when exit code $1 of command $2 says it failed or timed out.
check_exit() {
    if [ "$1" = 124 ] || [ "$1" = 137 ]; then
        why="timed out after $limit s: $(basename "$2")"
        return 1
    elif [ "$1" != 0 ]; then
        why="$(basename "$2") failed (exit $1): $(reason_of "$work/log")"
        return 1
    fi
}

# Runs a command under the time limit with its output in $work/log; non-zero with $why set when
# it fails or times out.
limited() {
    local rc=0
    timeout -k 10 "$limit" "$@" >"$work/log" 2>&1 || rc=$?
    check_exit "$rc" "$1"
}

# Like limited, and appends "wall cpu" (seconds; CPU = user + sys) to $work/times.
timed() {
    local rc=0
    /usr/bin/time -f "%e %U %S" -o "$work/time" timeout -k 10 "$limit" "$@" >"$work/log" 2>&1 ||
        rc=$?
    check_exit "$rc" "$1" || return 1
    tail -n 1 "$work/time" | awk '{ printf "%.3f %.3f\n", $1, $2 + $3 }' >>"$work/times"
}

# dump PART [csg_to_manifold options]: Manifold's tree of the part in $work/tree.json. Fails
# (with $why) when csg_to_manifold refuses a leaf or the part has no solid.
dump() {
    local part="$1"
    shift
    timeout -k 10 "$limit" "$dumper" "$part" "$@" >"$work/tree.json" 2>"$work/dump.err" || {
        why="$(reason_of "$work/dump.err")"
        [ -n "$why" ] || why="csg_to_manifold timed out after $limit s"
        return 1
    }
    if [ "$(head -c 15 "$work/tree.json")" = '{"empty":true}' ]; then
        why="no solid (the part is empty)"
        return 1
    fi
}

# manifold_run: one Manifold export of $work/tree.json to $work/manifold.stl; appends its
# seconds (first leaf to final mesh, as export.mjs times it) to $work/mseconds.
manifold_run() {
    limited node "$manifold/export.mjs" "$work/tree.json" "$work/manifold.stl" || return 1
    python3 -c "import json, sys; print('%.3f' % json.loads(open(sys.argv[1]).read().splitlines()[-1])['seconds'])" \
        "$work/log" >>"$work/mseconds"
}

# measure PART MESH [compare options]: "triangles mesh->surface surface->mesh volume tolerance
# closed" of the mesh against the part (tolerance: compare's default, the diagonal / 500) (csgray
# compare; closed is yes or no: a closed, manifold mesh oriented outward). Fails with $why when
# compare gives no figures.
# compare's mesh->surface is an upper bound at each sample that stops searching once within its
# tolerance, so a mesh far finer than the diagonal / 500 reads too far (csg_grid3 exported at
# T = 0.002: 0.0070 at compare's default, 0.0016 at --tolerance 0.002). A mesh measured within
# the default is therefore measured again with a quarter of the larger distance found as the
# tolerance, where the search goes on to the nearest surface; not one within a thousandth of the
# default (float rounding of the file, which bench/peer_export.sh counts as equal).
measure() {
    local part="$1" mesh="$2"
    shift 2
    timeout -k 10 "$limit" "$csgray" compare "$part" "$mesh" --json "$@" >"$work/compare.json" \
        2>"$work/compare.err" || true # exit 1 only says "not within compare's tolerance"
    # compare's lines and nearest-triangle search reach max(10 tolerance, diagonal / 50); a
    # sample farther from the other side is unresolved and its maximum infinite (JSON null).
    # A mesh that coarse (OpenSCAD's default faceting of a small part) is measured again with
    # 100 times the tolerance, which reaches twice the diagonal.
    local tol wide
    read -r tol wide <<<"$(python3 -c 'import json, sys
j = json.load(open(sys.argv[1]))
print("%.6g" % j["tolerance"], "%.6g" % (100 * j["tolerance"])
      if j["meshToSurface"]["max"] is None or j["surfaceToMesh"]["max"] is None else "")' \
        "$work/compare.json" 2>/dev/null || true)"
    if [ -n "$wide" ]; then
        timeout -k 10 "$limit" "$csgray" compare "$part" "$mesh" --json "$@" --tolerance "$wide" \
            >"$work/compare.json" 2>"$work/compare.err" || true
    else
        local tight
        tight="$(python3 -c 'import json, sys
j = json.load(open(sys.argv[1]))
d = max(j["meshToSurface"]["max"], j["surfaceToMesh"]["max"])
print("%.6g" % (d / 4) if 1e-3 * j["tolerance"] < d / 4 < j["tolerance"] else "")' \
            "$work/compare.json" 2>/dev/null ||
            true)"
        # (Its exit code is 1 here: the distances are beyond the tolerance asked.) Taken when it
        # gives both maxima.
        if [ -n "$tight" ]; then
            timeout -k 10 "$limit" "$csgray" compare "$part" "$mesh" --json "$@" --tolerance \
                "$tight" >"$work/compare.tight.json" 2>"$work/compare.err" || true
            if python3 -c 'import json, sys
j = json.load(open(sys.argv[1]))
sys.exit(j["meshToSurface"]["max"] is None or j["surfaceToMesh"]["max"] is None)' \
                "$work/compare.tight.json" 2>/dev/null; then
                mv "$work/compare.tight.json" "$work/compare.json"
            fi
        fi
    fi
    python3 - "$work/compare.json" "$work/measure.why" "$tol" 2>/dev/null <<'EOF' || {
import json, sys
j = json.load(open(sys.argv[1]))
to, fro = j["meshToSurface"], j["surfaceToMesh"]
if to["max"] is None or fro["max"] is None:
    # compare gives no maximum when some samples found no surface (or no mesh) along their
    # lines: a mesh that far from the part has no figure to compare.
    open(sys.argv[2], "w").write(
        "compare bounds no distance: %d of %d mesh samples and %d of %d surface samples "
        "unresolved (volume %.4g against the part's %.4g)" % (
            to.get("unresolved", 0), to.get("samples", 0), fro.get("unresolved", 0),
            fro.get("samples", 0), j["volume"]["mesh"], j["volume"]["part"]))
    sys.exit(1)
print(j["triangles"], "%.3g" % to["max"], "%.3g" % fro["max"], "%.7g" % j["volume"]["mesh"],
      sys.argv[3],
      "yes" if j["topology"]["closedManifold"] and j["topology"]["outward"] else "no")
EOF
        if [ -s "$work/measure.why" ]; then
            why="$(basename "$mesh"): $(cat "$work/measure.why")"
        else
            why="compare of $(basename "$mesh") failed: $(reason_of "$work/compare.err")"
        fi
        rm -f "$work/measure.why"
        return 1
    }
}
