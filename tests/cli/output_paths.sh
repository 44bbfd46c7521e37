#!/usr/bin/env bash
# Output paths (issue #16 item 1/3, #15 item 2): no tool ever writes over a file it reads — mesh,
# --frame, --dwr, case — through the same name, `..`, a symlink or a hard link, for outputs and
# reports alike (exit 2, one line naming the file, input unchanged); `-o ""` and `-o DIR` are exit 2;
# a symlink output is written through to its target; a device or FIFO is written directly (no
# report beside it); `-` is standard output for -o / --report (.msh, JSON, SVG) and standard input
# for an input mesh or case.
set -euo pipefail
S=$QUADAPT_SOURCE_DIR
. "$S/tests/cli/lib/assert.sh"
in_temp_dir
cp "$E/meshes/square16.msh" plain.msh
cp "$E/cases/smooth.json" case.json
dgsolve -q plain.msh -c case.json -p 1 -o sol.msh
estimate-frame -q sol.msh -o shape.msh
size-solve -q shape.msh --complexity 2000 -o frame.msh
adjoint -q sol.msh -c case.json -o dwr.msh
mkdir d
ln -s frame.msh frame_link.msh
ln frame.msh frame_hard.msh
sha() { sha256sum plain.msh case.json sol.msh shape.msh frame.msh dwr.msh; }
sha > before.sha

# 1. every input, every output, every way of naming the same file
for f in frame.msh ./frame.msh d/../frame.msh "$T/frame.msh" frame_link.msh frame_hard.msh; do
  expect_exit 2 "$f" meshquality plain.msh --frame frame.msh --report "$f"
  expect_exit 2 "$f" quadsmooth plain.msh --frame frame.msh -o "$f"
  expect_exit 2 "$f" quadsmooth plain.msh --frame frame.msh -o q.msh --report "$f"
  expect_exit 2 "$f" lpcvt frame.msh -o "$f"
  expect_exit 2 "$f" bamgquad frame.msh -o b.msh --report "$f"
done
expect_exit 2 plain.msh meshquality plain.msh --report plain.msh
expect_exit 2 case.json dgsolve plain.msh -c case.json -p 1 -o case.json
expect_exit 2 case.json dgsolve plain.msh -c case.json -p 1 -o s.msh --report case.json
expect_exit 2 case.json adjoint sol.msh -c case.json -o a.msh --report ./case.json
expect_exit 2 dwr.msh size-solve shape.msh --dwr dwr.msh --complexity 2000 -o dwr.msh
expect_exit 2 dwr.msh size-solve shape.msh --dwr dwr.msh --complexity 2000 -o f.msh --report d/../dwr.msh
expect_exit 2 sol.msh estimate-frame sol.msh -o sh.msh --report sol.msh
expect_exit 2 sol.msh meshplot sol.msh -o p.svg --report sol.msh
expect_exit 2 "given twice" lpcvt frame.msh -o l.msh --write-frame d/../l.msh
sha | cmp -s - before.sha || fail "an input changed"
for f in q.msh q.json s.msh s.json a.msh a.json f.msh f.json sh.msh sh.json p.svg l.msh l.json b.msh; do
  if [ -e "$f" ]; then fail "$f written although the command was refused"; fi
done
if ls -a | grep -q '\.tmp-'; then fail "temporary file left: $(ls -a)"; fi

# 2. empty path, directory, missing folder: exit 2 naming the problem, nothing written
for tool in meshconvert refine; do
  args=(); [ $tool = refine ] && args=(--uniform)
  expect_exit 2 "empty" $tool plain.msh "${args[@]}" -o ""
  expect_exit 2 "d: is a directory" $tool plain.msh "${args[@]}" -o d
  expect_exit 2 "nodir" $tool plain.msh "${args[@]}" -o nodir/x.msh
