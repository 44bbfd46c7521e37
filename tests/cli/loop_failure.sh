#!/usr/bin/env bash
# A loop broken mid-way (issue #16 item 6; docs/loop.md "Exit status"): a tool that fails in
# step-1 stops scripts/loop/run-loop.sh with status 1 (the earlier steps are saved and valid),
# not 2 (bad input, nothing run); through make the status is make's own 2 with the loop's 1 in
# make's "Error 1" line. The files of step-0 are left untouched, and the same command, once the
# tool works again, resumes at step-1 without redoing step-0 and finishes with status 0.
set -euo pipefail
S=$QUADAPT_SOURCE_DIR
. "$S/tests/cli/lib/assert.sh"
in_temp_dir
python3 "$S/tests/golden/refine/make_square.py" 4 sq4.msh bare
cat > smooth.json <<'JSON'
{ "diffusion": [[1, 0], [0, 1]], "advection": [1, 0.5], "exact": "sin(pi*x)*sin(pi*y) + x*y",
  "functional": {"boundary": "right"} }
JSON
# the tools, with a refine that fails (exit 2, like a bad input) on step-1's mesh
mkdir bin
ln -s "$QUADAPT_BIN_DIR/dgsolve" bin/dgsolve
cat > bin/refine <<SH
#!/usr/bin/env bash
case "\$*" in *step-1/*) echo "refine: \$1: injected failure" >&2; exit 2 ;; esac
exec "$QUADAPT_BIN_DIR/refine" "\$@"
SH
chmod +x bin/refine
ARGS=(--case smooth.json --mesh sq4.msh --p 1 --method uniform --mode feature --steps 3 --pictures no)
MK=(make --no-print-directory -f "$S/Makefile.cases" CASE=smooth.json MESH=sq4.msh P=1 METHOD=uniform
    STEPS=3 PICTURES=no)

# --- the script: status 1, and a message that says where it stopped
rc=0; PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --out run > log1 2>&1 || rc=$?
if [ $rc -ne 1 ]; then cat log1; fail "run-loop.sh: exit $rc after a failing step (want 1)"; fi
grep -q 'refine failed (exit 2)' log1 || fail "the failing tool is not named: $(cat log1)"
grep -q 'stopped in step-1 (status 1)' log1 || fail "no stop message: $(cat log1)"
for f in step-0/mesh.msh step-0/sol.msh step-0/sol.json step-0/adapted.msh step-0/adapted.json step-1/mesh.msh \
         step-1/sol.msh convergence.csv; do
  [ -s "run/$f" ] || fail "run/$f missing after the failure"
done
if [ -e run/loop.done ] || [ -e run/step-1/adapted.msh ] || [ -e run/step-2 ]; then fail "work past the failure"; fi
meshconvert -q run/step-0/adapted.msh -o check.msh  # a valid mesh (the reader validates it)
[ "$(python3 -c 'import csv,sys; print(len(list(csv.DictReader(open(sys.argv[1])))))' run/convergence.csv)" = 2 ] ||
  fail "convergence.csv: $(cat run/convergence.csv)"
mkdir saved && cp -p run/step-0/* saved/

# --- through make: make's status is 2 (GNU make's for any failed recipe), its last line the loop's 1
rc=0; "${MK[@]}" loop BIN="$PWD/bin" OUT=run-make > log2 2>&1 || rc=$?
if [ $rc -ne 2 ]; then cat log2; fail "make: exit $rc"; fi
grep -q 'stopped in step-1 (status 1)' log2 || fail "make: no stop message: $(cat log2)"
tail -n 1 log2 | grep -q '\] Error 1$' || fail "make's last line does not carry the loop's status 1: $(tail -n 1 log2)"
# bad input through make and through the script: 2 both, nothing run
rc=0; "${MK[@]}" loop BIN="$PWD/bin" OUT=run-bad METHOD=simplex > log3 2>&1 || rc=$?
[ $rc -eq 2 ] || fail "make, bad METHOD: exit $rc"
tail -n 1 log3 | grep -q '\] Error 2$' || fail "make, bad METHOD: $(tail -n 1 log3)"
# --help (anywhere on the line) is the usage from the script's header, exit 0, nothing run
rc=0; "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --help --out run-help > logh 2>&1 || rc=$?
[ $rc -eq 0 ] || fail "run-loop.sh --help: exit $rc: $(cat logh)"
grep -q -- "--case CASE.json --mesh START.msh" logh && grep -q "Exit status" logh || fail "run-loop.sh --help: $(cat logh)"
[ ! -e run-help ] || fail "run-loop.sh --help created its --out"
rc=0; PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --method simplex --out run-bad > log4 2>&1 || rc=$?
[ $rc -eq 2 ] || fail "run-loop.sh, bad METHOD: exit $rc"
[ ! -e run-bad ] || fail "bad input created the run directory"
rc=0; PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --max-anisotropy 0.5 --out run-bad > log4b 2>&1 || rc=$?
[ $rc -eq 2 ] || fail "run-loop.sh, MAX_ANISOTROPY 0.5: exit $rc"
grep -q "MAX_ANISOTROPY='0.5': must be a number >= 1" log4b || fail "MAX_ANISOTROPY 0.5: $(cat log4b)"
[ ! -e run-bad ] || fail "bad MAX_ANISOTROPY created the run directory"
rc=0; PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --error-model bamg --out run-bad > log4e 2>&1 || rc=$?
[ $rc -eq 2 ] && grep -q "ERROR_MODEL='bamg': must be polynomial or thesis" log4e || fail "ERROR_MODEL bamg: exit $rc, $(cat log4e)"
[ ! -e run-bad ] || fail "bad ERROR_MODEL created the run directory"
rc=0; PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --start-jitter 0.5 --out run-bad > log4c 2>&1 || rc=$?
[ $rc -eq 2 ] && grep -q "START_JITTER='0.5'" log4c || fail "START_JITTER 0.5: exit $rc, $(cat log4c)"
[ ! -e run-bad ] || fail "bad START_JITTER created the run directory"
rc=0; PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --fit-frame smooth --out run-bad > log4d 2>&1 || rc=$?
[ $rc -eq 2 ] && grep -q "FIT_FRAME='smooth': use raw" log4d || fail "FIT_FRAME smooth: exit $rc, $(cat log4d)"
[ ! -e run-bad ] || fail "bad FIT_FRAME created the run directory"
rc=0; PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --walls loose --out run-bad > log4e 2>&1 || rc=$?
[ $rc -eq 2 ] && grep -q "WALLS='loose': must be slide or fixed" log4e || fail "WALLS loose: exit $rc, $(cat log4e)"
[ ! -e run-bad ] || fail "bad WALLS created the run directory"
rc=0; PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --c-max 1 --out run-bad > log4f 2>&1 || rc=$?
[ $rc -eq 2 ] && grep -q "C_MAX='1': must be a number > 1 (size-solve --c-max" log4f || fail "C_MAX 1: exit $rc, $(cat log4f)"
[ ! -e run-bad ] || fail "bad C_MAX created the run directory"
rc=0; PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --size-gradation 0.5 --out run-bad > log4g 2>&1 || rc=$?
[ $rc -eq 2 ] && grep -q "SIZE_GRADATION='0.5': must be a number > 1 (size-solve --gradation" log4g || fail "SIZE_GRADATION 0.5: exit $rc, $(cat log4g)"
[ ! -e run-bad ] || fail "bad SIZE_GRADATION created the run directory"
# a MESH that is not a mesh: status 2, the user's file named, nothing written (was: status 1
# from dgsolve in step-0, naming run-bad/step-0/mesh.msh, with loop.json and step-0 left behind)
echo "not a mesh" > text.msh
rc=0; PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --mesh text.msh --out run-bad > log4h 2>&1 || rc=$?
[ $rc -eq 2 ] && grep -q "^loop: error: MESH: text.msh: " log4h || fail "MESH text.msh: exit $rc, $(cat log4h)"
[ ! -e run-bad ] || fail "a bad MESH created the run directory"
rc=0; "${MK[@]}" loop BIN="$PWD/bin" OUT=run-bad MESH=text.msh > log4i 2>&1 || rc=$?
[ $rc -eq 2 ] && tail -n 1 log4i | grep -q '\] Error 2$' || fail "make, MESH text.msh: exit $rc, $(tail -n 2 log4i)"
[ ! -e run-bad ] || fail "make, a bad MESH created the run directory"
# what only the solver can check (an expression, boundary names) is checked before OUT exists too
# (was: status 1 from step-0's dgsolve, and the OUT it left refused the corrected rerun)
sed 's/"exact": "sin(pi\*x)\*sin(pi\*y) + x\*y"/"exact": "sin(pi*x)*sin(pi*y + x*y"/' smooth.json > typo.json
grep -q 'sin(pi\*y + x' typo.json || fail "typo.json: the sed did not apply"
rc=0; PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --case typo.json --out run-bad > log4j 2>&1 || rc=$?
[ $rc -eq 2 ] && grep -q "^loop: error: CASE on MESH: typo.json: " log4j || fail "CASE typo: exit $rc, $(cat log4j)"
[ ! -e run-bad ] || fail "a CASE typo created the run directory"
# goal mode with a case that has no functional: refused before OUT exists (it ran step 0's solve
# and estimate, then stopped at the adjoint with status 1, and a rerun could only fail again)
echo '{ "diffusion": [[1, 0], [0, 1]], "advection": [1, 0.5], "exact": "sin(pi*x)*sin(pi*y) + x*y" }' > nofunc.json
rc=0; PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --case nofunc.json --mode goal --method fixed-fraction --out run-bad > log4n 2>&1 || rc=$?
[ $rc -eq 2 ] && grep -q "nofunc.json: MODE=goal needs a functional" log4n || fail "goal without a functional: exit $rc, $(cat log4n)"
[ ! -e run-bad ] || fail "goal without a functional created the run directory"
rc=0; PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --method fixed-fraction --ff-by bogus --out run-bad > log4k 2>&1 || rc=$?
[ $rc -eq 2 ] && grep -q "FF_BY='bogus': use one of: A1h" log4k || fail "FF_BY bogus: exit $rc, $(cat log4k)"
rc=0; PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --window 1,2 --out run-bad > log4l 2>&1 || rc=$?
[ $rc -eq 2 ] && grep -q "WINDOW='1,2': give x0,x1,y0,y1" log4l || fail "WINDOW 1,2: exit $rc, $(cat log4l)"
[ ! -e run-bad ] || fail "bad FF_BY or WINDOW created the run directory"

# --- resume with a working refine: step-0 is not redone (same bytes, same times), the loop ends with 0
sleep 1.1  # a recomputed file would get a later modification time
rm bin/refine && ln -s "$QUADAPT_BIN_DIR/refine" bin/refine
PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --out run > log5 2>&1 || { cat log5; fail "resume failed"; }
for f in saved/*; do
  same_bytes "$f" "run/step-0/$(basename "$f")"
  [ ! "run/step-0/$(basename "$f")" -nt "$f" ] || fail "step-0/$(basename "$f") was rewritten by the resume"
done
if grep -q 'step-0: dgsolve\|step-0: refine' log5; then fail "step-0's tools ran again: $(cat log5)"; fi
[ -s run/loop.done ] && [ -s run/step-3/sol.msh ] || fail "the resumed loop did not finish"
# step-0/mesh.msh is a copy of MESH, not a hard link (an edit of one changed the other, and a
# rerun then solved another start mesh)
[ "$(stat -c %i sq4.msh)" != "$(stat -c %i run/step-0/mesh.msh)" ] || fail "step-0/mesh.msh is MESH itself (hard link)"
same_bytes sq4.msh run/step-0/mesh.msh
# the parameters are compared by value and the case by its contents: GROWTH=1.50 and a copy of
# the case elsewhere resume the run (were refused: text '1.50' != '1.5', another case path)
mkdir elsewhere && cp smooth.json elsewhere/ && touch elsewhere/smooth.json  # newer than every output: not redone
                                                   # (its contents are checked; every step was redone before)
PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --case elsewhere/smooth.json --growth 1.50 --out run > log6 2>&1 ||
  { cat log6; fail "GROWTH=1.50 or the moved case refused"; }
if grep -q ': dgsolve\|: refine' log6; then fail "the equal parameters reran tools: $(cat log6)"; fi
# an option given as its tool's default is the run's own setting (was refused: "max_anisotropy:
# was None, now '25'"); another value is refused, naming both
PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --max-anisotropy 25 --out run > log6b 2>&1 ||
  { cat log6b; fail "MAX_ANISOTROPY=25 (the default) refused"; }
rc=0; PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --max-anisotropy 30 --out run > log6c 2>&1 || rc=$?
[ $rc -eq 2 ] && grep -q "max_anisotropy: was (not set), now '30'" log6c || fail "MAX_ANISOTROPY=30 on a default run: exit $rc, $(cat log6c)"
# loopctl's table of those defaults is the tools' own (their --help)
python3 - "$S/scripts/loop" "$QUADAPT_BIN_DIR" <<'PYEOF' || fail "loopctl.PARAM_DEFAULTS differs from the tools' defaults"
import re, subprocess, sys
sys.path.insert(0, sys.argv[1])
import loopctl
def default(tool, opt):
    h = subprocess.run([sys.argv[2] + "/" + tool, "--help"], capture_output=True, text=True).stdout
    return re.search(re.escape(opt) + r" [A-Z:]*[^=\n]*=(\S+)", h).group(1)
want = {"max_anisotropy": default("size-solve", "--max-anisotropy"), "size_gradation": default("size-solve", "--gradation"),
        "r_max": default("size-solve", "--r-max"), "c_max": default("size-solve", "--c-max"),
        "phases": default("lpcvt", "--phases"), "walls": default("quadsmooth", "--walls"), "fit_frame": "raw"}
def norm(v):
    try:
        return float(v)
    except ValueError:
        return v
bad = {k: (loopctl.PARAM_DEFAULTS.get(k), v) for k, v in want.items() if norm(loopctl.PARAM_DEFAULTS.get(k, "?")) != norm(v)}
if bad or set(loopctl.PARAM_DEFAULTS) != set(want):
    sys.exit("FAIL: loopctl PARAM_DEFAULTS vs the tools: %r" % bad)
print("ok: loopctl's defaults are the tools'", want)
PYEOF

# the tools' provenance in loop.json (a list: every set of tools the run has seen); a resume with
# other tools goes on with a warning naming both (was: nothing recorded which tools made a run)
python3 - run/loop.json "$(dgsolve --version | sed -n 2p)" <<'PYEOF' || fail "loop.json: tools"
import json, sys
t = json.load(open(sys.argv[1]))["tools"]
assert isinstance(t, list) and len(t) == 1 and t[0].startswith("quadapt ") and sys.argv[2] in t[0], t
PYEOF
python3 - run/loop.json <<'PYEOF'
import json, sys
d = json.load(open(sys.argv[1])); d["tools"] = ["quadapt 0.0.9, commit 0000000"]
json.dump(d, open(sys.argv[1], "w"), indent=1, sort_keys=True)
PYEOF
PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --out run > log6d 2>&1 ||
  { cat log6d; fail "a resume with other tools was refused"; }
grep -q "loop: warning: .*/run/loop.json: resumed with other tools (quadapt .*); the run was made with quadapt 0.0.9, commit 0000000" log6d ||
  fail "no warning for other tools: $(cat log6d)"
