#!/usr/bin/env bash
# Golden test of `adjoint`: the DWR maps of the goal-oriented thesis cases (S-shock, advection
# only, thesis section 6.4; boundary layer as PHiLiP runs it, pure advection, section 6.5, and as
# the thesis text states it, with diffusion and Dirichlet data everywhere) on the
# 16x16 unit-square grid for p = 1, 2, 3. Stored per case and p (tests/golden/adjoint/<case>.json):
# the report's functional figures and the per-cell 'dwr' values in cell order, compared with
# |a - b| <= atol + 1e-6 |b|, atol = 1e-9 x the largest eta of that map (the tiny eta far from the
# functional's domain of influence are noise at the linear solver's tolerance, pinned to 1e-12).
# Regenerate after an intended change of the discretisation: ADJ_UPDATE_GOLDEN=1 bash this-script.
set -euo pipefail
SRC=${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
BIN=${QUADAPT_BIN_DIR:-}
[ -n "$BIN" ] && PATH="$BIN:$PATH"
for t in adjoint dgsolve; do command -v $t >/dev/null || { echo "FAIL: $t not built (tools must be on PATH)" >&2; exit 1; }; done
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
GOLD="$SRC/tests/golden/adjoint"
python3 "$SRC/tests/golden/refine/make_square.py" 16 "$T/square16.msh" bare

status=0
for case in sshock-advection boundary-layer-advection boundary-layer-goal-thesis; do
  for p in 1 2 3; do
    dgsolve -q "$T/square16.msh" -c "$SRC/examples/cases/$case.json" -p "$p" -o "$T/$case-sol$p.msh"
    adjoint -q "$T/$case-sol$p.msh" -c "$SRC/examples/cases/$case.json" -o "$T/$case-dwr$p.msh" --rtol 1e-12
  done
  python3 - "$T" "$case" >"$T/$case.json" <<'EOF'
import json, re, sys
T, case = sys.argv[1:3]
keys = ["cells", "p", "fine_dofs", "functional", "functional_exact", "functional_error_signed",
        "functional_error_estimate", "sum_eta", "effectivity"]
out = {}
for p in (1, 2, 3):
    r = json.load(open(f"{T}/{case}-dwr{p}.json"))
    text = open(f"{T}/{case}-dwr{p}.msh").read()
    body = re.search(r'\$ElementData\n1\n"dwr"\n(.*?)\$EndElementData', text, re.S).group(1).split("\n")
    n = int(body[5])
    eta = [float(l.split()[1]) for l in body[6:6 + n]]
    out[f"p{p}"] = {k: r[k] for k in keys}
    out[f"p{p}"]["dwr"] = eta
print(json.dumps(out, indent=1))
EOF
  if [ "${ADJ_UPDATE_GOLDEN:-0}" = 1 ]; then
    cp "$T/$case.json" "$GOLD/$case.json"
    echo "updated $GOLD/$case.json"
    continue
  fi
  python3 - "$T/$case.json" "$GOLD/$case.json" <<'EOF' || { echo "FAIL: $case differs from the golden DWR" >&2; status=1; }
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
bad = []
for p in b:
    scale = max(b[p]["dwr"])
    for k in b[p]:
        x, y = a[p][k], b[p][k]
        if k == "dwr":
            if len(x) != len(y):
                bad.append((p, k, "length", len(x), len(y)))
                continue
            for c, (u, v) in enumerate(zip(x, y)):
                if not abs(u - v) <= 1e-9 * scale + 1e-6 * abs(v):
                    bad.append((p, "dwr[%d]" % c, u, v))
        elif not abs(x - y) <= 1e-13 + 1e-6 * abs(y):
            bad.append((p, k, x, y))
for x in bad[:30]:
    print("differs:", *x)
sys.exit(1 if bad else 0)
EOF
done
[ $status = 0 ] && echo "adjoint golden: OK"
exit $status
