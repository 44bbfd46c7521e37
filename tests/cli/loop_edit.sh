#!/usr/bin/env bash
# Editing scripts/loop/run-loop.sh while a loop runs (a git pull during a long study) does not
# break that loop: the script is one compound command that bash reads whole before running it.
# Before, bash read the file as it went, and lines added above the running point made the loop
# fail mid-way ("unexpected EOF while looking for matching '"'", a helper's 75-degree loop of
# session 25). Here a copy of the scripts runs a 3-step uniform loop whose refine is slowed to
# 1 s; during step-0's refine 4 KB of comments are inserted at the top of the copy's run-loop.sh;
# the loop must finish with status 0 and the full table.
set -euo pipefail
S=$QUADAPT_SOURCE_DIR
. "$S/tests/cli/lib/assert.sh"
in_temp_dir
mkdir -p repo/scripts
cp -r "$S/scripts/loop" repo/scripts/loop
python3 "$S/tests/golden/refine/make_square.py" 4 sq4.msh bare
cat > smooth.json <<'JSON'
{ "diffusion": [[1, 0], [0, 1]], "advection": [1, 0.5], "exact": "sin(pi*x)*sin(pi*y) + x*y" }
JSON
mkdir bin
ln -s "$QUADAPT_BIN_DIR/dgsolve" bin/dgsolve
cat > bin/refine <<SH
#!/usr/bin/env bash
touch "$PWD/refine.started"
sleep 1
exec "$QUADAPT_BIN_DIR/refine" "\$@"
SH
chmod +x bin/refine
PATH="$PWD/bin:$PATH" bash repo/scripts/loop/run-loop.sh --case smooth.json --mesh sq4.msh --p 1 \
  --method uniform --mode feature --steps 3 --pictures no --out run > log 2>&1 &
pid=$!
for _ in $(seq 100); do [ -e refine.started ] && break; sleep 0.1; done
[ -e refine.started ] || { kill $pid; cat log; fail "the loop's refine never started"; }
python3 - repo/scripts/loop/run-loop.sh <<'PY'
import sys
p = sys.argv[1]
lines = open(p).read().split("\n")
pad = ["# an edit while the loop runs: %03d %s" % (i, "x" * 30) for i in range(60)]
open(p, "w").write("\n".join(lines[:2] + pad + lines[2:]))
PY
rc=0; wait $pid || rc=$?
[ $rc -eq 0 ] || { cat log; fail "the loop failed (exit $rc) after its script was edited"; }
[ "$(cat run/loop.done)" = 3 ] || { cat log; fail "loop.done is not 3"; }
[ "$(grep -c '^[0-9]' run/convergence.csv)" -eq 4 ] || { cat run/convergence.csv; fail "not 4 rows"; }
echo "ok: loop survives an edit of its script"