python3 -c 'import json,sys; t = json.load(open(sys.argv[1]))["tools"]; assert len(t) == 2 and t[0].endswith("0000000"), t' run/loop.json ||
  fail "loop.json does not list both sets of tools"

# --- a TERM to the loop stops the running tool too and leaves the lock free (was: the tool ran on,
# orphaned, holding the lock, and a rerun said "another loop is running"); status 143
rm -f bin/refine  # a symlink to the real refine now: writing through it would replace the tool
cat > bin/refine <<SH
#!/usr/bin/env bash
case "\$*" in *step-1/*) echo \$\$ > "$PWD/slow.pid"; exec sleep 60 ;; esac
exec "$QUADAPT_BIN_DIR/refine" "\$@"
SH
chmod +x bin/refine
PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --out run-term > log7 2>&1 &
loop_pid=$!
for i in $(seq 1 200); do [ -s slow.pid ] && break; sleep 0.05; done
[ -s slow.pid ] || fail "the slow tool did not start: $(cat log7)"
kill -TERM "$loop_pid"
rc=0; wait "$loop_pid" || rc=$?
[ $rc -eq 143 ] || fail "TERM: loop status $rc (want 143)"
grep -q "^loop: stopped by a signal (status 143): .*rerun the same command to resume" log7 || fail "TERM: no line saying how to resume: $(cat log7)"
sleep 0.2
if kill -0 "$(cat slow.pid)" 2>/dev/null; then kill "$(cat slow.pid)"; fail "the running tool outlived the loop"; fi
rm bin/refine && ln -s "$QUADAPT_BIN_DIR/refine" bin/refine
PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --out run-term > log8 2>&1 || { cat log8; fail "resume after TERM"; }
[ -s run-term/loop.done ] || fail "no loop.done after the resume"
# --- OUT an existing file: one line, the loop's (mkdir's own "File exists" line came first)
touch afile
rc=0; PATH="$PWD/bin:$PATH" "$S/scripts/loop/run-loop.sh" "${ARGS[@]}" --out afile > log9 2>&1 || rc=$?
[ $rc -eq 2 ] || fail "OUT a file: status $rc (want 2): $(cat log9)"
[ "$(cat log9)" = "loop: error: cannot create OUT 'afile': it exists and is not a directory" ] || fail "OUT a file: $(cat log9)"
echo "ok: a failing step stops the loop with status 1 (make: 2, 'Error 1'), earlier steps intact, resume finishes"
