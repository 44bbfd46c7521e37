#!/usr/bin/env bash
# One-step loops of every adaptive method through Makefile.cases (feature: fixed-fraction, lpcvt,
# bamg; goal: fixed-fraction, lpcvt) on the smooth case from an 8x8 grid: each step's files, the
# table's tool columns, the DWR estimate in goal mode, and a resume after deleting a middle file.
# A missing tool fails the test; a missing gmsh program is a ctest skip (exit 77).
set -euo pipefail
SRC="${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}"
BIN="${QUADAPT_BIN_DIR:-$SRC/build/bin}"
export PATH="$BIN:$PATH"
command -v dgsolve >/dev/null || { echo "FAIL: dgsolve not built (tools must be on PATH)" >&2; exit 1; }
command -v gmsh >/dev/null || { echo "SKIPPED: gmsh (the program) not installed"; exit 77; }
PY=/usr/bin/python3; [ -x "$PY" ] || PY=python3
T="$(mktemp -d)"; trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
gmsh -2 -format msh41 -setnumber N 8 -o "$T/sq8.msh" "$SRC/examples/geometry/unit_square.geo" >/dev/null 2>&1 \
  || fail "gmsh could not mesh the square"

ran=0
run() {  # run METHOD MODE TOOLS...: one adaptation, then checks
  local method="$1" mode="$2"; shift 2
  local t
  for t in "$@"; do
    command -v "$t" >/dev/null || { echo "FAIL: $method/$mode: $t not built" >&2; exit 1; }
  done
  local out="$T/$method-$mode"
  make --no-print-directory -f "$SRC/Makefile.cases" loop BIN="$BIN" CASE="$SRC/examples/cases/smooth.json" \
    MESH="$T/sq8.msh" P=1 METHOD="$method" MODE="$mode" STEPS=1 OUT="$out" PICTURES=no > "$out.log" 2>&1 \
    || { cat "$out.log" >&2; fail "$method/$mode loop failed"; }
  # the next mesh: adapted.msh, or bamgquad's quad.msh itself (SMOOTH_BAMG=no, the default)
  [ -s "$out/step-0/adapted.msh" ] || { [ "$method" = bamg ] && [ -s "$out/step-0/quad.msh" ]; } \
    || fail "$method/$mode: step-0's next mesh missing"
  [ -s "$out/step-1/mesh.msh" ] && [ -s "$out/step-1/sol.msh" ] || fail "$method/$mode: step files missing"
  "$PY" - "$out/convergence.csv" "$method" "$mode" <<'PYEOF' || fail "$method/$mode: table"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
method, mode = sys.argv[2], sys.argv[3]
assert len(rows) == 2, rows
r0 = rows[0]
need = {"fixed-fraction": ["t_refine"], "lpcvt": ["t_size_solve", "t_lpcvt", "t_recombine", "t_quadsmooth"],
        "bamg": ["t_size_solve", "t_bamgquad"]}[method]
if method != "fixed-fraction" or mode == "feature":
    need += ["t_estimate_frame"]
if mode == "goal":
    need += ["t_adjoint", "functional_error_estimate"]
    assert rows[1]["functional_error_estimate"] != "", "the final step has no DWR estimate"
for c in need:
    assert r0[c] != "", "%s empty in step 0" % c
if method in ("lpcvt", "bamg"):
    # complexity honesty (docs/design.md §4): the new mesh's DOFs near size-solve's target
    tc, dofs = float(r0["target_complexity"]), float(rows[1]["dofs"])
    print("%s/%s: DOFs/target = %.3f" % (method, mode, dofs / tc))
    # measured at 83a2a20: lpcvt 1.104 (feature and goal), bamg 0.958; was (0.6, 1.6), which a
    # wrong (p+1)^2 factor (x 4/9 or 9/4 at p = 1 vs 2) could pass
    assert 0.85 < dofs / tc < 1.2, "DOFs %g vs target %g" % (dofs, tc)
PYEOF
  ran=$((ran + 1))
}
run fixed-fraction feature estimate-frame refine
run lpcvt feature estimate-frame size-solve lpcvt recombine quadsmooth
run bamg feature estimate-frame size-solve bamgquad
run fixed-fraction goal adjoint refine
run lpcvt goal estimate-frame adjoint size-solve lpcvt recombine quadsmooth

