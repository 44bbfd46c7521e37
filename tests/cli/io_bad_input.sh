#!/usr/bin/env bash
# Bad input: non-zero exit (2), ONE line on stderr naming the file and the problem, nothing
# written (no output, no report, no temporary file), for meshconvert and meshquality; a
# suspicious but valid input (unmerged blocks): exit 0 and one warning.
set -euo pipefail
S=$QUADAPT_SOURCE_DIR
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
good="$S/tests/golden/io/square2_fields.msh"
mkdir "$T/in" "$T/out"

head -c 400 "$good" > "$T/in/truncated.msh"
sed 's/^4\.1 0 8$/5.0 0 8/' "$good" > "$T/in/version.msh"
python3 - "$good" "$T/in/missing_nodes.msh" <<'PY'
import sys
t = open(sys.argv[1]).read()
a, b = t.index("$Nodes"), t.index("$EndNodes") + len("$EndNodes\n")
open(sys.argv[2], "w").write(t[:a] + t[b:])
PY
sed '0,/^0\.5 0 0$/s//nan 0 0/' "$good" > "$T/in/nan.msh"
# a $Nodes header that counts 11 more nodes than its blocks list (was read as the blocks say)
python3 - "$good" "$T/in/count.msh" <<'PY'
import sys
L = open(sys.argv[1]).read().split("\n")
i = L.index("$Nodes") + 1
h = L[i].split()
L[i] = " ".join([h[0], str(int(h[1]) + 11)] + h[2:])
open(sys.argv[2], "w").write("\n".join(L))
PY
# its smallest and largest node tag (MSH 4.1; both were read and thrown away): a node tag outside
# the header's range (node 9 listed as 10), and a header whose smallest tag exceeds its largest
python3 - "$good" "$T/in" <<'PY'
import sys
L = open(sys.argv[1]).read().split("\n")
i = L.index("$Nodes") + 1
h = L[i].split()
last = i + 1 + int(h[1])  # the block's last node tag (one block, its header at i + 1)
assert L[last] == h[3]
open(f"{sys.argv[2]}/nodes_tag_outside.msh", "w").write("\n".join(L[:last] + [str(int(h[3]) + 1)] + L[last + 1:]))
open(f"{sys.argv[2]}/nodes_tags_reversed.msh", "w").write("\n".join(L[:i] + [" ".join([h[0], h[1], h[3], h[2]])] + L[i + 1:]))
PY
# the same for $Elements (MSH 4.1): a header counting 3 more elements than its blocks list, one
# whose largest element tag is not the blocks' (both were read without a word), one counting a
# block too many
python3 - "$good" "$T/in" <<'PY'
import sys
L = open(sys.argv[1]).read().split("\n")
i = L.index("$Elements") + 1
h = L[i].split()
for name, header in (("elements_count", [h[0], str(int(h[1]) + 3), h[2], h[3]]),
                     ("elements_tags", [h[0], h[1], h[2], str(int(h[3]) + 1)]),
                     ("elements_blocks", [str(int(h[0]) + 1)] + h[1:])):
    open(f"{sys.argv[2]}/{name}.msh", "w").write("\n".join(L[:i] + [" ".join(header)] + L[i + 1:]))
PY
sed 's/^1 1 2 5 4$/1 1 4 5 2/' "$good" > "$T/in/inverted.msh"
cat > "$T/in/triangle.msh" <<'MSH'
$MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
5
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
5 2 0 0
$EndNodes
$Elements
2
1 3 2 1 1 1 2 3 4
2 2 2 1 1 2 5 3
$EndElements
MSH

