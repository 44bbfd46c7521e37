#!/usr/bin/env bash
# The loop's convergence plot (scripts/plot/convergence.py via scripts/loop/pictures.sh): titled by
# case, mode, p and method (it was the run's path), readable 1-2-5 ticks when the DOFs span less
# than two decades (the demo's x axis had one labelled tick), and the thesis's final point of the
# same study, p and method from docs/data/thesis-tables.json (the demo promised it and had none).
set -euo pipefail
S=$QUADAPT_SOURCE_DIR
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
PY=/usr/bin/python3
$PY -c "import matplotlib" 2>/dev/null || { echo "FAIL: python3-matplotlib missing" >&2; exit 1; }
run="$T/runs/demo"
mkdir -p "$run"
cat > "$run/loop.json" <<JSON
{"case": "$S/examples/cases/sshock.json", "method": "lpcvt", "mode": "feature", "p": "2"}
JSON
cat > "$run/convergence.csv" <<'CSV'
step,cells,dofs,l2_error,functional_error
0,256,2304,9.49e-3,9.5e-9
1,388,3492,9.61e-4,6.1e-8
2,590,5310,6.4e-4,1e-9
3,912,8208,2.2e-4,3e-8
4,1400,12600,1.0e-4,1e-10
5,2114,19026,5.3e-5,1e-11
6,3200,28800,2.4e-5,1e-11
CSV
[ "$($PY "$S/scripts/loop/loopctl.py" plot-title "$run")" = "sshock (feature), p = 2, lpcvt" ]
[ "$($PY "$S/scripts/loop/loopctl.py" thesis-key "$run")" = "sshock-feature" ]
PYTHON=$PY PATH=/usr/bin:/bin bash "$S/scripts/loop/pictures.sh" "$run" 2>/dev/null
test -s "$run/convergence.png"
$PY - "$S" "$run" <<'PY'
import sys
S, run = sys.argv[1], sys.argv[2]
sys.path.insert(0, S + "/scripts/plot")
import convergence
fig, ax, _ = convergence.make_figure(["--p", "2", "--title", "sshock (feature), p = 2, lpcvt",
                                      "--thesis", S + "/docs/data/thesis-tables.json", "--thesis-case", "sshock-feature",
                                      "-o", "x.png", "lpcvt=" + run + "/convergence.csv"])
fig.canvas.draw()
assert ax.get_title() == "sshock (feature), p = 2, lpcvt", ax.get_title()
lo, hi = ax.get_xlim()
labels = [t.get_text() for t in ax.xaxis.get_majorticklabels()
          if t.get_text() and lo <= t.get_position()[0] <= hi]
assert len(labels) >= 3, labels
legend = [t.get_text() for t in ax.get_legend().get_texts()]
assert "thesis lpcvt (final)" in legend and not any("bamg" in l for l in legend), legend
star = [l for l in ax.get_lines() if l.get_label() == "thesis lpcvt (final)"][0]
assert list(star.get_xdata()) == [3.75e4] and list(star.get_ydata()) == [1.42e-5], (star.get_xdata(), star.get_ydata())
print("convergence_plot: title ok; x tick labels", labels, "; thesis point (3.75e4, 1.42e-5)")
PY
# output mistakes: one line naming the path, exit 2, nothing written (was: a traceback, exit 1)
for out in "$T/nodir/c.png" "$T/c.csv"; do
  rc=0; err=$($PY "$S/scripts/plot/convergence.py" --p 2 -o "$out" "lpcvt=$run/convergence.csv" 2>&1) || rc=$?
  [ $rc -eq 2 ] && [ "$(wc -l <<<"$err")" -eq 1 ] && grep -q "^convergence.py: $out: " <<<"$err" || { echo "FAIL: -o $out: exit $rc: $err" >&2; exit 1; }
  [ ! -e "$out" ] || { echo "FAIL: -o $out written" >&2; exit 1; }
done
# input mistakes: no run with data, a misspelt measure: exit 2, nothing written (each drew an empty
# plot, exit 0: a review, session 38); a run's directory stands for its convergence.csv
for bad in "--measure l2_eror lpcvt=$run/convergence.csv" "lpcvt=$T/nope/convergence.csv"; do
  rc=0; err=$($PY "$S/scripts/plot/convergence.py" --p 2 -o "$T/bad.png" $bad 2>&1) || rc=$?
  [ $rc -eq 2 ] && [ ! -e "$T/bad.png" ] || { echo "FAIL: convergence.py $bad: exit $rc: $err" >&2; exit 1; }
done
$PY "$S/scripts/plot/convergence.py" --p 2 -o "$T/dir.png" "lpcvt=$run" "bamg=$T/nope" ||
  { echo "FAIL: convergence.py lpcvt=RUN_DIR" >&2; exit 1; }
# goal mode: the guide line's order is 2p with diffusion (SIPG) and 2p + 1 for pure advection,
# read from step-0/sol.msh's $SolvedCase (was: 2p + 1 always; diffusion cases measured ~2p)
mkdir -p "$run/step-0"
guide() {  # guide DIFFUSION -> the guide line's label
  printf '$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$SolvedCase\n{"advection":[1.0,0.0],"diffusion":%s,"exact":"x"}\n$EndSolvedCase\n' "$1" > "$run/step-0/sol.msh"
  $PY - "$S" "$run" <<'PY'
import sys
S, run = sys.argv[1], sys.argv[2]
sys.path.insert(0, S + "/scripts/plot")
import convergence
fig, ax, _ = convergence.make_figure(["--p", "2", "--mode", "goal", "-o", "x.png", "lpcvt=" + run + "/convergence.csv"])
print([l.get_label() for l in ax.get_lines() if l.get_label().startswith("$")][0])
PY
}
[ "$(guide '[[0.01,0.0],[0.0,0.01]]')" = '$\mathcal{O}(h^{4})$' ] || { echo "FAIL: diffusion guide: $(guide '[[0.01,0.0],[0.0,0.01]]')" >&2; exit 1; }
[ "$(guide '[[0.0,0.0],[0.0,0.0]]')" = '$\mathcal{O}(h^{5})$' ] || { echo "FAIL: advection guide" >&2; exit 1; }
echo "convergence_plot: ok"
