#!/usr/bin/env bash
# BOSL2's own regression tests (tests/test_*.scadtest, TOML, one [[test]] a script) run through
# Debian's OpenSCAD 2021 and through csgray, with the pass rule of BOSL2's runner `openscad-test`
# (openscad_runner in test-only mode: `openscad -o foo.term SCRIPT`; the run fails on an ERROR:
# or TRACE: line or a non-zero exit; then expect_success, assert_no_echoes and
# assert_no_warnings, default true, are checked against the ECHO:/WARNING: lines). csgray runs
# `csgray info SCRIPT` under the same rule, its "file:line:col: error:" and "warning:" lines
# counted as ERROR: and WARNING:. BOSL2 cannot be bundled or downloaded in CI, so this is a
# script over a checkout you have; bench/README.md has its figures and the commit they were
# taken at.
# Usage: scripts/bosl2_conformance.sh BOSL2_DIR [--build DIR] [--jobs N] [--filter REGEX]
#        [--geometry] [--keep DIR]
#   --filter REGEX  only the tests whose "file:name" matches REGEX
#   --geometry      for every test both pass whose top level makes a 3-D solid, also export
#                   OpenSCAD's STL (up to 120 s) and run `csgray compare --curves openscad`
#                   (agree: surface->mesh maximum and mesh->surface mean within 1e-5 of the
#                   diagonal, as tests/examples_test.cpp holds Debian's examples)
#   --keep DIR      leave the extracted scripts and every run's output in DIR
# Prints one line per test that OpenSCAD and csgray judge differently, then the counts.
set -euo pipefail
[ $# -ge 1 ] || { sed -n 2,18p "$0" | sed 's/^# \{0,1\}//'; exit 2; }
bosl2=$(cd "$1" && pwd)
shift
root=$(cd "$(dirname "$0")/.." && pwd)
build="$root/build"
jobs=1
filter=""
geometry=0
keep=""
while [ $# -gt 0 ]; do
    case "$1" in
        --build) build=$(cd "$2" && pwd); shift 2 ;;
        --jobs) jobs=$2; shift 2 ;;
        --filter) filter=$2; shift 2 ;;
        --geometry) geometry=1; shift ;;
        --keep) keep=$2; shift 2 ;;
        *) echo "bosl2_conformance: unknown option '$1'" >&2; exit 2 ;;
    esac
done
csgray="$build/viewer/csgray"
[ -x "$csgray" ] || { echo "bosl2_conformance: no $csgray (build the csgray target)" >&2; exit 2; }
[ -f "$bosl2/std.scad" ] && [ -d "$bosl2/tests" ] || {
    echo "bosl2_conformance: $bosl2 has no std.scad and tests/" >&2
    exit 2
}
if [ -n "$keep" ]; then
    mkdir -p "$keep"
    work=$(cd "$keep" && pwd)
else
    work=$(mktemp -d)
    trap 'rm -rf "$work"' EXIT
fi

commit=$(git -C "$bosl2" rev-parse HEAD 2>/dev/null || echo unknown)
echo "BOSL2 $commit; $(openscad --version 2>&1); csgray $(git -C "$root" rev-parse --short HEAD)"

# A tree of links to BOSL2's files, so that a test script written to tree/tests/ finds
# <../std.scad> the way it does in BOSL2's own tests/ folder.
rm -rf "$work/tree" "$work/runs"
cp -rs "$bosl2/." "$work/tree"
mkdir -p "$work/runs"
# A copy of the binary, so that a rebuild during the run does not change it.
cp "$csgray" "$work/csgray"

BOSL2_WORK=$work CSGRAY=$work/csgray JOBS=$jobs FILTER=$filter GEOMETRY=$geometry python3 - <<'EOF'
import concurrent.futures, json, os, re, subprocess, sys, tomllib
from pathlib import Path

work = Path(os.environ["BOSL2_WORK"])
csgray = os.environ["CSGRAY"]
geometry = os.environ["GEOMETRY"] == "1"
pattern = re.compile(os.environ["FILTER"]) if os.environ["FILTER"] else None
tree_tests = work / "tree" / "tests"
runs = work / "runs"

cases = []
for f in sorted(tree_tests.glob("test_*.scadtest")):
    with open(f, "rb") as fh:
        data = tomllib.load(fh)
    for i, t in enumerate(data.get("test", [])):
        key = f"{f.stem}:{t.get('name', i)}"
        if pattern and not pattern.search(key):
            continue
        unsupported = set(t) - {"name", "script", "expect_success", "assert_no_echoes",
                                "assert_no_warnings", "assert_echoes", "assert_warnings"}
        if unsupported or "script" not in t:
            print(f"bosl2_conformance: {key}: cannot run ({sorted(unsupported) or 'no script'})",
                  file=sys.stderr)
            continue
        script = tree_tests / f"zz_{f.stem}_{i:03d}.scad"
        script.write_text(t["script"])
        cases.append((key, script, t))

