#!/usr/bin/env bash
# Messages a person can act on (issue: first hour in the shell):
#  - every tool's --help ends with an example;
#  - an unknown option is named (dgsolve --bogus used to say "MESH is required");
#  - range errors print no 310-digit bound; logged values print in %.3e (adjoint printed
#    "estimate 0.000000, true error 0.000000" for 7.5e-8 / 6.1e-8);
#  - one degree range, the library's (lib/dg/degree.hpp: 1..8; adjoint 1..7), in dgsolve, adjoint
#    and the loop's check (which said "inputs OK" for P=9);
#  - loop warnings reach the loop's console and convergence.csv's `warnings` column.
set -euo pipefail
S=$QUADAPT_SOURCE_DIR
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
MK="$S/tests/golden/refine/make_square.py"

# --- --help ends with an example
for t in adjoint bamgquad dgsolve estimate-frame lpcvt meshconvert meshplot meshquality quadsmooth recombine refine size-solve; do
  h=$($t --help)
  tail_lines=$(printf '%s\n' "$h" | sed '/^$/d' | tail -n 3)
  # no pipes into head/grep -q here: under pipefail an early-exiting reader can SIGPIPE the
  # writer and fail the check although it matched (seen once in a clean-clone run)
  [ "$(sed -n 1p <<< "$tail_lines")" = "Example:" ] || fail "$t --help does not end with an example: $tail_lines"
  [[ "$(sed -n 2p <<< "$tail_lines")" == "  $t "* ]] || fail "$t example does not run $t"
done

# --- unknown options are named, with or without the required arguments
for args in "--bogus" "$S/examples/meshes/square16.msh -c $S/examples/cases/smooth.json -p 1 -o $T/x.msh --bogus=3"; do
  rc=0; msg=$(dgsolve $args 2>&1) || rc=$?
  [ $rc -eq 2 ] || fail "dgsolve $args: exit $rc"
  grep -q 'unknown option --bogus' <<<"$msg" || fail "unknown option not named: $msg"
done
[ ! -e "$T/x.msh" ] || fail "output written despite an unknown option"
rc=0; msg=$(lpcvt -q --bogus 2>&1) || rc=$?
grep -q 'unknown option --bogus' <<<"$msg" || fail "lpcvt: $msg"

# --- a value of the wrong type says what the option takes (was CLI11's "Could not convert:
# --degree = 2.5")
for c in "dgsolve|-p 2.5|--degree 2.5: not a whole number" "lpcvt|--seed abc|--seed abc: not a non-negative whole number" \
         "lpcvt|--lp-exponent six|--lp-exponent six: not a number"; do
  IFS='|' read -r tool opt want <<<"$c"
  case $tool in
    dgsolve) args=("$S/examples/meshes/square16.msh" -c "$S/examples/cases/smooth.json") ;;
    lpcvt) args=("$S/tests/fixtures/philip/input_ss15_fb_p1_3.msh") ;;
  esac
  rc=0; msg=$($tool "${args[@]}" -o "$T/y.msh" $opt 2>&1) || rc=$?
  [ $rc -eq 2 ] || fail "$tool $opt: exit $rc"
  grep -qF -- "$want" <<<"$msg" || fail "$tool $opt: '$msg' lacks '$want'"
done
[ ! -e "$T/y.msh" ] || fail "output written despite a malformed option value"
# CLI11's count messages in the tools' words (were "At least 2 required but received 1", "At Most 1
# required but received 2", "The following arguments were not expected: b a")
M16="$S/examples/meshes/square16.msh"
for c in "lpcvt|$M16 -o $T/y.msh --lattice-phase 0.5|--lattice-phase takes 2 values, got 1" \
         "dgsolve|$M16 -c $S/examples/cases/smooth.json -p 1 -p 2 -o $T/y.msh|--degree is given 2 times: give it once" \
         "meshplot|$M16 a b -o $T/y.svg|unexpected arguments a b"; do
  IFS='|' read -r tool args want <<<"$c"
  rc=0; msg=$($tool $args 2>&1) || rc=$?
  [ $rc -eq 2 ] || fail "$tool $args: exit $rc"
  grep -qF -- "$tool: $want (see $tool --help)" <<<"$msg" || fail "$tool $args: '$msg' lacks '$want'"