# resume in the middle of a step: delete lpcvt's triangles -> lpcvt, recombine, quadsmooth and the
# step-1 solve run again, nothing before them
if [ -d "$T/lpcvt-feature/step-0" ]; then
  rm "$T/lpcvt-feature/step-0/tri.msh"
  make --no-print-directory -f "$SRC/Makefile.cases" loop BIN="$BIN" CASE="$SRC/examples/cases/smooth.json" \
    MESH="$T/sq8.msh" P=1 METHOD=lpcvt MODE=feature STEPS=1 OUT="$T/lpcvt-feature" PICTURES=no > "$T/resume.log" 2>&1 \
    || { cat "$T/resume.log" >&2; fail "resume failed"; }
  for t in lpcvt recombine quadsmooth; do grep -q "step-0: $t " "$T/resume.log" || fail "resume: $t not rerun"; done
  grep -q "step-1: dgsolve " "$T/resume.log" || fail "resume: step-1 solve not rerun"
  for t in dgsolve estimate-frame size-solve; do
    grep -q "step-0: $t " "$T/resume.log" && fail "resume: step-0 $t rerun"
  done
fi
# FIT_FRAME=meshed: quadsmooth fits the frame lpcvt wrote (meshed-frame.msh), recorded in the run's
# parameters, so the same OUT with the default is refused
out="$T/lpcvt-fit"
make --no-print-directory -f "$SRC/Makefile.cases" loop BIN="$BIN" CASE="$SRC/examples/cases/smooth.json" \
  MESH="$T/sq8.msh" P=1 METHOD=lpcvt MODE=feature STEPS=1 OUT="$out" PICTURES=no FIT_FRAME=meshed > "$out.log" 2>&1 \
  || { cat "$out.log" >&2; fail "FIT_FRAME=meshed loop failed"; }
[ -s "$out/step-0/meshed-frame.msh" ] || fail "FIT_FRAME=meshed: no meshed-frame.msh"
"$PY" - "$out/step-0/adapted.json" "$out/loop.json" <<'PYEOF' || fail "FIT_FRAME=meshed: quadsmooth's frame"
import json, sys
rep, loop = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
assert rep["command"].endswith("--frame " + sys.argv[1].replace("adapted.json", "meshed-frame.msh")), rep["command"]
assert json.dumps(loop).count('"fit_frame": "meshed"') == 1, loop
PYEOF
rc=0
make --no-print-directory -f "$SRC/Makefile.cases" loop BIN="$BIN" CASE="$SRC/examples/cases/smooth.json" \
  MESH="$T/sq8.msh" P=1 METHOD=lpcvt MODE=feature STEPS=1 OUT="$out" PICTURES=no > "$out-raw.log" 2>&1 || rc=$?
[ $rc -ne 0 ] && grep -q "fit_frame" "$out-raw.log" || fail "FIT_FRAME changed on the same OUT: exit $rc, $(cat "$out-raw.log")"
ran=$((ran + 1))
# WALLS=fixed: passed to quadsmooth (its report's options) and recorded in the run's parameters
out="$T/lpcvt-walls"
make --no-print-directory -f "$SRC/Makefile.cases" loop BIN="$BIN" CASE="$SRC/examples/cases/smooth.json" \
  MESH="$T/sq8.msh" P=1 METHOD=lpcvt MODE=feature STEPS=1 OUT="$out" PICTURES=no WALLS=fixed > "$out.log" 2>&1 \
  || { cat "$out.log" >&2; fail "WALLS=fixed loop failed"; }
