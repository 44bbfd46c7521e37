#!/usr/bin/env bash
# The fixed-fraction baseline loop of the thesis (§2.5, ch. 6) on the S-shock, feature-based, p = 2:
#   mesh_k --dgsolve--> sol_k --estimate-frame--> shape_k --refine --by A1 --fraction 0.3--> mesh_k+1
# from a uniform 8x8 grid, 6 adaptations (7 solves). Checks: the L2 error falls at every step, the
# cell counts follow N -> N + 3 * split, the meshes stay 2:1 (refine reads every output back), and
# the numbers match the golden table tests/golden/refine/sshock_p2_fraction.json:
#   cells, dofs, flagged, added_by_balance: exactly; l2_error: |a - b| <= 1e-12 + 1e-6 |b|.
# Regenerate the golden after an intended change with  REFINE_LOOP_UPDATE_GOLDEN=1 bash refine_loop.sh
set -euo pipefail
SRC=${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
BIN=${QUADAPT_BIN_DIR:-}
[ -n "$BIN" ] && PATH="$BIN:$PATH"
for t in dgsolve estimate-frame refine; do
  command -v "$t" >/dev/null || { echo "SKIPPED: $t not built"; exit 0; }
done
CASE="$SRC/examples/cases/sshock.json"
[ -f "$CASE" ] || { echo "SKIPPED: $CASE missing"; exit 0; }
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

python3 - "$T" "$STEPS" "$GOLDEN" "${REFINE_LOOP_UPDATE_GOLDEN:-0}" <<'EOF'
import json, sys, os
T, steps, golden, update = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4] == "1"
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
         "by": "A1", "tolerance": {"l2_error": {"abs": 1e-12, "rel": 1e-6}, "integers": "exact"},
         "steps": rows}
if update:
    with open(golden, "w") as f:
        json.dump(table, f, indent=1)
        f.write("\n")
    print("golden written:", golden)
    sys.exit(0)
if not os.path.exists(golden):
    sys.exit("no golden table %s (run with REFINE_LOOP_UPDATE_GOLDEN=1)" % golden)
ref = json.load(open(golden))["steps"]
assert len(ref) == len(rows), "golden has %d steps, run has %d" % (len(ref), len(rows))
bad = []
for r, g in zip(rows, ref):
    for key, v in g.items():
        if key == "l2_error":
            if abs(r[key] - v) > 1e-12 + 1e-6 * abs(v):
                bad.append("step %d %s: %.10e vs golden %.10e" % (r["step"], key, r[key], v))
        elif r.get(key) != v:
            bad.append("step %d %s: %s vs golden %s" % (r["step"], key, r.get(key), v))
if bad:
    sys.exit("golden mismatch:\n  " + "\n  ".join(bad))
print("refine loop: L2 error falls at every step; matches the golden table")
EOF