done
expect_exit 2 "empty" dgsolve plain.msh -c case.json -p 1 -o ""
expect_exit 2 "is a directory" meshplot plain.msh -o d
if [ -n "$(ls d)" ]; then fail "something written into d: $(ls d)"; fi
# "" for any path option is refused (was: --report "" wrote the default x.json, --voronoi "" nothing,
# both exit 0)
expect_exit 2 '--report: empty value ""' meshconvert plain.msh -o x.msh --report ""
expect_exit 2 '--report: empty value ""' dgsolve plain.msh -c case.json -p 1 -o x.msh --report ""
expect_exit 2 '--voronoi: empty value ""' lpcvt frame.msh -o x.msh --voronoi ""
if [ -e x.msh ] || [ -e x.json ]; then fail "written although a path was empty"; fi
# below a file: "is not a directory" (was "directory sol.msh does not exist")
expect_exit 2 "sol.msh/x.msh: sol.msh is not a directory" meshconvert plain.msh -o sol.msh/x.msh
# a folder this user cannot write: refused before any work (was: lpcvt ran, then failed at the end).
# Root may write anywhere: then as user 65534 (setpriv), if this system allows it.
mkdir ro && cp frame.msh ro/frame.msh && chmod 555 ro
ro_run=()
if [ "$(id -u)" -ne 0 ]; then ro_run=(env)
# (user 65534 must be able to run the tools: a build below a folder only root may enter — CI's
# mktemp clone — cannot, and then the check is skipped with a note)
elif command -v setpriv > /dev/null && chmod 755 "$T" &&
  setpriv --reuid=65534 --regid=65534 --clear-groups lpcvt --version > /dev/null 2>&1 &&
  setpriv --reuid=65534 --regid=65534 --clear-groups meshconvert --version > /dev/null 2>&1; then
  ro_run=(setpriv --reuid=65534 --regid=65534 --clear-groups)
fi
if [ ${#ro_run[@]} -gt 0 ]; then
  expect_exit 2 "ro/t.msh: directory ro is not writable (Permission denied)" "${ro_run[@]}" lpcvt ro/frame.msh -o ro/t.msh
  mkdir w && chmod 777 w
  expect_exit 2 "ro/x.json: directory ro is not writable" "${ro_run[@]}" meshconvert plain.msh -o w/x.msh --report ro/x.json
  if [ -e w/x.msh ]; then fail "w/x.msh written although its report cannot be"; fi
else
  echo "note: running as root, and user 65534 cannot run the tools here: the unwritable-folder check is not exercised"
fi
chmod 755 ro

# 3. a symlink output: the link stays, its target gets the mesh (and the report goes beside the link)
cp plain.msh target.msh
ln -s target.msh out_link.msh
meshconvert -q sol.msh -o out_link.msh
if [ ! -L out_link.msh ]; then fail "the symlink was replaced"; fi
meshconvert -q sol.msh -o direct.msh
same_bytes target.msh direct.msh
if [ ! -f out_link.json ]; then fail "no report beside the link"; fi
# a dangling link: its target is created
ln -s made.msh dangling.msh
meshconvert -q sol.msh -o dangling.msh
if [ ! -L dangling.msh ]; then fail "dangling link replaced"; fi
same_bytes made.msh direct.msh

# 4. a FIFO and a device are written directly; no report is invented beside them
mkfifo pipe.msh
cat pipe.msh > from_pipe.msh &
reader=$!
meshconvert -q sol.msh -o pipe.msh
wait $reader
same_bytes from_pipe.msh direct.msh
if [ -e pipe.json ]; then fail "report written beside a FIFO"; fi
meshconvert -q sol.msh -o /dev/null
if [ -e /dev/null.json ]; then fail "/dev/null.json written"; fi
if [ ! -c /dev/null ]; then fail "/dev/null is no longer a device"; fi

# 5. "-": standard output for -o (.msh, SVG) and --report (JSON); standard input for inputs
meshconvert -q sol.msh -o - > stdout.msh
same_bytes stdout.msh direct.msh
if [ -e ./-  ] || [ -e ./-.json ]; then fail "a file named - was written"; fi
meshconvert -q - -o stdin.msh < sol.msh
same_bytes stdin.msh direct.msh
meshquality - < plain.msh > q_stdin.json
meshquality plain.msh > q_file.json
python3 - q_stdin.json q_file.json <<'PY'
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:])
for k in ("cells", "area", "physical"):
    if a[k] != b[k]: sys.exit("FAIL: meshquality from stdin differs in %s" % k)