done
# a whole number too large for its type is not "not a whole number" (a CLI audit)
rc=0; msg=$(dgsolve "$S/examples/meshes/square16.msh" -c "$S/examples/cases/smooth.json" -o "$T/y.msh" --threads 99999999999 2>&1) || rc=$?
[ $rc -eq 2 ] && grep -qF -- "--threads 99999999999: a whole number out of range" <<<"$msg" || fail "--threads 99999999999: exit $rc, $msg"
# lpcvt: --complexity without --degree is refused before the frame is read and filtered (it
# printed three progress lines first)
rc=0; msg=$(lpcvt "$S/tests/fixtures/philip/input_ss15_fb_p1_3.msh" -o "$T/y.msh" --complexity 4000 2>&1) || rc=$?
[ $rc -eq 2 ] && [ "$(grep -c . <<<"$msg")" -eq 1 ] && grep -q -- "--complexity and --degree go together" <<<"$msg" ||
  fail "lpcvt --complexity alone: exit $rc, $msg"
# lpcvt: an option of another mode or start is refused, not ignored (each gave the bytes of the run
# without it, exit 0: a new-user review, session 38)
P1="$S/tests/fixtures/philip/input_ss15_fb_p1_3.msh"
for c in "$P1 --sampled|--sampled applies to --analytic only" "$P1 --grid 8|--grid applies to --analytic only" \
         "--analytic saddle --convention philip|--convention applies to a FRAME's sizes" \
         "$P1 --coarse-points 100|--coarse-points applies to --init multilevel only (the start is --init lattice)" \
         "$P1 --init density --jitter 0.5|--jitter moves the lattice start's points; the start is --init density" \
         "$P1 --init multilevel --lattice-phase 0.5 0.5|--lattice-phase moves the lattice start; the start is --init multilevel" \
         "$P1 --init density --phases 3|--phases applies to the lattice start; the start is --init density" \
         "--analytic saddle --phases 2|--phases applies to a FRAME's lattice start, not to --analytic" \
         "$P1 --cells euclidean --cell-anisotropy 0.3|--cell-anisotropy applies to --cells metric only"; do
  IFS='|' read -r args want <<<"$c"
  rc=0; msg=$(lpcvt $args -o "$T/y.msh" 2>&1) || rc=$?
  [ $rc -eq 2 ] && [ "$(grep -c . <<<"$msg")" -eq 1 ] && grep -qF -- "lpcvt: $want" <<<"$msg" || fail "lpcvt $args: exit $rc, '$msg'"
done
[ ! -e "$T/y.msh" ] || fail "lpcvt wrote an output despite an option of another mode"
# ... and the same options where they apply still run (the loop passes --jitter 0 with every start)
lpcvt -q "$P1" -o "$T/ok.msh" --init density --jitter 0 --max-iterations 2 --max-cycles 1 ||
  fail "lpcvt --init density --jitter 0 refused"
lpcvt -q --analytic saddle --sampled --grid 8 --init lattice --jitter 0.1 --max-iterations 2 --max-cycles 1 -o "$T/ok.msh" ||
  fail "lpcvt --analytic --sampled --grid --init lattice --jitter refused"

# --- a report that would overwrite an input is named as the report, with its remedy (was
# "X.json: output would overwrite the input file X.json" for `-c X.json -o X.msh`)
cp "$S/examples/cases/smooth.json" "$T/X.json"
rc=0; msg=$(dgsolve "$S/examples/meshes/square16.msh" -c "$T/X.json" -p 1 -o "$T/X.msh" 2>&1) || rc=$?
[ $rc -eq 2 ] && grep -q "X.json: the report written beside the output .*X.msh would overwrite the input file .*X.json; give --report another path, or -o another name" <<<"$msg" ||
  fail "report over the case: exit $rc, $msg"
