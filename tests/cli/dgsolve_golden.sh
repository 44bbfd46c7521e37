#!/usr/bin/env bash
# Golden test of `dgsolve`: the thesis's cases (S-shock eqs. 6.2-6.4 and boundary layer eq. 6.5,
# feature and goal variants) on the 16x16 unit-square grid for p = 1, 2, 3. The stored numbers
# (tests/golden/dg/<case>.json) are compared with |a - b| <= 1e-13 + 1e-8 |b| (the absolute part
# covers functional_error, a difference of two numbers near 0.5625).
# Regenerate after an intended change of the discretisation: DG_UPDATE_GOLDEN=1 bash this-script.
set -euo pipefail
SRC=${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
BIN=${QUADAPT_BIN_DIR:-}
[ -n "$BIN" ] && PATH="$BIN:$PATH"
command -v dgsolve >/dev/null || { echo "FAIL: dgsolve not built (tools must be on PATH)" >&2; exit 1; }
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
GOLD="$SRC/tests/golden/dg"
# The canonical 16x16 grid (examples/meshes/square16.msh); a generated copy if it is absent.
if [ -f "$SRC/examples/meshes/square16.msh" ]; then
  cp "$SRC/examples/meshes/square16.msh" "$T/square16.msh"
else
  python3 "$SRC/bench/dg/make_mesh.py" 16 16 "$T/square16.msh"
fi

status=0
for case in sshock boundary-layer sshock-advection boundary-layer-advection; do
  for p in 1 2 3; do
    dgsolve -q "$T/square16.msh" -c "$SRC/examples/cases/$case.json" -p "$p" -o "$T/$case-p$p.msh"
  done
  # Keep the figures that define the result (not the provenance or the solver's rounding).
  python3 - "$T" "$case" >"$T/$case.json" <<'EOF'
import json, sys
T, case = sys.argv[1:3]
keys = ["cells", "p", "dofs", "hanging_faces", "l2_error", "functional", "functional_exact", "functional_error"]
out = {}
for p in (1, 2, 3):
    r = json.load(open(f"{T}/{case}-p{p}.json"))
    out[f"p{p}"] = {k: r[k] for k in keys}
print(json.dumps(out, indent=2))
EOF
  if [ "${DG_UPDATE_GOLDEN:-0}" = 1 ]; then
    cp "$T/$case.json" "$GOLD/$case.json"
    echo "updated $GOLD/$case.json"
    continue
  fi
  if [ -f "$SRC/tests/cli/golden_compare.py" ]; then
    python3 "$SRC/tests/cli/golden_compare.py" "$T/$case.json" "$GOLD/$case.json" --rtol 1e-8 --atol 1e-13 ||
      { echo "FAIL: $case differs from the golden numbers" >&2; status=1; }
  else
    python3 - "$T/$case.json" "$GOLD/$case.json" <<'EOF' || { echo "FAIL: $case differs" >&2; status=1; }
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
bad = [(p, k, a[p][k], b[p][k]) for p in b for k in b[p]
       if not abs(a[p][k] - b[p][k]) <= 1e-13 + 1e-8 * abs(b[p][k])]
for x in bad: print("differs:", *x)
sys.exit(1 if bad else 0)
EOF
  fi
done
[ $status = 0 ] && echo "dgsolve golden: OK"
exit $status
