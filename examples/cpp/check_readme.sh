#!/usr/bin/env bash
# example.cpp_adapt_step: runs the README's adapt_step command ("Calling the library from C++")
# and checks that it prints the line the README shows under it (the output path replaced), so
# that the README cannot go stale; then, with the tools' directory, that OUT.msh is byte for byte
# what the tools make from the same inputs (dgsolve | estimate-frame | size-solve --complexity
# 1.5 DOFs | lpcvt | recombine | quadsmooth --frame): the library calls are the tools' calls.
# Usage: check_readme.sh SOURCE_DIR ADAPT_STEP_BINARY OUT.msh [TOOLS_DIR]
set -euo pipefail
SRC=$1 BIN=$2 OUT=$3 TOOLS=${4:-}
cmd=$(grep -m1 '^    \$ build/examples/cpp/adapt_step ' "$SRC/README.md") || { echo "FAIL: no adapt_step command in README.md"; exit 1; }
want=$(grep -m1 -A1 '^    \$ build/examples/cpp/adapt_step ' "$SRC/README.md" | tail -n 1 | sed 's/^    //')
read -r -a args <<< "${cmd#    \$ build/examples/cpp/adapt_step }"
[ ${#args[@]} -eq 3 ] || { echo "FAIL: the README's command does not have 3 arguments: $cmd"; exit 1; }
got=$(cd "$SRC" && "$BIN" "${args[0]}" "${args[1]}" "$OUT")
want=${want/(${args[2]})/($OUT)}
if [ "$got" != "$want" ]; then
  printf 'FAIL: the README shows\n  %s\nthe example prints\n  %s\n' "$want" "$got"
  exit 1
fi
echo "ok: $got"
[ -n "$TOOLS" ] || exit 0
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
PATH="$TOOLS:$PATH"
(cd "$SRC" && dgsolve -q "${args[0]}" -c "${args[1]}" -p 2 -o "$T/sol.msh" --report "$T/sol.json")
dofs=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["dofs"])' "$T/sol.json")
estimate-frame -q "$T/sol.msh" -o "$T/shape.msh"
size-solve -q "$T/shape.msh" --complexity "$(python3 -c "print(1.5 * $dofs)")" -o "$T/frame.msh"
lpcvt -q "$T/frame.msh" -o "$T/tri.msh"
recombine -q "$T/tri.msh" -o "$T/quad.msh"
quadsmooth -q "$T/quad.msh" --frame "$T/frame.msh" -o "$T/adapted.msh"
cmp "$T/adapted.msh" "$OUT" || { echo "FAIL: the example's mesh differs from the tools' adapted.msh"; exit 1; }
echo "ok: $OUT is the tools' adapted.msh byte for byte"
