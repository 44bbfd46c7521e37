#!/usr/bin/env bash
# Numeric options (issue #16 items 2 and 6): a value outside its range, NaN or inf is refused at
# parse time (exit 2, one line naming the option and its range, nothing written); --threads is
# clamped to 4 x the cores, never a crash (was SIGSEGV at 100000 in dgsolve and estimate-frame).
set -euo pipefail
S=$QUADAPT_SOURCE_DIR
. "$S/tests/cli/lib/assert.sh"
in_temp_dir
cp "$E/meshes/square16.msh" m.msh
dgsolve -q m.msh -c "$E/cases/smooth.json" -p 1 -o sol.msh
estimate-frame -q sol.msh -o shape.msh
size-solve -q shape.msh --complexity 2000 -o frame.msh
C="$E/cases/smooth.json"

expect_exit 2 "--rtol: -1 is not in (0, 1)" dgsolve m.msh -c "$C" -p 1 -o x.msh --rtol -1
expect_exit 2 "--rtol" adjoint sol.msh -c "$C" -o x.msh --rtol 2
expect_exit 2 "--penalty: -5 is not in (0, inf)" dgsolve m.msh -c "$C" -p 1 -o x.msh --penalty -5
expect_exit 2 "--penalty: nan is not a finite number" dgsolve m.msh -c "$C" -p 1 -o x.msh --penalty nan
expect_exit 2 "--scale: -1 is not in (0, inf)" lpcvt frame.msh -o x.msh --scale -1
expect_exit 2 "--scale: 0 is not in (0, inf)" lpcvt frame.msh -o x.msh --scale 0
expect_exit 2 "--scale: inf is not a finite number" lpcvt frame.msh -o x.msh --scale inf
expect_exit 2 "--move-tol: -0.1 is not in [0, inf)" lpcvt frame.msh -o x.msh --move-tol -0.1
expect_exit 2 "--edge-tol: -0.1 is not in [0, inf)" lpcvt frame.msh -o x.msh --edge-tol -0.1
expect_exit 2 "--complexity" size-solve shape.msh --complexity -3 -o x.msh
expect_exit 2 "--fraction" refine m.msh --by u --fraction 1.5 -o x.msh
expect_exit 2 "--sweeps: must be >= 0 (got -1)" quadsmooth m.msh --sweeps -1 -o x.msh
expect_exit 2 "--edge-factor: must be > 0 (got 0)" bamgquad frame.msh --edge-factor 0 -o x.msh
expect_exit 2 "--glyph-scale" meshplot frame.msh --field Vinv --glyph-scale 0 -o x.svg
expect_exit 2 "--threads: must be >= 0 (got -3)" refine m.msh --uniform -o x.msh --threads -3
# --gradation: 0 (off) or a growth > 1 (was [0, inf): bamgquad took 0.5, which BAMG ignores below 1.1)
expect_exit 2 "--gradation: 0.5 is not 0 (off) or in (1, inf)" size-solve shape.msh --complexity 2000 --gradation 0.5 -o x.msh
expect_exit 2 "--gradation: 1 is not 0 (off) or in (1, inf)" lpcvt frame.msh --gradation 1 -o x.msh
expect_exit 2 "--gradation: 1.05 is not 0 (off) or in [1.1, inf)" bamgquad frame.msh --gradation 1.05 -o x.msh
bamgquad -q frame.msh --gradation 0 -o g0.msh
# lpcvt --lattice-phase: each in [0, 1) (1 1 was accepted)
expect_exit 2 "--lattice-phase: 1 is not in [0, 1)" lpcvt frame.msh -o x.msh --lattice-phase 1 1
# quadsmooth --frame-gradation: 0 or > 1, refused on the command line before any input is read and
# without naming one (it said "quadsmooth: m.msh: --frame-gradation must be > 1 (or 0: none)")
echo garbage > garbage.msh
expect_exit 2 "quadsmooth: --frame-gradation: 0.5 is not 0 (off) or in (1, inf) (see quadsmooth --help)" \
  quadsmooth garbage.msh --frame frame.msh --fit-frame meshed --frame-gradation 0.5 -o x.msh
