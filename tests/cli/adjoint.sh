#!/usr/bin/env bash
# CLI test of `adjoint`: DWR of a dgsolve output on a conforming and a 2:1 non-conforming mesh
# (report figures, the 'dwr' and 'psi' fields, effectivity on a smooth case), solver agreement,
# and bad input (exit 2, one line naming the file, nothing written).
set -euo pipefail
SRC=${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
BIN=${QUADAPT_BIN_DIR:-}
[ -n "$BIN" ] && PATH="$BIN:$PATH"
for t in adjoint dgsolve refine; do command -v $t >/dev/null || { echo "FAIL: $t not built (tools must be on PATH)" >&2; exit 1; }; done
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

python3 "$SRC/tests/golden/refine/make_square.py" 8 "$T/sq8.msh" bare
# Smooth case whose functional boundary (x = 1, natural) meets the Dirichlet sides where u = 0.
cat >"$T/smooth.json" <<'EOF'
{"exact": "sin(pi*y)*(exp(x) + 0.5*cos(2*x-y))", "diffusion": [[0.3, 0.1], [0.1, 0.5]],
 "advection": [1.0, -0.7], "dirichlet": ["left", "top", "bottom"], "functional": {"boundary": "right"}}
EOF

# Checks a DWR output: report keys and figures, fields in the mesh. check DWR.msh P CELLS
check() {
  python3 - "$@" <<'EOF'
import json, math, re, sys
msh, p, cells = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
r = json.load(open(msh[:-4] + ".json"))
for k in ["functional", "functional_exact", "functional_error", "functional_error_signed",
          "functional_error_estimate", "sum_eta", "effectivity", "functional_corrected", "p", "p_fine",
          "dofs", "fine_dofs", "solver", "solver_iterations", "timings", "time_s"]:
    assert k in r, "report lacks " + k
assert r["p"] == p and r["p_fine"] == p + 1 and r["cells"] == cells, r
assert r["fine_dofs"] == cells * (p + 2) ** 2 and r["dofs"] == cells * (p + 1) ** 2
assert abs(r["functional_error_signed"] - (r["functional_exact"] - r["functional"])) <= 1e-15
assert abs(r["functional_error_estimate"]) <= r["sum_eta"] * (1 + 1e-12)
assert 0.8 <= r["effectivity"] <= 1.25, "effectivity %g" % r["effectivity"]
for ph in ["read", "fine_assemble", "adjoint_solve", "write"]:
    assert ph in r["timings"], "timing of " + ph
# Fields: 'dwr' (one value per cell, sums to sum_eta), 'psi' of degree p+1, 'u' kept.
text = open(msh).read()
views = {}
for kind, body in re.findall(r"\$(ElementData|ElementNodeData)\n(.*?)\$End\1", text, re.S):
    lines = body.split("\n")
    ns = int(lines[0]); name = lines[1].strip('"')
    nr = int(lines[1 + ns]); ni = int(lines[2 + ns + nr])
    ints = [int(x) for x in lines[3 + ns + nr: 3 + ns + nr + ni]]
    rows = [l.split() for l in lines[3 + ns + nr + ni:] if l.strip()]
    views[name] = (kind, ints, rows)
assert set(["u", "psi", "dwr"]) <= set(views), sorted(views)
kind, ints, rows = views["dwr"]
assert kind == "ElementData" and ints[1] == 1 and len(rows) == cells
eta = [float(x[1]) for x in rows]
assert min(eta) >= 0 and abs(sum(eta) - r["sum_eta"]) <= 1e-12 * r["sum_eta"], (sum(eta), r["sum_eta"])
kind, ints, rows = views["psi"]
assert kind == "ElementNodeData" and len(rows) == cells
assert all(int(x[1]) == (p + 2) ** 2 for x in rows), "psi is not of degree p+1"
assert all(math.isfinite(float(v)) for x in rows for v in x[2:])
EOF
}

# --- conforming, p = 1 and 2
for p in 1 2; do
  dgsolve -q "$T/sq8.msh" -c "$T/smooth.json" -p $p -o "$T/sol$p.msh"
  adjoint -q "$T/sol$p.msh" -c "$T/smooth.json" -o "$T/dwr$p.msh"
  check "$T/dwr$p.msh" $p 64 || fail "conforming p=$p"
done

# --- the other solvers give the same estimate
for s in umfpack gmres-bilu0; do
  adjoint -q "$T/sol2.msh" -c "$T/smooth.json" -o "$T/dwr2-$s.msh" --solver $s
  python3 - "$T/dwr2.json" "$T/dwr2-$s.json" <<'EOF' || fail "solver $s differs"
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
for k in ["functional_error_estimate", "sum_eta"]:
    assert abs(a[k] - b[k]) <= 1e-8 * abs(a[k]), (k, a[k], b[k])
EOF
done

# --- the coarse degree (gmres-2level at the adjoint degree p + 1 = 3): auto = 2, reported; q = 1
# and q = 3 give the same estimate; the report says which ran
adjoint -q "$T/sol2.msh" -c "$T/smooth.json" -o "$T/dwr2-q1.msh" --coarse-degree 1
adjoint -q "$T/sol2.msh" -c "$T/smooth.json" -o "$T/dwr2-q3.msh" --coarse-degree 3
python3 - "$T/dwr2.json" "$T/dwr2-q1.json" "$T/dwr2-q3.json" <<'EOF' || fail "--coarse-degree"
import json, sys
a, b, c = (json.load(open(f)) for f in sys.argv[1:4])
assert [r["solver_coarse_degree"] for r in (a, b, c)] == [2, 1, 3], [r["solver_coarse_degree"] for r in (a, b, c)]
for r in (b, c):
    assert abs(a["functional_error_estimate"] - r["functional_error_estimate"]) <= 1e-8 * abs(a["functional_error_estimate"])
EOF

# --- non-conforming: fixed-fraction refinement by the DWR itself (the goal-oriented baseline)
refine -q "$T/dwr2.msh" --by dwr --fraction 0.3 -o "$T/nc.msh"
cells=$(python3 -c "import json; print(json.load(open('$T/nc.json'))['cells'])")
[ "$(python3 -c "import json; print(json.load(open('$T/nc.json'))['hanging_nodes'] > 0)")" = True ] || fail "no hanging nodes"
dgsolve -q "$T/nc.msh" -c "$T/smooth.json" -p 2 -o "$T/ncsol.msh"
adjoint -q "$T/ncsol.msh" -c "$T/smooth.json" -o "$T/ncdwr.msh"
check "$T/ncdwr.msh" 2 "$cells" || fail "non-conforming"

# --- bad input: exit 2, one line naming the file and the problem, nothing written
expect_fail() {  # expect_fail PATTERN ARGS...
  local pat=$1; shift
  rm -f "$T/bad.msh" "$T/bad.json"
  set +e
  adjoint -q "$@" -o "$T/bad.msh" 2>"$T/err"
  local rc=$?
  set -e
  [ $rc = 2 ] || fail "adjoint $* exited $rc, expected 2: $(cat "$T/err")"
  [ "$(wc -l <"$T/err")" -le 1 ] || fail "more than one line: $(cat "$T/err")"
  grep -q -- "$pat" "$T/err" || fail "message '$(cat "$T/err")' lacks '$pat'"
  [ ! -e "$T/bad.msh" ] && [ ! -e "$T/bad.json" ] || fail "adjoint $* wrote an output"
  # the tools' temporaries are hidden (".STEM.tmp-PID", lib/core/atomic_file.cpp): plain ls never
  # listed them, so this check could not fail (a test audit, session 38)
  if compgen -G "$T/.*.tmp-*" >/dev/null; then fail "temporary file left behind: $(ls -a "$T")"; fi
}
echo '{"exact": "x*y", "advection": [1, 0.5]}' >"$T/nofun.json"
echo '{"exact": "x*y", "advection": [1, 0.5], "functional": {"boundary": "outlet"}}' >"$T/outlet.json"
echo '{"exact": "x*y", "advection": [1, 0.5], "dirichlet": ["inlet"], "functional": {"boundary": "right"}}' >"$T/inlet.json"
expect_fail "sq8.msh.*no DG solution field 'u'" "$T/sq8.msh" -c "$T/smooth.json"
expect_fail "nofun.json.*no functional" "$T/sol1.msh" -c "$T/nofun.json"
expect_fail "outlet.json.*'outlet'" "$T/sol1.msh" -c "$T/outlet.json"
expect_fail "inlet.json.*'inlet'" "$T/sol1.msh" -c "$T/inlet.json"
expect_fail "no DG solution field 'v'" "$T/sol1.msh" -c "$T/smooth.json" --field v
expect_fail "unknown linear solver" "$T/sol1.msh" -c "$T/smooth.json" --solver magic
expect_fail "ordering" "$T/sol1.msh" -c "$T/smooth.json" --ordering sideways
expect_fail "coarse-degree" "$T/sol1.msh" -c "$T/smooth.json" --coarse-degree -1
# a case whose PDE is not the one the solution was solved with ($SolvedCase, written by dgsolve):
# refused, naming what differs (before: exit 0 and a meaningless estimate); the same PDE written
# otherwise, or with the functional added after the solve, is accepted
grep -q '^\$SolvedCase$' "$T/sol1.msh" || fail "dgsolve wrote no \$SolvedCase"
sed 's/"advection": \[1.0, -0.7\]/"advection": [1.0, -0.6]/' "$T/smooth.json" >"$T/other.json"
grep -q -- '-0.6' "$T/other.json" || fail "test setup: other.json"
expect_fail "other.json: is not the PDE .*sol1.msh was solved with (advection differ)" "$T/sol1.msh" -c "$T/other.json"
sed 's/, "functional": {"boundary": "right"}//' "$T/smooth.json" >"$T/solve-only.json"
grep -q functional "$T/solve-only.json" && fail "test setup: solve-only.json"
dgsolve -q "$T/sq8.msh" -c "$T/solve-only.json" -p 1 -o "$T/sol1-nofun.msh"
sed 's/exp(x) + 0.5/exp(x)+0.5/; s/"smooth"/"renamed"/' "$T/smooth.json" >"$T/respaced.json"
adjoint -q "$T/sol1-nofun.msh" -c "$T/respaced.json" -o "$T/later.msh" 2>"$T/errl" || fail "functional added after the solve refused: $(cat "$T/errl")"
# a solution from elsewhere (no $SolvedCase) is accepted as before
sed '/^\$SolvedCase$/,/^\$EndSolvedCase$/d' "$T/sol1.msh" >"$T/sol1-bare.msh"
grep -q SolvedCase "$T/sol1-bare.msh" && fail "test setup: sol1-bare.msh"
adjoint -q "$T/sol1-bare.msh" -c "$T/other.json" -o "$T/bare-dwr.msh" 2>"$T/errb" || fail "a solution without \$SolvedCase refused: $(cat "$T/errb")"
# a functional on a boundary with Dirichlet data: accepted, with a warning naming the boundary and
# the case (a reviewer's goal loop refined only the boundary mismatch, silently); none otherwise
sed 's/"dirichlet": \["left", "top", "bottom"\]/"dirichlet": ["left", "top", "bottom", "right"]/' "$T/smooth.json" >"$T/dirfun-case.json"
grep -q '"right"\]' "$T/dirfun-case.json" || fail "test setup: dirfun.json"
dgsolve -q "$T/sq8.msh" -c "$T/dirfun-case.json" -p 1 -o "$T/sol1-dirfun.msh"
adjoint "$T/sol1-dirfun.msh" -c "$T/dirfun-case.json" -o "$T/dirfun.msh" 2>"$T/errw" || fail "functional on a Dirichlet side refused: $(cat "$T/errw")"
grep -q "warning: the functional boundary 'right' has Dirichlet data in .*dirfun-case.json" "$T/errw" || fail "no warning: $(cat "$T/errw")"
adjoint "$T/sol1.msh" -c "$T/smooth.json" -o "$T/nowarn.msh" 2>"$T/errw2"
if grep -qi warning "$T/errw2"; then fail "a warning without Dirichlet data on the functional boundary: $(cat "$T/errw2")"; fi
# the penalty dgsolve solved with is recorded in SOL and is adjoint's default (before: 20 whatever
# the solve used; on sshock p = 1 solved at 50, sum_eta 1.7e-4 for a true error 1.6e-6); another
# --penalty is taken, with a warning
dgsolve -q "$T/sq8.msh" -c "$T/smooth.json" -p 1 --penalty 50 -o "$T/sol50.msh"
adjoint "$T/sol50.msh" -c "$T/smooth.json" -o "$T/dwr50.msh" 2>"$T/err50" || fail "adjoint on sol50: $(cat "$T/err50")"
if grep -qi warning "$T/err50"; then fail "a warning with SOL's own penalty: $(cat "$T/err50")"; fi
adjoint -q "$T/sol50.msh" -c "$T/smooth.json" --penalty 50 -o "$T/dwr50e.msh"
adjoint "$T/sol50.msh" -c "$T/smooth.json" --penalty 20 -o "$T/dwr50w.msh" 2>"$T/err20" || fail "--penalty 20 on sol50 refused"
grep -q "warning: --penalty 20 is not the factor .*sol50.msh was solved with (50)" "$T/err20" || fail "no penalty-mismatch warning: $(cat "$T/err20")"
python3 - "$T" <<'PY'
import json, sys
t = sys.argv[1]
d, e, w = (json.load(open(t + "/" + n + ".json")) for n in ("dwr50", "dwr50e", "dwr50w"))
assert d["options"]["penalty"] == 50 and w["options"]["penalty"] == 20, (d["options"], w["options"])
assert d["sum_eta"] == e["sum_eta"] and d["functional_error_estimate"] == e["functional_error_estimate"], "default is not SOL's penalty"
assert 0.8 <= d["effectivity"] <= 1.25, d["effectivity"]
assert w["sum_eta"] != d["sum_eta"], "--penalty 20 ignored"
PY
# a penalty factor below 5 (the solution was solved at 20): a warning naming the remedy
adjoint "$T/sol1.msh" -c "$T/smooth.json" -o "$T/pen.msh" --penalty 0.5 2>"$T/errp" || fail "--penalty 0.5 refused: $(cat "$T/errp")"
grep -q "warning: --penalty 0.5.* is below 5" "$T/errp" || fail "no penalty warning: $(cat "$T/errp")"
# never overwrite an input
cp "$T/sol1.msh" "$T/keep.msh"
set +e
adjoint -q "$T/sol1.msh" -c "$T/smooth.json" -o "$T/sol1.msh" 2>"$T/err"
rc=$?
set -e
[ $rc = 2 ] || fail "overwriting the input exited $rc"
cmp -s "$T/sol1.msh" "$T/keep.msh" || fail "the input was modified"
# a solution of degree 8 (the fine space would be 9): one line naming the file, nothing written
# (was "adjoint: adjoint: the solution's degree p = 8 ...", no file)
dgsolve -q "$T/sq8.msh" -c "$T/smooth.json" -p 8 -o "$T/sol8.msh"
set +e
adjoint "$T/sol8.msh" -c "$T/smooth.json" -o "$T/dwr8.msh" 2>"$T/err8"
rc=$?
set -e
[ $rc = 2 ] || fail "p = 8: exit $rc"
grep -q "^adjoint: $T/sol8.msh: the solution's degree p = 8 is out of range (1..7)$" "$T/err8" || fail "p = 8: $(cat "$T/err8")"
[ ! -e "$T/dwr8.msh" ] || fail "p = 8: output written"
echo "adjoint CLI: OK"