def judge(t, ok, echos, warnings):
    """openscad-test's rule: the run's success against expect_success, then the echo and
    warning checks (skipped where a list of expected ones is given)."""
    if t.get("expect_success", True) != ok:
        return False
    if not ok:
        return True
    for want in t.get("assert_echoes", []):
        if not any(want in e for e in echos):
            return False
    if t.get("assert_no_echoes", True) and not t.get("assert_echoes") and echos:
        return False
    for want in t.get("assert_warnings", []):
        if not any(want in w for w in warnings):
            return False
    if t.get("assert_no_warnings", True) and not t.get("assert_warnings") and warnings:
        return False
    return True

geometry_timeout = 120  # seconds for OpenSCAD's STL export of one test (CGAL can be slow)

def run(cmd, cwd, timeout=600):
    try:
        p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=timeout,
                           errors="replace")
        return p.returncode, p.stdout, p.stderr
    except subprocess.TimeoutExpired:
        return None, "", f"timed out after {timeout} s"
    except OSError as e:
        return None, "", f"cannot run {cmd[0]}: {e}"

def one(case):
    key, script, t = case
    stem = runs / script.stem
    # OpenSCAD, exactly as openscad_runner's test-only mode runs it.
    rc, _, err = run(["openscad", "-o", f"{stem}.term", script.name], tree_tests)
    lines = err.splitlines()
    o_ok = rc == 0 and not any(l.startswith(("ERROR:", "TRACE:")) for l in lines)
    o_pass = judge(t, o_ok, [l for l in lines if l.startswith("ECHO:")],
                   [l for l in lines if l.startswith("WARNING:")])
    Path(f"{stem}.openscad").write_text(err)
    # csgray: the diagnostics are "file:line:col: error: ..." and "...: warning: ...".
    rc, out, err = run([csgray, "info", script.name], tree_tests)
    lines = err.splitlines()
    c_ok = rc == 0 and not any(": error: " in l for l in lines)
    c_pass = judge(t, c_ok, [l for l in lines if l.startswith("ECHO:")],
                   [l for l in lines if ": warning: " in l])
    Path(f"{stem}.csgray").write_text(err if rc is not None else "timed out\n")
    first = next((l for l in lines if ": error: " in l or ": warning: " in l
                  or l.startswith("ECHO:")), err.strip()[:200])
    same = None
    if geometry and o_pass and c_pass and c_ok:
        try:
            info = json.loads(out)
        except json.JSONDecodeError:
            info = {}
        bounds = info.get("bounds")
        # 3-D solids only: OpenSCAD exports no STL of a 2-D part.
        if bounds and info.get("dimensions") == 3:
            stl = f"{stem}.stl"
            src, _, _ = run(["openscad", "-o", stl, script.name], tree_tests, geometry_timeout)
            if src is None:
                same = "timeout"
            elif src == 0 and os.path.exists(stl) and os.path.getsize(stl) > 0:
                # As tests/examples_test.cpp holds Debian's examples: every sample of csgray's
                # surface within T of OpenSCAD's mesh, the mesh on the surface on average.
                diagonal = sum((a - b) ** 2 for a, b in zip(bounds["max"], bounds["min"])) ** 0.5
                tolerance = 1e-5 * diagonal
                _, cout, _ = run([csgray, "compare", script.name, stl, "--json", "--curves",
                                  "openscad"], tree_tests)
                try:
                    j = json.loads(cout)
                    worst, mean = j["surfaceToMesh"]["max"], j["meshToSurface"]["mean"]
                    same = worst is not None and worst <= tolerance and mean <= tolerance
                    if not same:
                        Path(f"{stem}.compare").write_text(cout)
                except (json.JSONDecodeError, KeyError, TypeError):
                    same = False
            else:
                same = False  # csgray made a solid, OpenSCAD exported none
    return key, o_pass, c_pass, first, same

with concurrent.futures.ThreadPoolExecutor(max_workers=int(os.environ["JOBS"])) as pool:
    results = list(pool.map(one, cases))

o_n = sum(1 for r in results if r[1])
c_n = sum(1 for r in results if r[2])
both = sum(1 for r in results if r[1] and r[2])
for key, o_pass, c_pass, first, _ in results:
    if o_pass != c_pass:
        print(f"{'csgray fails' if o_pass else 'csgray passes, OpenSCAD fails'}: {key}: {first}")
print(f"tests: {len(results)}")
print(f"OpenSCAD passes: {o_n}")
print(f"csgray passes: {c_n}")
print(f"csgray passes of OpenSCAD's passes: {both} of {o_n}")
if geometry:
    solids = [r for r in results if r[4] in (True, False)]
    slow = [r for r in results if r[4] == "timeout"]
    print(f"geometry: {sum(1 for r in solids if r[4] is True)} of {len(solids)} 3-D solids agree "
          f"(OpenSCAD's export took over {geometry_timeout} s for {len(slow)} more)")
    for key, *_, same in results:
        if same is False:
            print(f"geometry differs: {key}")
sys.exit(0 if both == o_n else 1)
EOF
