#!/usr/bin/env bash
# Determinism (issue #16 item 5): for a given input, options and seed, lpcvt, recombine,
# quadsmooth, bamgquad (dgsolve, adjoint, estimate-frame, size-solve, refine: 1, 2, 4 threads)
# and a 3-step lpcvt loop give byte-identical meshes across two runs,
# different output names and 1, 2 and 4 threads (the loop: 1 vs 2). (lpcvt gave a different
# mesh per output name: its Delaunay update compared face addresses.) Reports are compared
# without their timing, memory, command and path fields.
set -euo pipefail
S=$QUADAPT_SOURCE_DIR
. "$S/tests/cli/lib/assert.sh"
in_temp_dir
export OMP_NUM_THREADS=2
dgsolve -q "$E/meshes/square16.msh" -c "$E/cases/sshock.json" -p 2 -o sol.msh
estimate-frame -q sol.msh -o shape.msh
size-solve -q shape.msh --complexity 20000 -o frame.msh

# lpcvt alone under three output names (the heap layout differs with the name's length; before
# the fix these three names gave three different meshes)
for name in b big_a cc_long_name_here_x; do lpcvt -q frame.msh -o "$name.msh" --seed 1 --threads 1; done
same_bytes b.msh big_a.msh
same_bytes b.msh cc_long_name_here_x.msh

# --seed: without --jitter the lattice start has no randomness (seeds 1 and 2 agree); with it the
# seed decides the start: the same seed repeats, another seed gives another mesh
lpcvt -q frame.msh -o s2.msh --seed 2 --threads 1
same_bytes b.msh s2.msh
lpcvt -q frame.msh -o j2.msh --seed 2 --jitter 0.25 --threads 1
lpcvt -q frame.msh -o j2b.msh --seed 2 --jitter 0.25 --threads 2
lpcvt -q frame.msh -o j3.msh --seed 3 --jitter 0.25 --threads 1
same_bytes j2.msh j2b.msh
if cmp -s j2.msh j3.msh; then fail "lpcvt --jitter 0.25: seeds 2 and 3 gave the same mesh"; fi
if cmp -s j2.msh b.msh; then fail "lpcvt --jitter 0.25 --seed 2: the same mesh as without --jitter"; fi

# run TAG THREADS: every mesh tool once, outputs named after TAG (the names differ on purpose)
run() {
  local tag=$1 n=$2
  mkdir -p "$tag"
  lpcvt -q frame.msh -o "$tag/tri-$tag.msh" --seed 1 --threads "$n"
  recombine -q "$tag/tri-$tag.msh" -o "$tag/quad-$tag.msh" --matching blossom --pairing --threads "$n"
  recombine -q "$tag/tri-$tag.msh" -o "$tag/metric-$tag.msh" --threads "$n"  # the default mode (the loop uses it)
  quadsmooth -q "$tag/quad-$tag.msh" --frame frame.msh -o "$tag/smooth-$tag.msh" --threads "$n"
  if command -v ffbamg >/dev/null; then bamgquad -q frame.msh -o "$tag/bamg-$tag.msh" --threads "$n"; fi
}
run a 1
run second_run_with_a_longer_name 1
run c 2
run d 4
for t in tri quad metric smooth bamg; do
  [ -e "a/$t-a.msh" ] || { [ $t = bamg ] && continue; fail "a/$t-a.msh missing"; }
  same_bytes "a/$t-a.msh" "second_run_with_a_longer_name/$t-second_run_with_a_longer_name.msh"
  same_bytes "a/$t-a.msh" "c/$t-c.msh"
  same_bytes "a/$t-a.msh" "d/$t-d.msh"
done
python3 - a/tri-a.json c/tri-c.json <<'PY'
import json, sys
skip = {"timings", "command", "outputs", "options", "peak_memory_mb", "threads", "seconds", "time_s", "provenance"}
def strip(x):
    if isinstance(x, dict): return {k: strip(v) for k, v in x.items() if k not in skip and not k.endswith("seconds")}
    if isinstance(x, list): return [strip(v) for v in x]
    return x
a, b = (strip(json.load(open(f))) for f in sys.argv[1:])
if a != b: sys.exit("FAIL: lpcvt reports differ beyond timing fields")
PY

# the solver and the other mesh tools at 1, 2 and 4 threads
for n in 1 2 4; do
  dgsolve -q "$E/meshes/square16.msh" -c "$E/cases/smooth.json" -p 2 -o "dg$n.msh" --threads $n
  adjoint -q "dg$n.msh" -c "$E/cases/smooth.json" -o "adj$n.msh" --threads $n
  estimate-frame -q "dg$n.msh" -o "ef$n.msh" --threads $n
  size-solve -q shape.msh --complexity 3000 -o "ss$n.msh" --threads $n
  refine -q shape.msh --by B --fraction 0.3 -o "ref$n.msh" --threads $n
done
for t in dg adj ef ss ref; do same_bytes "${t}1.msh" "${t}2.msh"; same_bytes "${t}1.msh" "${t}4.msh"; done

# a 3-step loop, twice (1 and 2 threads): every step's meshes identical
for n in 1 2; do
  OMP_NUM_THREADS=$n make --no-print-directory -f "$S/Makefile.cases" loop BIN="$(dirname "$(command -v dgsolve)")" \
    CASE="$E/cases/smooth.json" MESH="$E/meshes/square16.msh" P=1 METHOD=lpcvt MODE=feature STEPS=3 \
    OUT="$T/loop$n" PICTURES=no > "loop$n.log" 2>&1 || { cat "loop$n.log" >&2; fail "loop with $n threads failed"; }
done
count=0
for f in $(cd loop1 && find . -name '*.msh' | sort); do
  same_bytes "loop1/$f" "loop2/$f"
  count=$((count + 1))
done
[ $count -ge 12 ] || fail "only $count meshes in the loop"
echo "ok: byte-identical meshes (tools: 2 runs, 2 names, 1, 2 and 4 threads; loop: $count meshes, 1 vs 2 threads)"
