#!/usr/bin/env bash
# CLI test of the Gmsh plugin (lib/gmsh/plugin.hpp): the tools do not load libgmsh at start-up
# (it pulls in ~90 shared libraries, ~0.1 s per process); recombine's Blossom mode loads it on
# first use and works; without libquadapt-gmsh.so beside libquadapt.so the tool that needs Gmsh
# fails with exit 2 and one line naming the missing file, nothing written, and a tool that does
# not need Gmsh still runs.
set -euo pipefail
SRC=${QUADAPT_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
BIN=${QUADAPT_BIN_DIR:-}
[ -n "$BIN" ] && PATH="$BIN:$PATH"
command -v lpcvt >/dev/null || { echo "FAIL: lpcvt not built (tools must be on PATH)" >&2; exit 1; }
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# the shared objects a process maps (the dynamic loader's own log)
loaded() { LD_DEBUG=files "$@" 2>&1 >/dev/null | grep -o 'file=[^ ]*' | sort -u; }

python3 "$SRC/tests/cli/lpcvt_frame.py" "$T/frame.msh" --n 8 --h1 0.1 --h2 0.1
loaded lpcvt --version > "$T/version.libs"
grep -q 'libquadapt\.so' "$T/version.libs" || fail "LD_DEBUG=files shows no libquadapt.so: the check cannot see loads"
grep -q 'libgmsh' "$T/version.libs" && fail "lpcvt --version loads libgmsh"
loaded lpcvt "$T/frame.msh" -o "$T/tri.msh" -q --seed 1 > "$T/lpcvt.libs"
grep -q 'libgmsh' "$T/lpcvt.libs" && fail "lpcvt (no --geometry) loads libgmsh"
[ -s "$T/tri.msh" ] || fail "lpcvt wrote no mesh"
loaded recombine "$T/tri.msh" --matching blossom -o "$T/quad.msh" -q > "$T/recombine.libs"
grep -q 'libquadapt-gmsh\.so' "$T/recombine.libs" || fail "recombine --matching blossom did not load the plugin"
grep -q 'libgmsh' "$T/recombine.libs" || fail "recombine --matching blossom did not load libgmsh"
[ -s "$T/quad.msh" ] || fail "recombine --matching blossom wrote no mesh"

# a copy of the library without the plugin beside it: LD_LIBRARY_PATH wins over the tools' RUNPATH
LIBPATH=$(ldd "$(command -v recombine)" | awk '$1 == "libquadapt.so" { print $3 }')
[ -f "$LIBPATH" ] || fail "cannot find libquadapt.so ($LIBPATH)"
mkdir "$T/alone"
cp "$LIBPATH" "$T/alone/"
set +e
LD_LIBRARY_PATH="$T/alone" recombine "$T/tri.msh" --matching blossom -o "$T/alone/quad.msh" -q 2> "$T/err"
code=$?
set -e
[ "$code" = 2 ] || fail "recombine without the plugin: exit $code, expected 2 ($(cat "$T/err"))"
[ "$(wc -l < "$T/err")" = 1 ] || fail "recombine without the plugin: not one line: $(cat "$T/err")"
grep -q 'libquadapt-gmsh\.so' "$T/err" || fail "the message does not name the plugin: $(cat "$T/err")"
[ -e "$T/alone/quad.msh" ] && fail "recombine without the plugin wrote a mesh"
LD_LIBRARY_PATH="$T/alone" recombine "$T/tri.msh" -o "$T/alone/metric.msh" -q \
  || fail "recombine (metric matching) needs the plugin"
echo "PASS: gmsh_plugin ($(cat "$T/err"))"
