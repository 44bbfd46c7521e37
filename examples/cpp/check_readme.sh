#!/usr/bin/env bash
# example.cpp_adapt_step: runs the README's adapt_step command ("Calling the library from C++")
# and checks that it prints the line the README shows under it (the output path replaced), so
# that the README cannot go stale. Usage: check_readme.sh SOURCE_DIR ADAPT_STEP_BINARY OUT.msh
set -euo pipefail
SRC=$1 BIN=$2 OUT=$3
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
