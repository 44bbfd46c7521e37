#!/usr/bin/env bash
# Accuracy of the DWR estimate and order of the functional error (docs/adjoint.md): unit-square
# n x n grids, n = 4..32, p = 1..3, three smooth cases (written below):
#   compatible    diffusion + advection, functional on the natural side x = 1 whose end points
#                 meet Dirichlet sides where u = 0 (smooth adjoint)
#   incompatible  same PDE and boundaries, u != 0 at those corners (adjoint corner singularity)
#   advection     pure advection, inflow data, functional on the outflow side x = 1
# usage: bench/adjoint/accuracy.sh [BIN_DIR]   -> markdown table on stdout
set -euo pipefail
SRC=$(cd "$(dirname "$0")/../.." && pwd)
BIN=${1:-$SRC/build/bin}
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
cat >"$W/compatible.json" <<'J'
{"exact": "sin(pi*y)*(exp(x) + 0.5*cos(2*x-y))", "diffusion": [[0.3, 0.1], [0.1, 0.5]], "advection": [1.0, -0.7],
 "dirichlet": ["left", "top", "bottom"], "functional": {"boundary": "right"}}
J
cat >"$W/incompatible.json" <<'J'
{"exact": "sin(2*x+0.5)*cos(3*y-0.2) + exp(x*y)", "diffusion": [[0.3, 0.1], [0.1, 0.5]], "advection": [1.0, -0.7],
 "dirichlet": ["left", "top", "bottom"], "functional": {"boundary": "right"}}
J
cat >"$W/advection.json" <<'J'
{"exact": "sin(2*x+0.5)*cos(3*y-0.2) + exp(x*y)", "advection": [1.0, 0.6], "functional": {"boundary": "right"}}
J
for n in 4 8 16 32; do python3 "$SRC/tests/golden/refine/make_square.py" $n "$W/sq$n.msh" bare; done
echo "| case | p | n | \|J(u) - J_H(u_H)\| | rate | estimate -psi^T R | effectivity |"
echo "|---|---|---|---|---|---|---|"
for case in compatible incompatible advection; do
  for p in 1 2 3; do
    prev=""
    for n in 4 8 16 32; do
      "$BIN/dgsolve" -q "$W/sq$n.msh" -c "$W/$case.json" -p $p -o "$W/sol.msh" --solver umfpack
      "$BIN/adjoint" -q "$W/sol.msh" -c "$W/$case.json" -o "$W/dwr.msh" --solver umfpack
      line=$(python3 - "$W/dwr.json" "$prev" <<'PY'
import json, math, sys
r = json.load(open(sys.argv[1]))
e = r["functional_error"]
rate = "" if not sys.argv[2] else "%.2f" % math.log2(float(sys.argv[2]) / e)
print("%.3e|%s|%.3e|%.4f|%r" % (e, rate, r["functional_error_estimate"], r["effectivity"], e))
PY
)
      IFS='|' read -r err rate est eff raw <<<"$line"
      echo "| $case | $p | $n | $err | $rate | $est | $eff |"
      prev=$raw
    done
  done
done
