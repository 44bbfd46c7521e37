#!/bin/bash
# Paired CPU times of two lpcvt builds on one frame (docs/bench-lpcvt-history.md, "Second pass"):
#   pair.sh BASE_BIN NEW_BIN FRAME REPS [lpcvt options...]
# BASE and NEW alternate (A B A B ...), one thread each, under /usr/bin/time; prints CPU seconds
# (user + sys) and their ratio per pair, and whether the last outputs are byte-identical.
# A build's bin/ may sit apart from its libquadapt.so: set LD_LIBRARY_PATH per side with
# BASE_LIB / NEW_LIB (the executables' RUNPATH yields to LD_LIBRARY_PATH).
set -euo pipefail
A=$1; B=$2; F=$3; R=$4; shift 4
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
cpu() {  # cpu LIB BIN OUT args...
  local lib=$1 bin=$2 out=$3; shift 3
  { LD_LIBRARY_PATH=$lib OMP_NUM_THREADS=1 /usr/bin/time -f "%U %S" "$bin/lpcvt" "$F" -o "$out" -q --threads 1 "$@"; } \
    2>&1 | tail -1 | awk '{print $1 + $2}'
}
for r in $(seq "$R"); do
  a=$(cpu "${BASE_LIB:-}" "$A" "$T/a.msh" "$@")
  b=$(cpu "${NEW_LIB:-}" "$B" "$T/b.msh" "$@")
  echo "base $a new $b ratio $(awk -v a="$a" -v b="$b" 'BEGIN { printf "%.3f", b / a }')"
done
cmp -s "$T/a.msh" "$T/b.msh" && echo "outputs identical" || echo "outputs differ"