PY
dgsolve -q plain.msh -c - -p 1 -o s_stdin.msh < case.json
dgsolve -q plain.msh -c case.json -p 1 -o - --report s_rep.json > s_stdout.msh
python3 - s_rep.json <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
if r["outputs"] != ["-"]: sys.exit("FAIL: outputs %r" % r["outputs"])
PY
cmp -s <(grep -v '^"' s_stdout.msh) <(grep -v '^"' s_stdin.msh) || fail "dgsolve -o - differs from -c -"
meshconvert -q sol.msh -o m.msh --report - > rep_stdout.json
python3 -c "import json,sys; json.load(open('rep_stdout.json'))" || fail "--report - is not JSON"
meshplot -q frame.msh --field Vinv -o - > pic.svg
head -c 200 pic.svg | grep -q '<svg' || fail "meshplot -o - is not SVG"
expect_exit 2 "standard output is used twice" meshconvert sol.msh -o - --report -
expect_exit 2 "standard input is used twice" meshquality - --frame -

# 6. the default report never replaces another tool's: converting sol.msh to sol.vtu writes
# sol.vtu.json beside it and leaves dgsolve's sol.json as it was (was: replaced by meshconvert's)
cp sol.json sol.json.before
meshconvert -q sol.msh -o sol.vtu
same_bytes sol.json sol.json.before
python3 -c "import json; r = json.load(open('sol.vtu.json')); assert r['tool'] == 'meshconvert', r['tool']" ||
  fail "sol.vtu.json is not meshconvert's report"
meshconvert -q sol.msh -o conv.msh
[ -s conv.json ] || fail "OUT.msh's report is not OUT.json"
# meshconvert picks the format by the extension: one it does not write is refused before any work
expect_exit 2 "out.vtk" meshconvert sol.msh -o out.vtk
[ ! -e out.vtk ] || fail "meshconvert wrote out.vtk"
# a mesh tool's output named for another format (a user's sol.vtu got MSH text, exit 0, and
# ParaView failed later): refused before any work, naming meshconvert; nothing written
for args in "dgsolve plain.msh -c case.json -p 1 -o s.vtu" "estimate-frame sol.msh -o sh.vtu" \
            "size-solve shape.msh --complexity 2000 -o f.vtk" "lpcvt frame.msh -o t.vtu" \
            "lpcvt frame.msh -o t.msh --write-frame m.vtu" "recombine plain.msh -o r.png" \
            "quadsmooth plain.msh -o q.vtu" "refine sol.msh -o r.vtu" \
            "adjoint sol.msh -c case.json -o a.vtu" "bamgquad frame.msh -o b.vtu"; do
  set -- $args
  out=${@: -1}
  expect_exit 2 "writes Gmsh MSH only" $args
  case "$ERR" in *"meshconvert ${out%.*}.msh -o $out"*) ;; *) fail "no meshconvert hint: $args :: $ERR" ;; esac
  for f in "$out" "${out%.*}.json" "${out}.json" t.msh; do [ ! -e "$f" ] || fail "$args wrote $f"; done