# MSH 2.2: a header counting one element more than the section lists (was "expected an integer
# (element tag), found '$EndElements'", which does not say what is wrong)
sed '/^\$Elements$/{n;s/^2$/3/}' "$T/in/triangle.msh" > "$T/in/elements22.msh"
# and both in binary files (the fuzzing corpus's squares): the 4.1 header's count (8-byte integers)
# and the 2.2 header's (an ASCII line before the binary blocks), each one too large
python3 - "$S/tests/fuzz/corpus/msh" "$T/in" <<'PY'
import struct, sys
b = open(f"{sys.argv[1]}/square_bin41.msh", "rb").read()
i = b.index(b"$Elements\n") + len(b"$Elements\n")
nb, ne, lo, hi = struct.unpack("<4Q", b[i:i + 32])
open(f"{sys.argv[2]}/elements41_bin.msh", "wb").write(b[:i] + struct.pack("<4Q", nb, ne + 2, lo, hi) + b[i + 32:])
i = b.index(b"$Nodes\n") + len(b"$Nodes\n")
nb, nn, lo, hi = struct.unpack("<4Q", b[i:i + 32])
open(f"{sys.argv[2]}/nodes41_bin.msh", "wb").write(b[:i] + struct.pack("<4Q", nb, nn, lo, hi + 1) + b[i + 32:])
b = open(f"{sys.argv[1]}/square_bin22.msh", "rb").read()
i = b.index(b"$Elements\n") + len(b"$Elements\n")
j = b.index(b"\n", i)
open(f"{sys.argv[2]}/elements22_bin.msh", "wb").write(b[:i] + str(int(b[i:j]) + 1).encode() + b[j:])
PY

check() {  # check NAME EXPECTED-PROBLEM [extra args]
  local name=$1 problem=$2
  shift 2
  local in="$T/in/$name.msh"
  for tool in meshconvert meshquality; do
    local args=("$in")
    [ "$tool" = meshconvert ] && args+=(-o "$T/out/$name.msh")
    set +e
    "$tool" "${args[@]}" "$@" > "$T/stdout" 2> "$T/stderr"
    local rc=$?
    set -e
    if [ $rc -ne 2 ]; then echo "$tool $name: exit $rc, expected 2"; cat "$T/stderr"; exit 1; fi
    if [ "$(wc -l < "$T/stderr")" -ne 1 ]; then echo "$tool $name: stderr is not one line:"; cat "$T/stderr"; exit 1; fi
    grep -qF "$in" "$T/stderr" || { echo "$tool $name: message does not name the file: $(cat "$T/stderr")"; exit 1; }
    grep -qF "$problem" "$T/stderr" || { echo "$tool $name: message lacks '$problem': $(cat "$T/stderr")"; exit 1; }
    [ ! -s "$T/stdout" ] || { echo "$tool $name: wrote to stdout"; exit 1; }
    if [ -n "$(ls -A "$T/out")" ]; then echo "$tool $name: left files behind: $(ls -A "$T/out")"; exit 1; fi
    echo "$tool $name: $(cat "$T/stderr")"
  done
}

check truncated "truncated file"
check version "unsupported MSH format version '5.0'"
check missing_nodes "\$Nodes"
check nan "non-finite coordinate"
check triangle "quadrilaterals; a quad-dominant mesh: in Gmsh add Mesh.RecombinationAlgorithm = 2" --require quads
check inverted "is inverted"
check count "\$Nodes: the header says 20 nodes, but the blocks list 9"
check nodes_tag_outside "\$Nodes: the header says node tags 1 to 9, but the blocks list tags 1 to 10"
check nodes_tags_reversed "\$Nodes: the header says node tags 9 to 1, but the blocks list tags 1 to 9"
check nodes41_bin "\$Nodes: the header says node tags 1 to 10, but the blocks list tags 1 to 9"
check elements_count "\$Elements: the header says 15 elements, but the blocks list 12"
check elements_tags "\$Elements: the header says element tags 1 to 13, but the blocks list tags 1 to 12"
check elements_blocks "\$Elements: the header says 6 element blocks, but the section has 5"
check elements22 "\$Elements: the header says 3 elements, but the section lists 2"
check elements41_bin "\$Elements: the header says 14 elements, but the blocks list 12"
check elements22_bin "\$Elements: the header says 13 elements, but the section lists 12"