# CLI11's own ranges, said like the table's (were "Value -1 not in range 0.000000 to 10.000000")
expect_exit 2 "lpcvt: --jitter: -1 is not in [0, 10] (see" lpcvt frame.msh -o x.msh --jitter -1
expect_exit 2 "lpcvt: --phases: -1 is not in [0, 16] (see" lpcvt frame.msh -o x.msh --phases -1
expect_exit 2 "lpcvt: --lp-exponent: 1 is not in [2, 32] (see" lpcvt frame.msh -o x.msh --lp-exponent 1
expect_exit 2 "lpcvt: --grid: 0 is not in [1, 4096] (see" lpcvt --analytic saddle -o x.msh --grid 0
expect_exit 2 "lpcvt: --degree: 0 is not in [1, 8] (see" lpcvt frame.msh -o x.msh --complexity 100 --degree 0
expect_exit 2 "lpcvt: --cells-per-triangle: 0.5 is not in [1, 3] (see" lpcvt frame.msh -o x.msh --cells-per-triangle 0.5
expect_exit 2 "recombine: --min-quality: -1 is not in [0, 0.99] (see" recombine m.msh -o x.msh --min-quality -1
expect_exit 2 "quadsmooth: --frame-smooth: -1 is not in [0, 1000] (see" quadsmooth m.msh -o x.msh --frame-smooth -1
expect_exit 2 "quadsmooth: --relaxation: 2 is not in (0, 2) (see" quadsmooth m.msh -o x.msh --relaxation 2
expect_exit 2 "quadsmooth: --relaxation applies to the shape fit only" quadsmooth m.msh -o x.msh --relaxation 1.2
expect_exit 2 "meshconvert: --jitter: -1 is not in [0, 0.45] (see" meshconvert m.msh -o x.msh --jitter -1
expect_exit 2 "meshconvert: --order: 9 is not in [1, 6] (see" meshconvert m.msh -o x.msh --order 9
# --help says the ranges enforced (quadsmooth said NONNEGATIVE, bamgquad NONNEGATIVE; lpcvt
# --gradation, meshplot --width / --subsample, dgsolve --rtol / --penalty said none)
for want in "quadsmooth|--frame-gradation FLOAT:0 or (1, inf)" "bamgquad|--gradation FLOAT:0 or [1.1, inf)" \
            "lpcvt|--gradation FLOAT:0 or (1, inf)" "lpcvt|--lattice-phase FLOAT:[0, 1)" "meshplot|--width INT:[16, 20000]" \
            "meshplot|--subsample INT:[0, 64]" "dgsolve|--rtol FLOAT:(0, 1)" "dgsolve|--penalty FLOAT:(0, inf)" \
            "quadsmooth|--relaxation FLOAT:(0, 2)=1.6"; do
  h=$(${want%%|*} --help)
  case "$h" in *"${want#*|}"*) ;; *) fail "${want%%|*} --help lacks '${want#*|}'" ;; esac
done
# a missing input: "TOOL: FILE: no such file" (was "dgsolve: MESH: File does not exist: FILE (see dgsolve --help)")
expect_exit 2 "dgsolve: nonexist.msh: no such file" dgsolve nonexist.msh -c "$C" -p 1 -o x.msh
[ "$ERR" = "dgsolve: nonexist.msh: no such file" ] || fail "missing input: $ERR"
expect_exit 2 "lpcvt: nonexist.geo: no such file" lpcvt frame.msh -o x.msh --geometry nonexist.geo
# an expression that does not parse names its option (it said "column 3: expression ends unexpectedly")
expect_exit 2 "estimate-frame: --exact 'x*': column 3: " estimate-frame sol.msh --exact "x*" -p 2 -o x.msh
# estimate-frame --exact: the library's degrees (was: any p >= 1; -p 100 grew past 3 GB)
expect_exit 2 "-p 9 is out of range (1..8)" estimate-frame sol.msh --exact "x*x" -p 9 -o x.msh
[ ! -e x.msh ] || fail "a refused option wrote x.msh"
case "$ERR" in *[0-9][0-9][0-9][0-9][0-9][0-9][0-9][0-9][0-9][0-9]*) fail "absurd bound printed: $ERR" ;; esac
if [ -e x.msh ] || [ -e x.json ] || [ -e x.svg ]; then fail "an output was written"; fi

# every floating-point option of every tool (read from --help): NaN and 1e400 (= inf) refused. The
# finite check missed the options that carry a tool's own check ("FLOAT:POSITIVE", "FLOAT in
# [2 - 32]"): lpcvt --lp-exponent nan, recombine --min-quality nan, quadsmooth --tolerance 1e400,
# bamgquad --edge-factor 1e400 ran with exit 0.
lpcvt -q frame.msh -o tri.msh
declare -A RUN=([adjoint]="sol.msh -c $C -o x.msh" [bamgquad]="frame.msh -o x.msh" [dgsolve]="m.msh -c $C -p 1 -o x.msh"
  [estimate-frame]="sol.msh -o x.msh" [lpcvt]="frame.msh -o x.msh" [meshconvert]="m.msh -o x.msh"
  [meshplot]="m.msh -o x.svg" [meshquality]="m.msh --report x.json" [quadsmooth]="m.msh -o x.msh"
  [recombine]="tri.msh -o x.msh" [refine]="shape.msh --by B -o x.msh" [size-solve]="shape.msh --complexity 2000 -o x.msh")
checked=0
for t in "${!RUN[@]}"; do
  for o in $($t --help | grep -oE -- '--[a-z0-9-]+ FLOAT' | awk '{print $1}' | sort -u); do
    for v in nan 1e400; do
      expect_exit 2 "$o" $t ${RUN[$t]} $o $v -q
      checked=$((checked + 1))
    done
  done
done
[ $checked -ge 60 ] || fail "only $checked floating-point option values checked"
if [ -e x.msh ] || [ -e x.json ] || [ -e x.svg ]; then fail "an output was written"; fi

# --threads 100000: clamped, exit 0, the effective count in the report
for n in 100000; do
  dgsolve -q m.msh -c "$C" -p 1 -o t.msh --threads $n
  estimate-frame -q t.msh -o ts.msh --threads $n
  OMP_NUM_THREADS=$n estimate-frame -q t.msh -o ts2.msh
done
python3 - t.json ts.json ts2.json <<'PY'
import json, os, sys
limit = 4 * os.cpu_count()
for f in sys.argv[1:]:
    r = json.load(open(f))
    if not (1 <= r["threads"] <= limit): sys.exit("FAIL: %s threads %r > %d" % (f, r["threads"], limit))
    if r["options"]["threads"] != r["threads"]: sys.exit("FAIL: %s options.threads %r" % (f, r["options"]["threads"]))
PY
echo "ok: option ranges ($checked non-finite floating-point option values refused)"