done
# a report named like a mesh would overwrite that mesh with JSON: refused, the mesh untouched
cp frame.msh keep.msh
expect_exit 2 "writes a JSON report, not a msh file" lpcvt frame.msh -o r1.msh --report keep.msh
cmp -s frame.msh keep.msh || fail "--report keep.msh changed keep.msh"
[ ! -e r1.msh ] || fail "--report keep.msh: wrote r1.msh"
# a name without an extension is still a mesh output
quadsmooth -q plain.msh -o noext
meshconvert -q noext -o /dev/null --require quads
# an output mesh's Gmsh options file (OUT.msh.opt) that is an input: refused before the solve
# (was: the solve ran, out.msh was written, then exit 2)
cp plain.msh out.msh.opt
expect_exit 2 "out.msh.opt" dgsolve out.msh.opt -c case.json -p 1 -o out.msh
[ ! -e out.msh ] || fail "dgsolve wrote out.msh before refusing out.msh.opt"
same_bytes out.msh.opt plain.msh
# the same for an output without an extension (MSH, so its options file is OUT.opt)
cp plain.msh noext2.opt
expect_exit 2 "noext2.opt" dgsolve noext2.opt -c case.json -p 1 -o noext2
[ ! -e noext2 ] || fail "dgsolve wrote noext2 before refusing noext2.opt"
same_bytes noext2.opt plain.msh
# extensions in any case: sol.MSH is a mesh for every tool (meshconvert refused it while refine
# accepted it), its report SOL.json; .VTU is ParaView's; --report K.MSH is refused like K.msh
meshconvert -q sol.msh -o upper.MSH
meshconvert -q upper.MSH -o /dev/null --require quads
[ -s upper.json ] && [ ! -e upper.MSH.json ] || fail "upper.MSH's report is not upper.json"
[ -s upper.MSH.opt ] || fail "meshconvert -o upper.MSH wrote no upper.MSH.opt (sol.msh has a DG field)"
meshconvert -q sol.msh -o upper.VTU
head -c 200 upper.VTU | grep -q "VTKFile" || fail "meshconvert -o upper.VTU did not write VTK XML"
refine -q plain.msh --uniform -o r2.MSH
[ -s r2.json ] || fail "refine -o r2.MSH: report not r2.json"
expect_exit 2 "writes Gmsh MSH only" refine plain.msh --uniform -o r3.VTU
expect_exit 2 "writes a JSON report, not a msh file" lpcvt frame.msh -o r4.msh --report keep.MSH
# a picture, a table or Gmsh options are not reports either (--report pic.svg overwrote the picture)
echo '<svg/>' > pic.svg
for c in "pic.svg|a svg" "tab.csv|a csv" "o.msh.opt|an opt"; do
  IFS='|' read -r f kind <<<"$c"
  expect_exit 2 "writes a JSON report, not $kind file" lpcvt frame.msh -o r5.msh --report $f
  [ ! -e r5.msh ] || fail "--report $f: wrote r5.msh"
done
# the Gmsh options file beside a mesh output is named as such when another output takes its name
# (it was "r6.msh.opt: is given twice as an output (also as r6.msh.opt)": a new-user review)
expect_exit 2 "r6.msh.opt: this output is the Gmsh options file written beside r6.msh too; choose another output path" \
  lpcvt frame.msh -o r6.msh --write-frame r6.msh.opt
[ ! -e r6.msh ] || fail "--write-frame r6.msh.opt: wrote r6.msh"
[ "$(cat pic.svg)" = '<svg/>' ] || fail "--report pic.svg changed pic.svg"
# a user's file that has the default report's name is not replaced (`-o mm1.msh` beside a case
# file mm1.json replaced it with the report: a new-user review); an earlier report is
cp case.json mm1.json
expect_exit 2 "mm1.json: exists and is not a quadapt report; the report written beside the output mm1.msh would replace it" \
  dgsolve plain.msh -c case.json -p 1 -o mm1.msh
same_bytes mm1.json case.json
[ ! -e mm1.msh ] || fail "dgsolve wrote mm1.msh before refusing to replace mm1.json"
dgsolve -q plain.msh -c case.json -p 1 -o mm2.msh
dgsolve -q plain.msh -c case.json -p 1 -o mm2.msh || fail "an earlier report was not replaced"
dgsolve -q plain.msh -c case.json -p 1 -o mm1.msh --report mm1r.json || fail "--report beside a user's file"
# an explicit --report naming a user's file is not replaced either (`--report case.json` of a case
# this run does not read replaced it with JSON: a CLI audit); an earlier report or an empty file is
expect_exit 2 "mm1.json: exists and is not a quadapt report; --report would replace it" \
  estimate-frame sol.msh -o sh2.msh --report mm1.json