# The same files are fine where they are valid: the triangle mesh without --require.
meshconvert -q "$T/in/triangle.msh" -o "$T/out/ok.msh"
test -s "$T/out/ok.msh"
# Never overwrite an input.
cp "$good" "$T/in/copy.msh"
set +e
meshconvert -q "$T/in/copy.msh" -o "$T/in/copy.msh" 2> "$T/stderr"
rc=$?
set -e
[ $rc -eq 2 ] || { echo "overwriting the input: exit $rc"; exit 1; }
cmp "$good" "$T/in/copy.msh"
echo "meshconvert, output = input: $(cat "$T/stderr")"

# Suspicious but valid: two blocks whose shared nodes were not merged, 1e-6 apart (Gmsh without
# Coherence Mesh;) read as a domain with a slit. Exit 0, the output written, and ONE warning line
# naming the file and the fix (mesh/near_boundary.hpp); none with -q, but the report has it.
cat > "$T/in/unmerged.msh" <<'MSH'
$MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
12
1 0 0 0
2 0.5 0 0
3 0 0.5 0
4 0.5 0.5 0
5 0 1 0
6 0.5 1 0
7 0.500001 0 0
8 1 0 0
9 0.500001 0.5 0
10 1 0.5 0
11 0.500001 1 0
12 1 1 0
$EndNodes
$Elements
4
1 3 2 1 1 1 2 4 3
2 3 2 1 1 3 4 6 5
3 3 2 1 2 7 8 10 9
4 3 2 1 2 9 10 12 11
$EndElements
MSH
warning="warning: $T/in/unmerged.msh: 4 boundary edges lie on other boundary edges (2 pairs, at most 1.000e-06 apart"
for tool in meshconvert meshquality; do
  args=("$T/in/unmerged.msh")
  [ "$tool" = meshconvert ] && args+=(-o "$T/out/unmerged.msh")
  "$tool" "${args[@]}" > "$T/stdout" 2> "$T/stderr" || { echo "$tool unmerged: exit $?"; cat "$T/stderr"; exit 1; }
  [ "$(grep -cF "$warning" "$T/stderr")" -eq 1 ] || { echo "$tool unmerged: not one warning:"; cat "$T/stderr"; exit 1; }
  grep -qF "Coherence Mesh;" "$T/stderr" || { echo "$tool unmerged: the warning names no fix: $(cat "$T/stderr")"; exit 1; }
  echo "$tool unmerged: $(grep -F "$warning" "$T/stderr")"
done
test -s "$T/out/unmerged.msh"
python3 - "$T/out/unmerged.json" "$T/stdout" "$T/in/unmerged.msh" <<'PY'
import json, sys
for report in sys.argv[1:3]:
    w = json.load(open(report))["warnings"]
    assert len(w) == 1 and w[0].startswith(sys.argv[3] + ": 4 boundary edges lie on"), w
PY
meshconvert -q "$T/in/unmerged.msh" -o "$T/out/unmerged_q.msh" 2> "$T/stderr"
[ ! -s "$T/stderr" ] || { echo "meshconvert -q unmerged: stderr not empty: $(cat "$T/stderr")"; exit 1; }
cmp "$T/out/unmerged.msh" "$T/out/unmerged_q.msh"
grep -q '"warnings"' "$T/out/unmerged_q.json" || { echo "meshconvert -q unmerged: no warnings in the report"; exit 1; }
# the same blocks merged (the right block's cells on the left block's nodes 2, 4, 6): no warning
sed -e 's/^3 3 2 1 2 7 8 10 9$/3 3 2 1 2 2 8 10 4/' -e 's/^4 3 2 1 2 9 10 12 11$/4 3 2 1 2 4 10 12 6/' \
  "$T/in/unmerged.msh" > "$T/in/merged.msh"
meshconvert "$T/in/merged.msh" -o "$T/out/merged.msh" 2> "$T/stderr"
! grep -q "warning" "$T/stderr" || { echo "meshconvert merged: $(cat "$T/stderr")"; exit 1; }
echo "io_bad_input: ok"
