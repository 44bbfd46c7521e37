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
  # Independent bounds (tests/cli/dg_exact.py: J(u_h) and J'(u_h)(u - u_h) from the solution file,
  # J(u) by Python quadrature of the exact solution; the dwr values from the output file):
  #  - functional_error_signed = J(u) - J(u_h) of those;
  #  - sum_eta = the sum of the file's dwr values, and |functional_error_estimate| <= sum_eta
  #    (the estimate is the sum of the signed eta_K, the map their absolute values);
  #  - the DWR estimates the linearised error J'(u_h)(u - u_h) = integral over x = 1 of
  #    2 u_h (u - u_h) (the adjoint linearises J = integral of u^2 at u_h). In the boundary-layer
  #    cases u = 0 on x = 1, so J'(u_h)(u - u_h) = -2 J(u_h) = 2 (J(u) - J(u_h)) exactly: their
  #    effectivity tends to 2, not 1 (the frozen 1.3-2.3 are this, plus the adjoint's own error).
  #    estimate / J'(u_h)(u - u_h) must lie in [0.5, 1.5]: the p+1 adjoint resolves neither the
  #    S-shock (width ~1/24) nor the layers (eps = 0.005) on cells of 1/16, so the adjoint error
  #    R(u_h; z - z_h) stays (measured 0.65-0.70 for the diffusive boundary layer, whose adjoint is
  #    a boundary layer at x = 1 too; 0.92-1.13 pure advection; S-shock 1.06-1.22); the estimate
  #    has the sign of the true error. A factor 2 in the estimate leaves the window for both
  #    pure-advection cases, and the smooth case below catches any factor.
  python3 - "$T" "$case" "$SRC" <<'EOF' || { echo "FAIL: $case: an independent bound does not hold" >&2; status=1; }
import json, subprocess, sys
T, case, SRC = sys.argv[1:4]
bad = []
for p in (1, 2, 3):
    r = json.load(open(f"{T}/{case}-dwr{p}.json"))
    g = json.load(open(f"{T}/{case}.json"))[f"p{p}"]
    x = json.loads(subprocess.check_output(["python3", f"{SRC}/tests/cli/dg_exact.py", f"{T}/{case}-sol{p}.msh",
                                            f"{SRC}/examples/cases/{case}.json"]))
    E = x["functional_exact"] - x["functional"]
    lin = x["functional_error_linearized"]
    est = r["functional_error_estimate"]
    print(f"{case} p={p}: J(u) - J(u_h) = {E:.6e}, linearised {lin:.6e}, estimate {est:.6e}, "
          f"estimate / linearised {est / lin:.3f}, effectivity {est / E:.3f}")
    if not abs(r["functional_error_signed"] - E) <= 1e-12 + 1e-8 * abs(E):
        bad.append(f"p={p}: functional_error_signed {r['functional_error_signed']!r} != J(u) - J(u_h) = {E!r}")
    s = sum(g["dwr"])
    if not abs(r["sum_eta"] - s) <= 1e-9 * s:
        bad.append(f"p={p}: sum_eta {r['sum_eta']!r} != sum of the dwr field {s!r}")
    if not abs(est) <= r["sum_eta"] * (1 + 1e-12):
        bad.append(f"p={p}: |estimate| {abs(est)!r} > sum_eta {r['sum_eta']!r}")
    if not 0.5 <= est / lin <= 1.5:
        bad.append(f"p={p}: estimate / linearised error = {est / lin:.4f} outside [0.5, 1.5]")
    if not est * E > 0:
        bad.append(f"p={p}: the estimate {est!r} and the error {E!r} differ in sign")
for b in bad:
    print("FAIL:", case, b)
sys.exit(1 if bad else 0)
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
# An independent bound that any factor in the estimate fails: on a smooth case (examples/cases/
# smooth.json, full anisotropic diffusion, oblique advection) u and the adjoint z are resolved, the
# p+1 adjoint's error R(u_h; z - z_h) and the quadratic remainder of J are of higher order, so the
# effectivity is 1 + o(1): measured 0.982, 0.993, 1.0006 at p = 1, 2, 3 on the 16x16 grid (0.992,
# 0.998, 1.0015 on 32x32). Required: |effectivity - 1| <= 0.03, with J(u) - J(u_h) from the file.
if [ "${ADJ_UPDATE_GOLDEN:-0}" != 1 ]; then
  for p in 1 2 3; do
    dgsolve -q "$T/square16.msh" -c "$SRC/examples/cases/smooth.json" -p "$p" -o "$T/smooth-sol$p.msh"
    adjoint -q "$T/smooth-sol$p.msh" -c "$SRC/examples/cases/smooth.json" -o "$T/smooth-dwr$p.msh" --rtol 1e-12
  done
  python3 - "$T" "$SRC" <<'EOF' || { echo "FAIL: smooth: effectivity not within 0.03 of 1" >&2; status=1; }
import json, subprocess, sys
T, SRC = sys.argv[1:3]
bad = []
for p in (1, 2, 3):
    r = json.load(open(f"{T}/smooth-dwr{p}.json"))
    x = json.loads(subprocess.check_output(["python3", f"{SRC}/tests/cli/dg_exact.py", f"{T}/smooth-sol{p}.msh",
                                            f"{SRC}/examples/cases/smooth.json"]))
    E = x["functional_exact"] - x["functional"]
    eff = r["functional_error_estimate"] / E
    print(f"smooth p={p}: J(u) - J(u_h) = {E:.6e} (report {r['functional_error_signed']:.6e}), "
          f"estimate {r['functional_error_estimate']:.6e}, effectivity {eff:.4f}")
    if not abs(eff - 1) <= 0.03:
        bad.append(f"p={p}: effectivity {eff:.4f}")
    # E is a difference of two numbers near J(u) = 3.34: rounding and quadrature at 1e-12 J(u)
    if not abs(r["functional_error_signed"] - E) <= 1e-12 * abs(x["functional_exact"]) + 1e-8 * abs(E):
        bad.append(f"p={p}: functional_error_signed {r['functional_error_signed']!r} != {E!r}")
for b in bad:
    print("FAIL: smooth", b)
sys.exit(1 if bad else 0)
EOF
fi
[ $status = 0 ] && echo "adjoint golden: OK"
exit $status
