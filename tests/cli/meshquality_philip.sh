#!/usr/bin/env bash
# meshquality reports on every file of PHiLiP's fixtures as it is, and on each output mesh of
# step 2 against the frame PHiLiP computed on it at step 3 (the same mesh). One pair is
# compared with a stored golden report (rtol 1e-9).
set -euo pipefail
S=$QUADAPT_SOURCE_DIR
D=$QUADAPT_FIXTURES_DIR
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
mkdir "$T/plain" "$T/frame"
for f in "$D"/*.msh; do
  meshquality -q --require quads "$f" > "$T/plain/$(basename "$f" .msh).json"
done
for out in "$D"/output_*_2.msh; do
  c=$(basename "$out" _2.msh)
  c=${c#output_}
  meshquality -q "$out" --frame "$D/input_${c}_3.msh" > "$T/frame/$c.json"
done
python3 - "$T" <<'PY'
import glob, json, os, sys
T = sys.argv[1]
plain = sorted(glob.glob(os.path.join(T, "plain", "*.json")))
assert len(plain) == 16, f"expected 16 fixture files, found {len(plain)}"
for p in plain:
    r = json.load(open(p))
    assert r["cells"] > 100 and r["quads"] == r["cells"] and abs(r["area"] - 1) < 1e-9, (p, r)
    assert sorted(b["name"] for b in r["boundary"]) == ["bottom", "left", "right", "top"], (p, r["boundary"])
    assert r["physical"]["scaled_jacobian_min"] > 0, p
framed = sorted(glob.glob(os.path.join(T, "frame", "*.json")))
assert len(framed) == 8
for p in framed:
    r = json.load(open(p))
    f, m = r["frame"], r["metric"]
    assert f["cells"] == r["cells"] and f["cells_outside"] == 0, (p, f)
    # PHiLiP's files state no convention: read with full-edge sizes, their 1296 cells (not 324)
    assert abs(f["continuous_complexity"] - 1296) < 0.1 and m["scaled_jacobian_min"] > 0, (p, f)
    assert 0 < m["edge_length"]["share_in_range"] < 1, (p, m)
PY
python3 "$S/tests/cli/golden_compare.py" "$T/frame/ss15_fb_p1.json" "$S/tests/golden/io/meshquality_philip_ss15_fb_p1.json" \
  --ignore mesh --ignore frame.file
echo "meshquality_philip: ok"
