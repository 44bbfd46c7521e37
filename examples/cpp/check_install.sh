#!/usr/bin/env bash
# example.cpp_installed: quadapt as a user installs it (docs/install.md). Installs the build into
# a scratch prefix, builds examples/cpp on its own against it with find_package(quadapt), checks
# that this adapt_step prints the README's line (check_readme.sh), and that the installed tools
# run from the prefix alone: libquadapt.so resolved from PREFIX/lib through their RUNPATH, and the
# Gmsh plugin loaded from beside it (recombine --matching blossom).
# Usage: check_install.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -euo pipefail
SRC=$1 BUILD=$2 WORK=$3
fail() { echo "FAIL: $*" >&2; exit 1; }
rm -rf "$WORK"
mkdir -p "$WORK"
P=$WORK/prefix
cmake --install "$BUILD" --prefix "$P" > "$WORK/install.log" || fail "cmake --install failed: $(tail -n 3 "$WORK/install.log")"
for f in bin/dgsolve bin/lpcvt lib/cmake/quadapt/quadaptConfig.cmake include/quadapt/dg/solve.hpp; do
  [ -e "$P/$f" ] || fail "the install has no $f"
done
[ -e "$(ls "$P"/lib*/libquadapt-gmsh.so 2>/dev/null | head -n 1)" ] || fail "the install has no libquadapt-gmsh.so"

# examples/cpp built on its own: only the installed package, never the source tree's lib/
cmake -S "$SRC/examples/cpp" -B "$WORK/example" -DCMAKE_PREFIX_PATH="$P" > "$WORK/configure.log" 2>&1 ||
  fail "configuring examples/cpp against the install: $(grep -m1 -A3 'Error' "$WORK/configure.log")"
grep -q -- "-I$SRC/lib\b\|-isystem $SRC/lib\b" "$WORK/example/CMakeFiles/adapt_step.dir/flags.make" &&
  fail "the example was compiled against the source tree's lib/, not the install"
cmake --build "$WORK/example" -j 2 > "$WORK/build.log" 2>&1 || fail "building examples/cpp against the install: $(grep -m1 -A3 'error' "$WORK/build.log")"
libs=$(ldd "$WORK/example/adapt_step")
lib=$(awk '$1 == "libquadapt.so" { print $3 }' <<<"$libs")
[ "$lib" -ef "$P/lib/libquadapt.so" ] || [ "$lib" -ef "$(ls "$P"/lib*/libquadapt.so | head -n 1)" ] ||
  fail "the example links $lib, not the installed library"
"$SRC/examples/cpp/check_readme.sh" "$SRC" "$WORK/example/adapt_step" "$WORK/adapted.msh"

# the installed tools, from the prefix alone
v=$("$P/bin/dgsolve" --version)
grep -q '^dgsolve (quadapt) ' <<<"$v" || fail "installed dgsolve --version: $v"
tlibs=$(ldd "$P/bin/lpcvt")
tlib=$(awk '$1 == "libquadapt.so" { print $3 }' <<<"$tlibs")
[[ "$tlib" == "$P"/* ]] || fail "the installed lpcvt resolves libquadapt.so to $tlib, not under $P"
python3 "$SRC/tests/cli/lpcvt_frame.py" "$WORK/frame.msh" --n 8 --h1 0.1 --h2 0.1
"$P/bin/lpcvt" "$WORK/frame.msh" -o "$WORK/tri.msh" -q --seed 1
loads=$(LD_DEBUG=files "$P/bin/recombine" "$WORK/tri.msh" --matching blossom -o "$WORK/quad.msh" -q 2>&1 >/dev/null)
grep -q "file=$P/[^ ]*libquadapt-gmsh\.so" <<<"$loads" || fail "the installed recombine did not load the installed Gmsh plugin"
[ -s "$WORK/quad.msh" ] || fail "the installed recombine --matching blossom wrote no mesh"
echo "ok: installed into $P; examples/cpp built against it; the installed tools run"
