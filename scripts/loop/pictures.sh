#!/usr/bin/env bash
# Pictures of a loop's run directory (called at the end of run-loop.sh; also
# `make -f Makefile.cases pictures OUT=dir [WINDOW=x0,x1,y0,y1] [ALL_STEPS=yes]`).
#   pictures.sh OUT [--window x0,x1,y0,y1] [--all-steps] [--title NAME] [--thesis-case KEY]
# (KEY: a case of docs/data/thesis-tables.json, e.g. sshock-feature: its final points go on the
#  plot; default: the study of the run's case and mode, loopctl.py thesis-key. NAME: the plot's
#  title; default "case (mode), p = P, method", loopctl.py plot-title)
# Writes, when the inputs exist and the picture is older than them:
#   OUT/final-mesh.png, OUT/final-solution.png, OUT/final-mesh-closeup.png (with --window),
#   OUT/final-frame.png (the frame that made the final mesh, 1/h crosses as thesis Fig. 6.5),
#   OUT/convergence.png (needs python3-matplotlib),
#   with --all-steps also OUT/step-K/mesh.png, frame.png (+ closeups) — the sequence of Fig. 6.5,
#   and dwr.png (log10) in goal mode.
# Missing meshplot or matplotlib: a note, no failure. A failing picture: a warning, no failure.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
OUT="${1:?usage: pictures.sh OUT [--window W] [--all-steps] [--title NAME]}"; shift
WINDOW="" ALL=0 THESIS_KEY="" NAME=""
while [ $# -gt 0 ]; do
  case "$1" in
    --window) WINDOW="$2"; shift 2 ;;
    --all-steps) ALL=1; shift ;;
    --title) NAME="$2"; shift 2 ;;
    --thesis-case) THESIS_KEY="$2"; shift 2 ;;
    *) echo "pictures: unknown option $1" >&2; exit 2 ;;
  esac
done
PY="${PYTHON:-}"
[ -n "$PY" ] || { [ -x /usr/bin/python3 ] && PY=/usr/bin/python3 || PY=python3; }
[ -f "$OUT/loop.json" ] || { echo "pictures: $OUT is not a loop's run directory (no loop.json)" >&2; exit 2; }
if [ -n "$WINDOW" ]; then  # the close-up: x0,x1,y0,y1 with x0 < x1, y0 < y1 (the loop's own check)
  "$PY" "$here/loopctl.py" check-window "$WINDOW" || { echo "pictures: WINDOW='$WINDOW': give x0,x1,y0,y1 with x0 < x1 and y0 < y1" >&2; exit 2; }
fi
# titles: case (mode), p, method
[ -n "$NAME" ] || NAME="$("$PY" "$here/loopctl.py" plot-title "$OUT")"
last="$(cat "$OUT/loop.done" 2>/dev/null || true)"
if [ -z "$last" ]; then  # unfinished run: the last solved step
  last=0
  while [ -s "$OUT/step-$((last + 1))/sol.msh" ]; do last=$((last + 1)); done
fi

pic() {  # pic OUTPUT INPUT ARGS...: skipped when OUTPUT is newer than INPUT and was drawn with
  # the same arguments (.OUTPUT.args beside it: a close-up asked with another WINDOW is drawn again)
  local o="$1" in="$2"; shift 2
  [ -s "$in" ] || return 0
  local args="$*" stamp
  stamp="$(dirname "$o")/.$(basename "$o").args"
  if [ ! -s "$o" ] || [ "$in" -nt "$o" ] || [ "$(cat "$stamp" 2>/dev/null)" != "$args" ]; then
    if meshplot "$in" "$@" -q -o "$o" --report - >/dev/null 2>"$OUT/meshplot.log"; then
      printf '%s\n' "$args" > "$stamp"
    else
      echo "pictures: warning: meshplot failed for $o: $(tail -n1 "$OUT/meshplot.log")" >&2
    fi
  fi
}

if command -v meshplot >/dev/null 2>&1; then
  fin="$OUT/step-$last"
  pic "$OUT/final-mesh.png" "$fin/mesh.msh" --title "$NAME: final mesh (step $last)"
  pic "$OUT/final-solution.png" "$fin/sol.msh" --field u --title "$NAME: u (step $last)"
  [ -n "$WINDOW" ] && pic "$OUT/final-mesh-closeup.png" "$fin/mesh.msh" --window "$WINDOW" \
    --title "$NAME: close-up (step $last)"
  [ $last -gt 0 ] && pic "$OUT/final-frame.png" "$OUT/step-$((last - 1))/frame.msh" --field Vinv \
    --title "$NAME: frame of step $((last - 1)) (1/h)"
  if [ $ALL = 1 ]; then
    for ((k = 0; k <= last; k++)); do
      d="$OUT/step-$k"
      pic "$d/mesh.png" "$d/mesh.msh" --title "$NAME: mesh, step $k"
      pic "$d/frame.png" "$d/frame.msh" --field Vinv --title "$NAME: frame (1/h), step $k"
      pic "$d/dwr.png" "$d/dwr.msh" --field dwr --log10 --title "$NAME: DWR, step $k"
      if [ -n "$WINDOW" ]; then
        pic "$d/mesh-closeup.png" "$d/mesh.msh" --window "$WINDOW" --title "$NAME: close-up, step $k"
        pic "$d/frame-closeup.png" "$d/frame.msh" --field Vinv --window "$WINDOW" \
          --title "$NAME: frame close-up, step $k"
      fi
    done
  fi
else
  echo "pictures: note: meshplot not found; no mesh pictures" >&2
fi

if "$PY" -c "import matplotlib" 2>/dev/null; then
  p="$("$PY" "$here/loopctl.py" get "$OUT/loop.json" p)"
  mode="$("$PY" "$here/loopctl.py" get "$OUT/loop.json" mode)"
  method="$("$PY" "$here/loopctl.py" get "$OUT/loop.json" method)"
  thesis=()
  tt="${THESIS_TABLES:-$root/docs/data/thesis-tables.json}"
  # the thesis's point: the study this case and mode belong to
  [ -n "$THESIS_KEY" ] || THESIS_KEY="$("$PY" "$here/loopctl.py" thesis-key "$OUT")"
  [ -n "$THESIS_KEY" ] && [ -f "$tt" ] && thesis=(--thesis "$tt" --thesis-case "$THESIS_KEY")
  if [ ! -s "$OUT/convergence.png" ] || [ "$OUT/convergence.csv" -nt "$OUT/convergence.png" ]; then
    "$PY" "$root/scripts/plot/convergence.py" --p "$p" --mode "$mode" --title "$NAME" ${thesis[@]+"${thesis[@]}"} \
      -o "$OUT/convergence.png" "$method=$OUT/convergence.csv" 2>"$OUT/plot.log" \
      || echo "pictures: warning: convergence plot failed (see $OUT/plot.log)" >&2
  fi
else
  echo "pictures: note: python3 matplotlib not found (apt-get install python3-matplotlib); no plot" >&2
fi
exit 0
