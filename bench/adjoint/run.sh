#!/usr/bin/env bash
# Benchmark: adjoint wall time vs dgsolve wall time on the same mesh and p (issue 4: adjoint at
# most 2x dgsolve). Unit-square n x n grids with ~2e4 and ~6.5e4 coarse DOFs, p = 1..3, the
# goal-oriented cases (advection only) and the diffusive thesis variants; REPS runs each, medians.
# Also dgsolve at degree p+1 on the same mesh: the size of the adjoint's system, for reference.
# usage: bench/adjoint/run.sh [BIN_DIR] [OUT_DIR]     env: REPS (3), THREADS (2), CASES, SIZES
# Writes OUT_DIR/adjoint-bench.csv and prints a markdown table.
set -euo pipefail
SRC=$(cd "$(dirname "$0")/../.." && pwd)
BIN=${1:-$SRC/build/bin}
OUT=${2:-$SRC/bench/adjoint/out}
REPS=${REPS:-3}
THREADS=${THREADS:-2}
CASES=${CASES:-"sshock-advection boundary-layer-advection sshock boundary-layer-goal-thesis"}
SIZES=${SIZES:-"20000 65000"}
mkdir -p "$OUT"
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
CSV="$OUT/adjoint-bench.csv"
echo "case,p,target_dofs,n,dofs,fine_dofs,dgsolve_s,adjoint_s,ratio,dg_solver,adj_solver,adj_iterations,adj_assemble_s,adj_solve_s,effectivity,dgsolve_p1_s,ratio_p1" >"$CSV"
for case in $CASES; do
  for p in 1 2 3; do
    for D in $SIZES; do
      n=$(python3 -c "import math; print(round(math.sqrt($D / ($p + 1) ** 2)))")
      [ -f "$W/sq$n.msh" ] || python3 "$SRC/tests/golden/refine/make_square.py" "$n" "$W/sq$n.msh" bare
      for r in $(seq "$REPS"); do
        OMP_NUM_THREADS=$THREADS "$BIN/dgsolve" -q "$W/sq$n.msh" -c "$SRC/examples/cases/$case.json" -p "$p" -o "$W/sol.msh" --report "$W/dg$r.json"
        OMP_NUM_THREADS=$THREADS "$BIN/adjoint" -q "$W/sol.msh" -c "$SRC/examples/cases/$case.json" -o "$W/dwr.msh" --report "$W/adj$r.json"
        # reference: a primal solve of degree p+1 on the same mesh (the adjoint's system size)
        OMP_NUM_THREADS=$THREADS "$BIN/dgsolve" -q "$W/sq$n.msh" -c "$SRC/examples/cases/$case.json" -p $((p + 1)) -o "$W/solp1.msh" --report "$W/dgp$r.json"
      done
      python3 - "$W" "$REPS" "$case" "$p" "$D" "$n" >>"$CSV" <<'PY'
import json, statistics, sys
W, reps, case, p, D, n = sys.argv[1], int(sys.argv[2]), *sys.argv[3:]
dg = [json.load(open(f"{W}/dg{r}.json")) for r in range(1, reps + 1)]
ad = [json.load(open(f"{W}/adj{r}.json")) for r in range(1, reps + 1)]
d1 = [json.load(open(f"{W}/dgp{r}.json")) for r in range(1, reps + 1)]
med = lambda xs: statistics.median(xs)
tdg, tad = med([d["time_s"] for d in dg]), med([a["time_s"] for a in ad])
a = ad[-1]
print(",".join(str(x) for x in [case, p, D, n, a["dofs"], a["fine_dofs"], "%.3f" % tdg, "%.3f" % tad,
      "%.2f" % (tad / tdg), dg[-1]["solver"], a["solver"], a["solver_iterations"],
      "%.3f" % med([x["timings"]["fine_assemble"] for x in ad]),
      "%.3f" % med([x["timings"]["adjoint_solve"] for x in ad]),
      "%.3f" % a["effectivity"] if a["effectivity"] is not None else "nan",
      "%.3f" % med([d["time_s"] for d in d1]), "%.2f" % (tad / med([d["time_s"] for d in d1]))]))
PY
      tail -1 "$CSV" >&2
    done
  done
done
python3 - "$CSV" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print("| case | p | DOFs | fine DOFs | dgsolve s | adjoint s | ratio | adjoint solver (its.) | dgsolve at p+1 s | adjoint / dgsolve(p+1) |")
print("|---|---|---|---|---|---|---|---|---|---|")
for r in rows:
    print(f"| {r['case']} | {r['p']} | {r['dofs']} | {r['fine_dofs']} | {r['dgsolve_s']} | {r['adjoint_s']} | "
          f"{r['ratio']} | {r['adj_solver']} ({r['adj_iterations']}) | {r['dgsolve_p1_s']} | {r['ratio_p1']} |")
print("\nmax ratio: %.2f" % max(float(r["ratio"]) for r in rows))
PY
