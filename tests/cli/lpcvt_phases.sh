#!/usr/bin/env bash
# CLI test: lpcvt --phases (lib/lpcvt/phases.hpp). On a 10:1 frame at 45 degrees (walls oblique
# to the lattice) lpcvt --phases 4 runs four lattice phases and keeps the one whose recombined
# mesh has the fewest irregular interior vertices (ties: the higher pair quality):
#   - the report lists the four runs and the kept index is their best by that rule;
#   - the output is byte-identical to a one-phase run at the kept phase (--lattice-phase) and to
#     the run with two threads (the phases then run two at a time), and
#     recombine on it gives exactly the irregular count the report states;
#   - the default (auto) on this small constant frame is 6 phases (the --phases 6 run), on a graded
#     frame (the curved band) one run; --phases 1 is phase 0's run;
#   - on a frame aligned with the walls every phase has the same start: one run, three skipped;
#   - --lattice-phase with --phases > 1, or out of [0, 1), is refused with one line.
set -euo pipefail
S=$QUADAPT_SOURCE_DIR
. "$S/tests/cli/lib/assert.sh"
in_temp_dir
PY=/usr/bin/python3; [ -x $PY ] || PY=python3
export OMP_NUM_THREADS=1
frame() {  # frame NAME ANGLE_DEG: 0.05 x 0.005 half-axes on a 16 x 16 background (1000 final cells)
  $PY "$S/tests/cli/lpcvt_frame.py" "$T/$1.msh" --n 16 --h1 0.05 --h2 0.005 \
    --theta "$($PY -c "import math; print(math.radians($2))")"
}
frame f45 45
frame f0 0

lpcvt -q "$T/f45.msh" -o "$T/k4.msh" --phases 4
lpcvt -q "$T/f45.msh" -o "$T/k4-t2.msh" --phases 4 --threads 2   # phases two at a time
lpcvt -q "$T/f45.msh" -o "$T/auto.msh"
lpcvt -q "$T/f45.msh" -o "$T/k6.msh" --phases 6
lpcvt -q "$T/f45.msh" -o "$T/one.msh" --phases 1
lpcvt -q "$T/f45.msh" -o "$T/zero.msh" --lattice-phase 0 0
KEPT=$($PY - "$T" <<'PY'
import json, sys
T = sys.argv[1]
r = json.load(open(f"{T}/k4.json"))
runs, kept = r["phases"], r["phase"]
assert r["options"]["phases"] == 4 and len(runs) == 4, r["options"]
assert all("irregular" in e for e in runs), runs  # oblique walls: four distinct starts
best = min(range(4), key=lambda k: (runs[k]["irregular"], -runs[k]["pair_quality"], k))
assert kept == best, (kept, best, runs)
# the phases differ: a selection that cannot choose would not be a test
assert len({(e["irregular"], round(e["pair_quality"], 9)) for e in runs}) > 1, runs
a = json.load(open(f"{T}/auto.json"))
assert a["options"]["phases"] == 6 and a["phase"] == json.load(open(f"{T}/k6.json"))["phase"], (a["options"], a.get("phase"))
assert a["metric_spread"] < 1e-9, a["metric_spread"]  # a constant frame
assert json.load(open(f"{T}/one.json"))["options"]["phases"] == 1
print(*runs[kept]["phase"], runs[kept]["irregular"])
PY
)
read -r PX PY_ IRR <<< "$KEPT"
lpcvt -q "$T/f45.msh" -o "$T/kept.msh" --lattice-phase "$PX" "$PY_"
same_bytes "$T/k4.msh" "$T/kept.msh"    # --phases 4's output is the run at its kept phase
same_bytes "$T/k4.msh" "$T/k4-t2.msh"   # the same for any thread count
same_bytes "$T/k6.msh" "$T/auto.msh"    # the default (auto) is the 6-phase run on a small constant frame
same_bytes "$T/one.msh" "$T/zero.msh"   # --phases 1 is phase (0, 0)
recombine -q "$T/k4.msh" -o "$T/k4-quad.msh"
GOT=$(meshquality "$T/k4-quad.msh" | $PY -c "import json, sys; print(json.load(sys.stdin)['irregular_interior_vertices'])")
[ "$GOT" = "$IRR" ] || fail "recombine gives $GOT irregular interior vertices, the report says $IRR"

# a graded frame (the curved band): auto runs one phase, the run of --phases 1
$PY "$S/tests/cli/lpcvt_frame.py" "$T/band.msh" --n 16 --kind band --h1 0.05
lpcvt -q "$T/band.msh" -o "$T/band-auto.msh"
lpcvt -q "$T/band.msh" -o "$T/band-one.msh" --phases 1
$PY - "$T/band-auto.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert r["options"]["phases"] == 1 and "phases" not in r and r["metric_spread"] > 0.1, (r["options"], r.get("metric_spread"))
PY
same_bytes "$T/band-auto.msh" "$T/band-one.msh"

# walls along the frame register both axes: one run, the others skipped
lpcvt -q "$T/f0.msh" -o "$T/f0.msh.out.msh" --phases 4
$PY - "$T/f0.msh.out.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
runs = r["phases"]
assert "irregular" in runs[0] and all(e.get("same_start_as_earlier") for e in runs[1:]), runs
assert r["phase"] == 0
PY

# refusals: one line naming the option, exit 2, nothing written
expect_exit 2 "--lattice-phase gives one phase" lpcvt "$T/f45.msh" -o "$T/bad.msh" --phases 4 --lattice-phase 0.5 0.5
expect_exit 2 "--lattice-phase: 1.5 is not in [0, 1)" lpcvt "$T/f45.msh" -o "$T/bad.msh" --lattice-phase 1.5 0
[ ! -e "$T/bad.msh" ] || fail "a refused lpcvt wrote its output"
echo "OK: lpcvt --phases keeps its best phase ($PX $PY_, $IRR irregular), equal to that phase's run"