same_bytes mm1.json case.json
[ ! -e sh2.msh ] || fail "estimate-frame wrote sh2.msh before refusing --report mm1.json"
: > empty.json
estimate-frame -q sol.msh -o sh2.msh --report empty.json
estimate-frame -q sol.msh -o sh2.msh --report empty.json || fail "--report over an earlier report refused"
# ... but the report beside the output replaces no empty file: the user did not name it
# (docs/exit-codes.md; a new-user review found the two cases undocumented)
: > sh3.json
expect_exit 2 "sh3.json: exists and is not a quadapt report" estimate-frame sol.msh -o sh3.msh
[ ! -e sh3.msh ] && [ ! -s sh3.json ] || fail "estimate-frame -o sh3.msh wrote beside an empty sh3.json"
# lpcvt's --voronoi is JSON too: a user's file in its way is refused before any work (it was
# replaced: a CLI audit), a mesh name is refused, and a rerun replaces its own earlier --voronoi
expect_exit 2 "mm1.json: exists and is not quadapt's JSON" lpcvt frame.msh -o v1.msh --voronoi mm1.json
same_bytes mm1.json case.json
[ ! -e v1.msh ] || fail "lpcvt wrote v1.msh before refusing --voronoi mm1.json"
expect_exit 2 "--voronoi writes JSON, not a msh file" lpcvt frame.msh -o v1.msh --voronoi keep.msh
cmp -s frame.msh keep.msh || fail "--voronoi keep.msh changed keep.msh"
lpcvt -q frame.msh -o v1.msh --voronoi v1-vor.json --max-iterations 2
lpcvt -q frame.msh -o v1.msh --voronoi v1-vor.json --max-iterations 2 || fail "--voronoi over its own earlier output refused"
# all or nothing (exit 2 = nothing written; a CLI audit): OUT.msh.opt that cannot be written is
# refused before the solve (it was found after OUT.msh had been replaced, the old report left)
echo OLD > aon.msh
mkdir aon.msh.opt
expect_exit 2 "aon.msh.opt: is a directory" dgsolve sol.msh -c case.json -p 1 -o aon.msh
[ "$(cat aon.msh)" = OLD ] || fail "dgsolve replaced aon.msh, then refused aon.msh.opt"
rmdir aon.msh.opt
# a side output that fails leaves the main output as it was (lpcvt --write-frame after tri.msh)
if [ -w /dev/full ]; then
  echo OLD > aon.msh
  expect_exit 2 "/dev/full" lpcvt -q frame.msh -o aon.msh --write-frame /dev/full
  [ "$(cat aon.msh)" = OLD ] || fail "lpcvt replaced aon.msh, then failed on --write-frame /dev/full"
  for f in .aon.tmp-* ; do [ ! -e "$f" ] || fail "left a temporary $f"; done
fi
# a file-size limit (ulimit -f) is a failed write like a full disk: exit 2, the old output kept,
# no temporary left (SIGXFSZ killed the tool and left a truncated .NAME.tmp-PID.msh)
echo OLD > aon.msh
rc=0
ERR=$( (ulimit -f 8; meshconvert -q sol.msh -o aon.msh) 2>&1 >/dev/null) || rc=$?
[ "$rc" -eq 2 ] || fail "ulimit -f: exit $rc (want 2): $ERR"
case "$ERR" in *"aon.msh: write failed (File too large)"*) ;; *) fail "ulimit -f: $ERR" ;; esac
[ "$(cat aon.msh)" = OLD ] || fail "ulimit -f: aon.msh replaced"
for f in .aon.tmp-* ; do [ ! -e "$f" ] || fail "ulimit -f: left a temporary $f"; done
# the outputs written, the report not (a full device): exit 1, "the outputs were written"
if [ -w /dev/full ]; then
  expect_exit 1 "" meshconvert sol.msh -o full.msh --report /dev/full
  case "$ERR" in *"/dev/full"*"(the outputs were written)"*) ;; *) fail "report on /dev/full: $ERR" ;; esac
  meshconvert -q full.msh -o /dev/null --require quads
fi
echo "ok: output paths"
