#!/usr/bin/env bash
# A PNG of a .msh file as Gmsh shows it on open (FILE.msh.opt included), without a display.
# Usage: scripts/gmsh-screenshot.sh FILE.msh OUT.png [VIEW]
#   VIEW (default: the last view) is the only view shown. Needs gmsh and xvfb (xvfb-run);
#   scripts/install-deps.sh installs both.
# Example: scripts/gmsh-screenshot.sh runs/demo/step-6/sol.msh docs/img/gmsh-sol.png
set -euo pipefail
[ $# -ge 2 ] || { sed -n '2,6p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
in=$1; out=$2; view=${3:-}
[ -r "$in" ] || { echo "gmsh-screenshot: $in: cannot read" >&2; exit 2; }
command -v xvfb-run >/dev/null || { echo "gmsh-screenshot: xvfb-run not found (apt-get install xvfb)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
out_abs=$(cd "$(dirname "$out")" && pwd)/$(basename "$out")
cat > "$tmp/shot.geo" <<GEO
n = PostProcessing.NbViews;
v = ${view:-n - 1};
For i In {0 : n - 1}
  View[i].Visible = (i == v);
EndFor
General.SmallAxes = 0;
Mesh.SurfaceEdges = 0;
Mesh.Lines = 0;
Print "$tmp/shot.png";
Exit;
GEO
dir=$(cd "$(dirname "$in")" && pwd)
(cd "$dir" && xvfb-run -a -s "-screen 0 1024x900x24" gmsh "$(basename "$in")" "$tmp/shot.geo" >"$tmp/gmsh.log" 2>&1) ||
  { echo "gmsh-screenshot: gmsh failed:" >&2; tail -3 "$tmp/gmsh.log" >&2; exit 1; }
mv "$tmp/shot.png" "$out_abs"
echo "gmsh-screenshot: $out"
