#!/usr/bin/env bash
# Plots and comparison report of one study (called by Makefile.cases; docs/studies.md).
#   study-report.sh STUDY_DIR MODE THESIS_CASE_KEY "1 2 3" "uniform fixed-fraction bamg lpcvt" [TITLE]
# Writes STUDY_DIR/convergence-p<P>.png (all methods, guide line, thesis final points) and
# STUDY_DIR/report.md (+ report.json). Works on whatever runs exist (missing ones are marked).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
dir="$1" mode="$2" key="$3" ps="$4" methods="$5" title="${6:-$(basename "$1")}"
PY="${PYTHON:-}"
[ -n "$PY" ] || { [ -x /usr/bin/python3 ] && PY=/usr/bin/python3 || PY=python3; }
thesis="${THESIS_TABLES:-$root/docs/data/thesis-tables.json}"
[ -f "$thesis" ] || { echo "study-report: error: thesis tables not found: $thesis (set THESIS_TABLES=)" >&2; exit 2; }
mkdir -p "$dir"
if "$PY" -c "import matplotlib" 2>/dev/null; then
  for p in $ps; do
    args=() found=0
    for m in $methods; do args+=("$m=$dir/p$p-$m/convergence.csv"); [ ! -s "$dir/p$p-$m/convergence.csv" ] || found=1; done
    [ "$found" = 1 ] || { echo "study-report: note: no run of p = $p in $dir yet: no plot" >&2; continue; }
    "$PY" "$root/scripts/plot/convergence.py" --p "$p" --mode "$mode" --title "$title, p = $p" \
      --thesis "$thesis" --thesis-case "$key" -o "$dir/convergence-p$p.png" "${args[@]}"
  done
else
  echo "study-report: note: python3 matplotlib not found (apt-get install python3-matplotlib); no plots" >&2
fi
"$PY" "$here/compare.py" --study "$dir" --thesis "$thesis" --case "$key" --mode "$mode" \
  --ps "$(echo $ps | tr ' ' ',')" --methods "$(echo $methods | tr ' ' ',')" --title "$title"
