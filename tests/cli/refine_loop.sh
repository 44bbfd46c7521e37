#!/usr/bin/env bash
# The fixed-fraction baseline loop of the thesis (§2.5, ch. 6) on the S-shock, feature-based, p = 2:
#   mesh_k --dgsolve--> sol_k --estimate-frame--> shape_k --refine --by A1 --fraction 0.3--> mesh_k+1
# from a uniform 8x8 grid, 6 adaptations (7 solves). Checks: the L2 error falls at every step, the
# cell counts follow N -> N + 3 * split, the meshes stay 2:1 (refine reads every output back), and
# the numbers match the golden table tests/golden/refine/sshock_p2_fraction.json:
#   cells, dofs, flagged, added_by_balance, hanging_nodes: exactly; l2_error: |a - b| <= 1e-12 + 1e-6 |b|
# (tests/cli/golden_compare.py --rtol 1e-6 --atol 1e-12).
# Regenerate the golden after an intended change with  REFINE_LOOP_UPDATE_GOLDEN=1 bash refine_loop.sh
set -euo pipefail
SRC=${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
BIN=${QUADAPT_BIN_DIR:-}
[ -n "$BIN" ] && PATH="$BIN:$PATH"
for t in dgsolve estimate-frame refine; do
  command -v "$t" >/dev/null || { echo "FAIL: $t not built (tools must be on PATH)" >&2; exit 1; }
done
CASE="$SRC/examples/cases/sshock.json"
[ -f "$CASE" ] || { echo "FAIL: $CASE missing" >&2; exit 1; }
GOLDEN="$SRC/tests/golden/refine/sshock_p2_fraction.json"
STEPS=6 P=2 FRACTION=0.3 BY=A1 N0=8
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT

python3 "$SRC/tests/golden/refine/make_square.py" "$N0" "$T/mesh-0.msh" bare
for ((k = 0; k <= STEPS; ++k)); do
  dgsolve -q "$T/mesh-$k.msh" -c "$CASE" -p "$P" -o "$T/sol-$k.msh"
  if ((k < STEPS)); then
    estimate-frame -q "$T/sol-$k.msh" -o "$T/shape-$k.msh"
    refine -q "$T/shape-$k.msh" --by "$BY" --fraction "$FRACTION" -o "$T/mesh-$((k + 1)).msh"
  fi
done

python3 - "$T" "$STEPS" <<'EOF'
import json, sys, os
T, steps = sys.argv[1], int(sys.argv[2])
rows = []
for k in range(steps + 1):
    s = json.load(open(os.path.join(T, "sol-%d.json" % k)))
    row = {"step": k, "cells": s["cells"], "dofs": s["dofs"], "l2_error": s["l2_error"]}
    if k < steps:
        r = json.load(open(os.path.join(T, "mesh-%d.json" % (k + 1))))
        assert r["cells_before"] == s["cells"], (k, r["cells_before"], s["cells"])
        assert r["cells"] == r["cells_before"] + 3 * r["split"], r
        row.update(flagged=r["flagged"], added_by_balance=r["added_by_balance"],
                   hanging_nodes=r["hanging_nodes"])
    rows.append(row)
print("step  cells   dofs      l2_error   flagged  balance  hanging")
for r in rows:
    print("%4d %6d %6d  %.6e  %7s  %7s  %7s" % (r["step"], r["cells"], r["dofs"], r["l2_error"],
          r.get("flagged", ""), r.get("added_by_balance", ""), r.get("hanging_nodes", "")))
for a, b in zip(rows, rows[1:]):
    assert b["l2_error"] < a["l2_error"], "L2 error did not fall at step %d: %g -> %g" % (
        b["step"], a["l2_error"], b["l2_error"])
table = {"case": "examples/cases/sshock.json", "p": 2, "start": "uniform 8x8", "fraction": 0.3,
         "by": "A1", "tolerance": "golden_compare.py --rtol 1e-6 --atol 1e-12 (integers exact)",
         "steps": rows}
with open(os.path.join(T, "table.json"), "w") as f:
    json.dump(table, f, indent=1)
    f.write("\n")
EOF
if [ "${REFINE_LOOP_UPDATE_GOLDEN:-0}" = 1 ]; then
  cp "$T/table.json" "$GOLDEN"
  echo "golden written: $GOLDEN"
  exit 0
fi
# integers differ by >= 1 > 1e-12 + 1e-6 * |n| for n < 1e6: compared exactly
python3 "$SRC/tests/cli/golden_compare.py" "$T/table.json" "$GOLDEN" --rtol 1e-6 --atol 1e-12
echo "refine loop: L2 error falls at every step; matches the golden table"