"$PY" - "$out/step-0/adapted.json" "$out/loop.json" "$T/lpcvt-fit/step-0/adapted.json" <<'PYEOF' || fail "WALLS=fixed: quadsmooth's walls"
import json, sys
rep, loop, dflt = (json.load(open(f)) for f in sys.argv[1:])
assert rep["options"]["walls"] == "fixed" and rep["sliding_wall_nodes"] == 0, rep["options"]
assert dflt["options"]["walls"] == "slide" and dflt["sliding_wall_nodes"] > 0, dflt["options"]
assert json.dumps(loop).count('"walls": "fixed"') == 1, loop
PYEOF
ran=$((ran + 1))
# FIT_FRAME=capped: quadsmooth --fit-frame capped on size-solve's frame, recorded in the run's parameters
out="$T/lpcvt-capped"
make --no-print-directory -f "$SRC/Makefile.cases" loop BIN="$BIN" CASE="$SRC/examples/cases/smooth.json" \
  MESH="$T/sq8.msh" P=1 METHOD=lpcvt MODE=feature STEPS=1 OUT="$out" PICTURES=no FIT_FRAME=capped > "$out.log" 2>&1 \
  || { cat "$out.log" >&2; fail "FIT_FRAME=capped loop failed"; }
"$PY" - "$out/step-0/adapted.json" "$out/loop.json" <<'PYEOF' || fail "FIT_FRAME=capped: quadsmooth's fit frame"
import json, sys
rep, loop = (json.load(open(f)) for f in sys.argv[1:])
assert rep["options"]["fit_frame"] == "capped" and rep["fit_frame"]["mode"] == "capped", rep["options"]
assert rep["command"].split("--frame ")[1].split()[0].endswith("step-0/frame.msh"), rep["command"]
assert json.dumps(loop).count('"fit_frame": "capped"') == 1, loop
PYEOF
ran=$((ran + 1))
# C_MAX / R_MAX (goal mode) and SIZE_GRADATION: passed to size-solve and recorded in the run's parameters
out="$T/goal-cmax"
make --no-print-directory -f "$SRC/Makefile.cases" loop BIN="$BIN" CASE="$SRC/examples/cases/sshock-advection.json" \
  MESH="$T/sq8.msh" P=1 METHOD=lpcvt MODE=goal STEPS=1 OUT="$out" PICTURES=no C_MAX=2 R_MAX=10 SIZE_GRADATION=1.5 \
  > "$out.log" 2>&1 || { cat "$out.log" >&2; fail "C_MAX=2 goal loop failed"; }
"$PY" - "$out/step-0/frame.json" "$out/loop.json" <<'PYEOF' || fail "C_MAX / R_MAX / SIZE_GRADATION: size-solve's options"
import json, sys
rep, loop = (json.load(open(f)) for f in sys.argv[1:])
assert "--r-max 10 --c-max 2 --gradation 1.5" in rep["command"], rep["command"]
s = json.dumps(loop)
assert s.count('"c_max": "2"') == 1 and s.count('"r_max": "10"') == 1 and s.count('"size_gradation": "1.5"') == 1, loop
PYEOF
ran=$((ran + 1))
# the study rules pass the loop's knobs a study varies (MAX_ANISOTROPY and START_JITTER were
# accepted by the variable check and silently left out of every study run)
for target in sshock-feature-p2-lpcvt "$T/study-runs/sshock-goal/p2-lpcvt-seed2/loop.done" \
              "$T/study-runs/sshock-goal/p2-bamg-seed2/loop.done" loop; do
  # one loop's variables for `loop`, the studies' for the study targets (each kind is refused with
  # the other, cli.messages)
  if [ "$target" = loop ]; then own=(CASE=c.json OUT="$T/o"); else own=(RUNS="$T/study-runs"); fi
  cmd=$(make -n -s -f "$SRC/Makefile.cases" "$target" "${own[@]}" \
        MAX_ANISOTROPY=4 START_JITTER=0.1 ERROR_MODEL=thesis 2>&1 | grep run-loop)
  grep -q -- '--max-anisotropy "4"' <<<"$cmd" && grep -q -- '--start-jitter "0.1"' <<<"$cmd" &&
    grep -q -- '--error-model "thesis"' <<<"$cmd" ||
    { echo "FAIL: $target does not pass MAX_ANISOTROPY / START_JITTER / ERROR_MODEL: $cmd" >&2; exit 1; }
done
echo "loop methods CLI: $ran loops checked"