rc=0; msg=$(dgsolve "$S/examples/meshes/square16.msh" -c "$T/X.json" -p 1 -o "$T/Y.msh" --report "$T/X.json" 2>&1) || rc=$?
[ $rc -eq 2 ] && grep -q "the report (--report) would overwrite the input file .*X.json; give --report another path" <<<"$msg" ||
  fail "--report over the case: exit $rc, $msg"
[ ! -e "$T/X.msh" ] && [ ! -e "$T/Y.msh" ] && cmp -s "$T/X.json" "$S/examples/cases/smooth.json" || fail "report collision: something was written"

# --- no absurd bounds in range errors
M=$S/examples/meshes/square16.msh
for cmd in "dgsolve --threads -1 $M" "recombine $M -o $T/y.msh --topology-passes -5" "bamgquad $M -o $T/y.msh --edge-factor -1"; do
  msg=$($cmd 2>&1 || true)
  grep -q -E '[0-9]{13,}' <<<"$msg" && fail "$cmd: long number in: $msg"
  [ ${#msg} -lt 200 ] || fail "$cmd: message of ${#msg} characters: $msg"
  grep -q -E 'must be >=? 0 \(got -[0-9]+\)' <<<"$msg" || fail "$cmd: $msg"
done
msg=$(dgsolve --threads -1 x 2>&1 || true)
grep -q 'must be >= 0 (got -1)' <<<"$msg" || fail "threads: $msg"

# --- values in %.3e: a polynomial case, errors at rounding level (used to print 0.000000)
python3 "$MK" 2 "$T/sq2.msh"
cat > "$T/poly.json" <<'JSON'
{"diffusion": [[0.1, 0], [0, 0.1]], "advection": [1, 0.5], "exact": "x*y + 0.5", "functional": {"boundary": "right"}}
JSON
dgsolve "$T/sq2.msh" -c "$T/poly.json" -p 2 -o "$T/sol.msh" 2> "$T/dg.log"
grep -q -E 'L2 error -?[0-9]\.[0-9]{3}e[-+][0-9]{2}$' "$T/dg.log" || fail "dgsolve log: $(cat "$T/dg.log")"
adjoint "$T/sol.msh" -c "$T/poly.json" -o "$T/dwr.msh" 2> "$T/adj.log"
grep -q -E 'estimate -?[0-9]\.[0-9]{3}e[-+][0-9]{2}, true error [0-9]\.[0-9]{3}e[-+][0-9]{2}$' "$T/adj.log" ||
  fail "adjoint log: $(cat "$T/adj.log")"
grep -q '0\.000000' "$T/dg.log" "$T/adj.log" && fail "fixed-point zeros in the logs"

# --- one degree range
help=$(dgsolve --help); grep -q 'degree P (1\.\.8)' <<<"$help" || fail "dgsolve --help range"
rc=0; msg=$(dgsolve "$T/sq2.msh" -c "$T/poly.json" -p 9 -o "$T/p9.msh" 2>&1) || rc=$?
[ $rc -eq 2 ] && grep -q 'out of range (1\.\.8)' <<<"$msg" || fail "p=9: exit $rc: $msg"
dgsolve -q "$T/sq2.msh" -c "$T/poly.json" -p 8 -o "$T/p8.msh"
rc=0; msg=$(adjoint "$T/p8.msh" -c "$T/poly.json" -o "$T/d8.msh" 2>&1) || rc=$?
[ $rc -eq 2 ] && grep -q 'out of range (1\.\.7)' <<<"$msg" || fail "adjoint p=8: exit $rc: $msg"
mk() { make -s -f "$S/Makefile.cases" check CASE=sshock BIN="$QUADAPT_BIN_DIR" "$@" 2>&1; }
msg=$(mk P=9) && fail "make check P=9 passed: $msg"
grep -q 'P=9: the DG degree must be 1..8' <<<"$msg" || fail "check P=9: $msg"
msg=$(mk P=8); grep -q 'inputs OK' <<<"$msg" || fail "check P=8"
msg=$(mk P=8 MODE=goal) && fail "goal P=8 passed"
grep -q 'must be 1..7 in goal mode' <<<"$msg" || fail "goal P=8: $msg"
# CASE=NAME is ./NAME.json when that exists (a reviewer's own smooth.json lost to the shipped one,
# and the log said only "CASE=smooth.json"); the check names the case file it resolved
cp "$S/examples/cases/smooth.json" "$T/sshock.json"
msg=$(cd "$T" && mk OUT="$T/r-local")
grep -q "case $(cd "$T" && pwd)/sshock.json;" <<<"$msg" || fail "CASE=sshock with ./sshock.json: $msg"
rm "$T/sshock.json"
msg=$(cd "$T" && mk OUT="$T/r-local")
grep -q "case $S/examples/cases/sshock.json;\|case .*/examples/cases/sshock.json;" <<<"$msg" || fail "CASE=sshock shipped: $msg"
# check refuses the OUT the run would refuse (was: "inputs OK", then the loop exited 2)
msg=$(mk OUT="$T/sq2.msh") && fail "check OUT=a file passed: $msg"
grep -q "it exists and is not a directory" <<<"$msg" || fail "check OUT=a file: $msg"
[ ! -e "$T/r-local" ] || fail "check created OUT"
# a variable of the other kind of target is refused, not ignored (a study target took STEPS=2 P=3 and
# ran p = 1 for 30 steps; `loop RUNS=dir` wrote under runs/: a new-user review, session 38)
msg=$(make -n -s -f "$S/Makefile.cases" sshock-feature-p1-lpcvt RUNS="$T/st" STEPS=2 P=3 2>&1) && fail "a study target took STEPS P: $msg"
grep -q "P STEPS: one loop's variables, which the study targets do not read\|STEPS P: one loop's variables, which the study targets do not read" <<<"$msg" || fail "study target with STEPS P: $msg"
msg=$(mk RUNS="$T/st" STUDY_STEPS=2) && fail "make check took RUNS STUDY_STEPS: $msg"
grep -q "the studies' variables, which check does not read" <<<"$msg" || fail "check with RUNS: $msg"
[ ! -e "$T/st" ] || fail "a refused make wrote $T/st"

# --- loop warnings: a wrapped lpcvt that warns (exit 0) and one that exits 1 with a valid output
mkdir "$T/bin"
for t in dgsolve estimate-frame size-solve recombine quadsmooth meshplot; do ln -s "$QUADAPT_BIN_DIR/$t" "$T/bin/$t"; done
cat > "$T/bin/lpcvt" <<SH
#!/usr/bin/env bash
"$QUADAPT_BIN_DIR/lpcvt" "\$@" || exit \$?
echo "lpcvt: warning: test warning one" >&2
if [ -e "$T/fail1" ]; then echo "lpcvt: test failure with a valid output" >&2; exit 1; fi
SH
chmod +x "$T/bin/lpcvt"
python3 "$MK" 8 "$T/sq8.msh"
touch "$T/fail1"
make -s -f "$S/Makefile.cases" loop CASE=sshock MESH="$T/sq8.msh" P=1 METHOD=lpcvt STEPS=1 OUT="$T/run" \
     PICTURES=no BIN="$T/bin" > "$T/loop.out" 2>&1 || fail "loop failed: $(tail -5 "$T/loop.out")"
grep -q 'loop: warning: step-0: lpcvt: test warning one' "$T/loop.out" || fail "console: $(cat "$T/loop.out")"
grep -q 'loop: warning: step-0: lpcvt: test failure with a valid output' "$T/loop.out" || fail "console exit 1"
python3 - "$T/run/convergence.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 2, rows
w = rows[0]["warnings"].split(" | ")
# the real lpcvt may warn too (e.g. not converged); ours come last, in order, each once
assert w[-2:] == ["lpcvt: test warning one", "lpcvt: test failure with a valid output"], w
assert all(x.startswith("lpcvt: ") for x in w) and len(w) == len(set(w)), w
assert rows[1]["warnings"] == "", rows[1]
print("messages: convergence.csv warnings:", rows[0]["warnings"])
PY
# --- options that would be silently ignored are refused (exit 2, the reason named)
rc=0; msg=$(lpcvt --analytic saddle --orientation boundary -o "$T/o.msh" 2>&1) || rc=$?
[ $rc -eq 2 ] && grep -q -- "--orientation boundary needs a frame" <<<"$msg" || fail "lpcvt --analytic --orientation boundary: exit $rc: $msg"
[ ! -e "$T/o.msh" ] || fail "lpcvt wrote an output after refusing its options"
python3 "$S/tests/cli/lpcvt_frame.py" "$T/f.msh" --n 4
rc=0; msg=$(lpcvt "$T/f.msh" --boundary-norm 0.5 -o "$T/o.msh" 2>&1) || rc=$?
[ $rc -eq 2 ] && grep -q -- "--boundary-norm: 0.5 is neither 0 (the L_p exponent) nor in \[1, 64\]" <<<"$msg" || fail "lpcvt --boundary-norm 0.5: exit $rc: $msg"
[ ! -e "$T/o.msh" ] || fail "lpcvt wrote an output after refusing --boundary-norm"
lpcvt -q "$T/f.msh" -o "$T/t.msh" && recombine -q "$T/t.msh" -o "$T/q.msh"
rc=0; msg=$(recombine "$T/t.msh" -o "$T/qb.msh" --matching blossom --interior-bonus 0.2 2>&1) || rc=$?
[ $rc -eq 2 ] && grep -q -- "--interior-bonus applies to the metric matching only" <<<"$msg" || fail "recombine --matching blossom --interior-bonus: exit $rc: $msg"
[ ! -e "$T/qb.msh" ] || fail "recombine wrote an output after refusing --interior-bonus"
# ... and the reverse: Blossom's options under the metric matching (they were ignored, the report
# naming a mode that never ran: a docs audit)
for o in --pairing "--topology-passes 0" "--relocation-passes 2"; do
  rc=0; msg=$(recombine "$T/t.msh" -o "$T/qm.msh" $o 2>&1) || rc=$?
  [ $rc -eq 2 ] && grep -q -- "${o%% *} applies to Blossom-Quad only (--matching blossom)" <<<"$msg" || fail "recombine $o (metric): exit $rc: $msg"
  [ ! -e "$T/qm.msh" ] || fail "recombine wrote an output after refusing $o"
done
python3 -c "import json,sys; o=json.load(open(sys.argv[1]))['options']; assert 'mode' not in o and 'topology_passes' not in o, o" "$T/q.json" ||
  fail "the metric matching's report names Blossom's mode"
rc=0; msg=$(quadsmooth "$T/q.msh" -o "$T/s.msh" --corner-metric cell 2>&1) || rc=$?
[ $rc -eq 2 ] && grep -q -- "--corner-metric applies to the shape fit only" <<<"$msg" || fail "quadsmooth --corner-metric without --frame: exit $rc: $msg"
rc=0; msg=$(quadsmooth "$T/q.msh" -o "$T/s.msh" --walls fixed 2>&1) || rc=$?
[ $rc -eq 2 ] && grep -q -- "--walls applies to the shape fit only" <<<"$msg" || fail "quadsmooth --walls without --frame: exit $rc: $msg"

echo "messages: ok"
