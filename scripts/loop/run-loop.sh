#!/usr/bin/env bash
# One adaptive loop (docs/design.md §1; docs/loop.md). Called by `make -f Makefile.cases loop`.
#
#   run-loop.sh --case CASE.json --mesh START.msh --p P --method lpcvt|bamg|fixed-fraction|uniform
#               --mode feature|goal --steps N --growth G --out DIR
#               [--maxdofs N] [--fraction F] [--ff-by FIELD] [--seed S] [--smooth-bamg yes|no]
#               [--max-anisotropy A] [--start-jitter J] [--fit-frame raw|meshed|capped] [--phases N]
#               [--walls slide|fixed] [--r-max R] [--c-max C] [--size-gradation G] [--error-model polynomial|thesis]
#               [--pictures yes|no] [--window x0,x1,y0,y1] [--thesis-case KEY] [--check-only]
#               [--geometry FILE.geo [--order Q]] [--jitter J] [-h|--help]
#
# Each option is the make variable of the same name (--max-anisotropy = MAX_ANISOTROPY, ...); what
# they do and their defaults: docs/loop.md. Example:
#   run-loop.sh --case examples/cases/sshock.json --mesh examples/meshes/square16.msh --p 2 \
#               --method lpcvt --mode feature --steps 6 --growth 1.5 --maxdofs 2e4 --out runs/mine
#
# Every input is checked, and every tool the method needs is looked up, BEFORE any work starts.
# Step K lives in DIR/step-K/: mesh.msh (its mesh), sol.msh (dgsolve), then per method
# shape.msh (estimate-frame), indicator.msh (fixed-fraction, FF_BY=A1h), dwr.msh (adjoint, goal
# mode), frame.msh (size-solve), tri.msh
# (lpcvt), quad.msh (recombine | bamgquad), adapted.msh (quadsmooth | refine) = the next mesh,
# each with its JSON report beside it (.json) and the tool's stderr in TOOL.log.
# Resume: every tool writes atomically, and a tool is skipped when its output and report exist
# and are not older than its inputs — an interrupted loop continues where it stopped.
#
# Exit status (docs/loop.md "Exit status", docs/exit-codes.md "Loops"): 0 finished; 1 stopped by a
# failing step — the files of the earlier steps are saved and valid, rerunning resumes; 2 bad input
# or options, nothing run; 128+N killed by signal N (Ctrl-C: 130), also resumable.
set -euo pipefail
# The whole script is one compound command ({ ... exit; }): bash reads all of it before it runs
# any, so editing this file while a loop runs (a git pull during a long study) cannot change what
# that loop does. Bash otherwise reads a script as it goes, and a running loop failed mid-way when
# lines were added above where it was (cli.loop_edit).
{

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
PY="${PYTHON:-}"
if [ -z "$PY" ]; then
  if [ -x /usr/bin/python3 ]; then PY=/usr/bin/python3; else PY=python3; fi
fi
ctl() { "$PY" "$here/loopctl.py" "$@"; }

die() { echo "loop: error: $*" >&2; exit 2; }

# The one set of loop defaults (Makefile.cases passes only what the user sets).
CASE="" MESH="" P="" METHOD="" MODE="" STEPS="6" GROWTH="1.5" OUT="" MAXDOFS="0" FRACTION="0.3" FF_BY=""
SEED="1" JITTER="0" SMOOTH_BAMG="no" PICTURES="yes" WINDOW="" THESIS_KEY="" CHECK_ONLY=0 GEOMETRY="" ORDER=""
MAX_ANISO=""  # size-solve --max-anisotropy; empty = its default (25)
ERROR_MODEL=""  # estimate-frame --model polynomial|thesis; empty = its default (polynomial)
R_MAX=""      # goal mode: size-solve --r-max, the largest refinement factor per step; empty = its default (20)
C_MAX=""      # goal mode: size-solve --c-max, the largest coarsening factor per step; empty = its default (4)
SIZE_GRADATION=""  # size-solve --gradation G (lpcvt, bamg): h at most G x a face neighbour's; empty = its default (off)
PHASES=""        # lpcvt --phases N (lattice phases tried; empty: lpcvt's default, auto)
WALLS=""         # quadsmooth --walls slide|fixed (lpcvt path; empty: quadsmooth's default, slide)
START_JITTER="0"  # > 0: the start mesh's interior nodes moved at random from SEED (meshconvert --jitter)
FIT_FRAME="raw"   # lpcvt: quadsmooth fits size-solve's frame (raw), the one lpcvt meshed (meshed: --write-frame) or that one never coarser than raw (capped: quadsmooth --fit-frame capped)
while [ $# -gt 0 ]; do
  opt="$1"
  case "$opt" in
    --check-only) CHECK_ONLY=1; shift; continue ;;
    -h|--help) sed -n '2,/^# or options, nothing run/s/^# \{0,1\}//p' "${BASH_SOURCE[0]}"; exit 0 ;;
  esac
  [ $# -ge 2 ] || die "option $opt needs a value"
  val="$2"; shift 2
  case "$opt" in
    --case) CASE="$val" ;; --mesh) MESH="$val" ;; --p) P="$val" ;; --method) METHOD="$val" ;;
    --mode) MODE="$val" ;; --steps) STEPS="$val" ;; --growth) GROWTH="$val" ;; --out) OUT="$val" ;;
    --maxdofs) MAXDOFS="$val" ;; --fraction) FRACTION="$val" ;; --ff-by) FF_BY="$val" ;;
    --seed) SEED="$val" ;; --jitter) JITTER="$val" ;; --smooth-bamg) SMOOTH_BAMG="$val" ;; --pictures) PICTURES="$val" ;;
    --window) WINDOW="$val" ;; --thesis-case) THESIS_KEY="$val" ;;
    --geometry) GEOMETRY="$val" ;; --order) ORDER="$val" ;; --max-anisotropy) MAX_ANISO="$val" ;;
    --start-jitter) START_JITTER="$val" ;; --phases) PHASES="$val" ;; --walls) WALLS="$val" ;; --fit-frame) FIT_FRAME="$val" ;;
    --r-max) R_MAX="$val" ;; --c-max) C_MAX="$val" ;; --size-gradation) SIZE_GRADATION="$val" ;;
    --error-model) ERROR_MODEL="$val" ;;
    *) die "unknown option $opt (see docs/loop.md)" ;;
  esac
done

# ------------------------------------------------------------------ checks, before any work
is_uint() { [[ "$1" =~ ^[0-9]+$ ]]; }
is_num() { [[ "$1" =~ ^[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$|^[0-9]+\.$ ]]; }

case "$METHOD" in
  lpcvt|bamg|fixed-fraction|uniform) ;;
  "") die "METHOD is not set (--method lpcvt|bamg|fixed-fraction|uniform; with make: METHOD=...)" ;;
  *) die "unknown METHOD '$METHOD' (use lpcvt, bamg, fixed-fraction or uniform)" ;;
esac
case "$MODE" in
  feature|goal) ;;
  "") die "MODE is not set (--mode feature|goal; with make: MODE=...)" ;;
  *) die "unknown MODE '$MODE' (use feature or goal)" ;;
esac
[ -n "$CASE" ] || die "CASE is not set (a case file: --case examples/cases/sshock.json; with make: CASE=...)"
if [ ! -f "$CASE" ] && [[ "$CASE" != */* ]]; then
  # short name: CASE=sshock is ./sshock.json when that exists (your own case), else the shipped one
  if [ -f "${CASE%.json}.json" ]; then
    CASE="${CASE%.json}.json"
  elif [ -f "$root/examples/cases/${CASE%.json}.json" ]; then
    CASE="$root/examples/cases/${CASE%.json}.json"
  fi
fi
if [ ! -f "$CASE" ]; then
  avail="$(cd "$root/examples/cases" 2>/dev/null && ls *.json 2>/dev/null | sed 's/\.json$//' | paste -sd ' ' || true)"
  die "unknown CASE '$CASE': no such file${avail:+ (shipped cases: $avail)}"
fi
msg="$(ctl check-case "$CASE" "$MODE" 2>&1)" || die "$msg"
[ -n "$MESH" ] || die "MESH is not set (the start mesh: --mesh examples/meshes/square16.msh; with make: MESH=...)"
[ -f "$MESH" ] || die "MESH '$MESH': no such file"
is_uint "$P" || die "P='$P': the DG degree must be an integer"
is_uint "$STEPS" || die "STEPS='$STEPS': must be a non-negative integer (number of adaptations)"
is_num "$GROWTH" && "$PY" -c "import sys; sys.exit(0 if float('$GROWTH') > 1 else 1)" \
  || die "GROWTH='$GROWTH': must be a number > 1 (complexity growth per step)"
is_num "$MAXDOFS" || die "MAXDOFS='$MAXDOFS': must be a non-negative number (0 = no limit)"
is_num "$FRACTION" && "$PY" -c "import sys; f=float('$FRACTION'); sys.exit(0 if 0 < f <= 1 else 1)" \
  || die "FRACTION='$FRACTION': must be in (0, 1]"
is_uint "$SEED" || die "SEED='$SEED': must be a non-negative integer"
is_num "$JITTER" || die "JITTER='$JITTER': must be a non-negative number (lpcvt --jitter, target edges)"
[ -z "$MAX_ANISO" ] || { is_num "$MAX_ANISO" && "$PY" -c "import sys; sys.exit(0 if float('$MAX_ANISO') >= 1 else 1)"; } \
  || die "MAX_ANISOTROPY='$MAX_ANISO': must be a number >= 1 (size-solve --max-anisotropy, largest h1/h2)"
# size-solve's factors > 1, each when set: NAME:value:option:what it bounds
for rc in "R_MAX:$R_MAX:--r-max:the largest refinement factor of a cell's area per step" \
          "C_MAX:$C_MAX:--c-max:the largest coarsening factor of a cell's area per step" \
          "SIZE_GRADATION:$SIZE_GRADATION:--gradation:the largest ratio of h between face neighbours"; do
  IFS=: read -r rcn rcv rco rcw <<< "$rc"
  [ -z "$rcv" ] || { is_num "$rcv" && "$PY" -c "import sys; sys.exit(0 if float('$rcv') > 1 else 1)"; } \
    || die "$rcn='$rcv': must be a number > 1 (size-solve $rco: $rcw)"
done
rcm=()  # goal mode only: R_MAX / C_MAX when set
[ "$MODE" != goal ] || rcm=(${R_MAX:+r_max="$R_MAX"} ${C_MAX:+c_max="$C_MAX"})
is_num "$START_JITTER" && "$PY" -c "import sys; sys.exit(0 if float('$START_JITTER') <= 0.45 else 1)" \
  || die "START_JITTER='$START_JITTER': must be a number in [0, 0.45] (meshconvert --jitter: the largest move over the shortest edge)"
[ -z "$PHASES" ] || { is_uint "$PHASES" && [ "$PHASES" -le 16 ]; } \
  || die "PHASES='$PHASES': must be an integer in [0, 16] (lpcvt --phases: lattice phases tried, 0 = auto)"
[ -z "$WALLS" ] || [ "$WALLS" = slide ] || [ "$WALLS" = fixed ] \
  || die "WALLS='$WALLS': must be slide or fixed (quadsmooth --walls: wall nodes slide along straight walls or stay)"
[ -z "$ERROR_MODEL" ] || [ "$ERROR_MODEL" = polynomial ] || [ "$ERROR_MODEL" = thesis ] \
  || die "ERROR_MODEL='$ERROR_MODEL': must be polynomial or thesis (estimate-frame --model: stretch and error constant from the whole (p+1)-th term, or the thesis's A1, A2 bound)"
thesis_floor=()  # ERROR_MODEL=thesis: the thesis's eqs. 5.9-5.16 exactly, without the observed-error floor
[ "$ERROR_MODEL" != thesis ] || thesis_floor=(--observed-floor 0)
[ -n "$OUT" ] || die "OUT is not set (the run directory: --out DIR; with make: OUT=DIR)"
case "$SMOOTH_BAMG" in yes|no) ;; *) die "SMOOTH_BAMG='$SMOOTH_BAMG': use yes or no" ;; esac
case "$PICTURES" in yes|no) ;; *) die "PICTURES='$PICTURES': use yes or no" ;; esac
case "$FIT_FRAME" in raw|meshed|capped) ;; *) die "FIT_FRAME='$FIT_FRAME': use raw (size-solve's frame), meshed (the frame lpcvt meshed) or capped (meshed, never coarser than raw)" ;; esac
if [ -n "$GEOMETRY" ]; then  # the true geometry (docs/curved.md): meshes snapped to it, cells of order ORDER
  [ -f "$GEOMETRY" ] || die "GEOMETRY '$GEOMETRY': no such file"
  GEOMETRY="$(cd "$(dirname "$GEOMETRY")" && pwd)/$(basename "$GEOMETRY")"
  if [ -z "$ORDER" ]; then ORDER=$(( P < 1 ? 1 : (P > 6 ? 6 : P) )); fi
  [[ "$ORDER" =~ ^[1-6]$ ]] || die "ORDER='$ORDER': the geometric order must be 1..6"
fi
if [ -z "$FF_BY" ]; then
  if [ "$MODE" = goal ]; then FF_BY=dwr; else FF_BY=A1h; fi
fi
if [ "$METHOD" = fixed-fraction ]; then  # a 1-component cell field of what refine reads
  if [ "$MODE" = goal ]; then ffok="dwr"; else ffok="A1h rho B A1 A2 theta phi"; fi
  [[ " $ffok " == *" $FF_BY "* ]] || die "FF_BY='$FF_BY': use one of: $ffok (MODE=$MODE)"
fi
if [ -n "$WINDOW" ]; then  # the pictures' close-up: x0,x1,y0,y1 with x0 < x1, y0 < y1
  ctl check-window "$WINDOW" || die "WINDOW='$WINDOW': give x0,x1,y0,y1 with x0 < x1 and y0 < y1"
fi

# tools this loop needs
tools=(dgsolve)
if [ -n "$GEOMETRY" ] || [ "$START_JITTER" != 0 ]; then tools+=(meshconvert); fi
case "$METHOD" in
  uniform) tools+=(refine) ;;
  fixed-fraction) if [ "$MODE" = goal ]; then tools+=(adjoint refine); else tools+=(estimate-frame refine); fi ;;
  lpcvt) tools+=(estimate-frame size-solve lpcvt recombine quadsmooth) ;;
  bamg) tools+=(estimate-frame size-solve bamgquad); [ "$SMOOTH_BAMG" = yes ] && tools+=(quadsmooth) ;;
esac
if [ "$MODE" = goal ] && [ "$METHOD" != uniform ] && [[ " ${tools[*]} " != *" adjoint "* ]]; then tools+=(adjoint); fi
# called directly from a checkout with no tools on PATH: the tools built in place (build/bin)
if ! command -v dgsolve >/dev/null 2>&1 && [ -x "$root/build/bin/dgsolve" ]; then PATH="$root/build/bin:$PATH"; fi
missing=()
for t in "${tools[@]}"; do command -v "$t" >/dev/null 2>&1 || missing+=("$t"); done
if [ ${#missing[@]} -gt 0 ]; then
  die "tool(s) not found: ${missing[*]} (needed by METHOD=$METHOD MODE=$MODE). Build them (cmake --build build --target ${missing[*]}) and put their directory on PATH (make -f Makefile.cases loop does: BIN=build/bin by default)"
fi
# the DG degree range is the library's, as dgsolve --help states it ("degree P (1..8)"); goal mode
# solves the adjoint at p + 1, so its largest p is one less (lib/dg/degree.hpp)
range="$(dgsolve --help 2>/dev/null | grep -o 'degree P ([0-9]*\.\.[0-9]*)' | grep -o '[0-9]*\.\.[0-9]*' || true)"
[ -n "$range" ] || die "cannot read the degree range from 'dgsolve --help' ($(command -v dgsolve))"
pmin=${range%..*}; pmax=${range#*..}
if [ "$MODE" = goal ] && [ "$METHOD" != uniform ]; then pmax=$((pmax - 1)); fi
if [ "$P" -lt "$pmin" ] || [ "$P" -gt "$pmax" ]; then
  die "P=$P: the DG degree must be $pmin..$pmax$([ "$MODE" = goal ] && [ "$METHOD" != uniform ] && echo " in goal mode (the adjoint solves at p+1)")"
fi
# MESH and CASE: one p = 1 solve written nowhere reads and validates MESH (an all-quad mesh) and
# checks what only the solver can (expressions, boundary names, the functional). Exit 1 (a valid
# output, e.g. not converged) passes; 2 and 3 are bad input, refused before OUT exists. With
# GEOMETRY, MESH's boundary must snap to it.
rc=0; err="$(dgsolve -q "$MESH" -c "$CASE" -p 1 -o /dev/null 2>&1)" || rc=$?
if [ $rc -gt 1 ]; then
  err="${err#dgsolve: }"
  case "$err" in "$MESH: "*) die "MESH: $err" ;; *) die "CASE on MESH: $err" ;; esac
fi
if [ -n "$GEOMETRY" ]; then
  err="$(meshconvert -q "$MESH" --geometry "$GEOMETRY" --order 1 -o /dev/null 2>&1)" || die "GEOMETRY: ${err#meshconvert: }"
else
  # a curved MESH (Gmsh -order 2) without GEOMETRY: refine cannot split it (before, uniform and
  # fixed-fraction failed inside step 0, after this check), and lpcvt / bamg mesh its polygon (the
  # steps after 0 straight-sided, silently)
  q="$(command -v meshquality >/dev/null 2>&1 && meshquality -q "$MESH" 2>/dev/null | grep -o '"geometric_order": *[0-9]*' | grep -o '[0-9]*$' || true)"
  if [ -n "$q" ] && [ "$q" -gt 1 ]; then
    curved_start=yes  # step 0's solution is curved: size-solve takes the vertex view of its dwr.msh
    case "$METHOD" in
      uniform|fixed-fraction)
        die "MESH '$MESH' is curved (geometric order $q) and no GEOMETRY is given: refine splits straight-sided cells only; start from its straight view (meshconvert $MESH --order 1 -o STRAIGHT.msh), with GEOMETRY=FILE.geo to keep the boundary curved (docs/curved.md)" ;;
      *)
        echo "loop: warning: MESH '$MESH' is curved (geometric order $q) but no GEOMETRY is given: step 0 is solved on the curved cells, the adapted meshes of steps 1.. are straight-sided on MESH's polygon; to keep the boundary curved start from MESH's straight view (meshconvert $MESH --order 1 -o STRAIGHT.msh) with GEOMETRY=FILE.geo (docs/curved.md)" >&2 ;;
    esac
  fi
fi
if [ "$PICTURES" = yes ] && ! command -v meshplot >/dev/null 2>&1; then
  echo "loop: note: meshplot not found; the run will have no mesh pictures" >&2
fi
# OUT: an existing directory, or a path mkdir -p can make (checked here so that `check` refuses
# what the run would; nothing is created before the check passes)
if [ -e "$OUT" ] && [ ! -d "$OUT" ]; then
  die "cannot create OUT '$OUT': it exists and is not a directory"
fi
out_base="$OUT"
while [ ! -e "$out_base" ]; do out_base="$(dirname "$out_base")"; done
if [ ! -d "$out_base" ] || [ ! -w "$out_base" ]; then
  die "cannot create OUT '$OUT': '$out_base' is not a writable directory"
fi
tools_dir="$(dirname "$(command -v dgsolve)")"
[ "$CHECK_ONLY" = 1 ] && { echo "loop: inputs OK (case $(cd "$(dirname "$CASE")" && pwd)/$(basename "$CASE"); tools: ${tools[*]} from $tools_dir)"; exit 0; }

# OpenMP threads that wait sleep instead of spinning (docs/bench-dgsolve.md: with libgomp's
# default the idle thread spins through the sequential ILU sweeps; 2.36 s instead of 1.28 s for
# a p = 3 solve on a shared machine). An OMP_WAIT_POLICY set by the caller wins.
export OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-passive}"

# Under `make -jN` without OMP_NUM_THREADS, share the cores: nproc / N threads per tool (>= 1).
if [ -z "${OMP_NUM_THREADS:-}" ] && [[ " ${MAKEFLAGS:-} " =~ \ -j([0-9]*) ]]; then
  jobs="${BASH_REMATCH[1]:-0}"
  threads=1
  [ "$jobs" -gt 0 ] && threads=$(( $(nproc) / jobs ))
  [ "$threads" -ge 1 ] || threads=1
  export OMP_NUM_THREADS=$threads
fi

# ------------------------------------------------------------------ run directory
# one line on failure (mkdir's own message was printed first): why, from mkdir's, without its prefix
if ! err="$(mkdir -p "$OUT" 2>&1)"; then
  die "cannot create OUT '$OUT': ${err##*: }"
fi
OUT="$(cd "$OUT" && pwd)"
CASE="$(cd "$(dirname "$CASE")" && pwd)/$(basename "$CASE")"
exec 9>"$OUT/.lock"
flock -n 9 || die "another loop is running in $OUT"
# under the lock: no other loop writes here. Temporary files of writes that a signal cut short
# (tools' .NAME.tmp-PID.ext, the loop's own NAME.tmp-PID) are removed; loop.done goes once the
# parameters are accepted (below), until the steps have finished again.
find "$OUT" \( -name '.*.tmp-[0-9]*' -o -name '*.tmp-[0-9]*' \) -type f -delete 2>/dev/null || true
# a signal to the loop: the running tool is stopped first (its temporary file is removed by the
# next run), then the loop exits with 128 + N
CHILD=""
on_signal() {
  trap - INT TERM HUP
  if [ -n "$CHILD" ]; then kill -TERM "$CHILD" 2>/dev/null || true; wait "$CHILD" 2>/dev/null || true; fi
  echo "loop: stopped by a signal (status $1): the finished steps in $OUT are valid; rerun the same command to resume" >&2
  exit "$1"
}
trap 'on_signal 130' INT
trap 'on_signal 143' TERM
trap 'on_signal 129' HUP
# the case by its contents (re-indenting it or editing its description keeps the run's identity);
# the bytes' hash for runs made before that
case_sum="$(ctl case-sum "$CASE")"
case_bytes="$(sha256sum "$CASE" | cut -c1-16)"
mesh_sum="$(sha256sum "$MESH" | cut -c1-16)"
# STEPS and MAXDOFS only say where to stop: a finished run can be continued with more steps.
jit=()  # JITTER joins the run's parameters only when used (older runs have none)
[ "$JITTER" = 0 ] || jit=(jitter="$JITTER")
sjit=()
[ "$START_JITTER" = 0 ] || sjit=(start_jitter="$START_JITTER")
fitf=()  # likewise FIT_FRAME, only when not the default and only for the method it changes
[ "$FIT_FRAME" = raw ] || [ "$METHOD" != lpcvt ] || fitf=(fit_frame="$FIT_FRAME")
phs=()  # likewise PHASES
[ -z "$PHASES" ] || [ "$METHOD" != lpcvt ] || phs=(phases="$PHASES")
wls=()  # likewise WALLS
[ -z "$WALLS" ] || [ "$METHOD" != lpcvt ] || wls=(walls="$WALLS")
sgr=()  # likewise SIZE_GRADATION, for the methods that call size-solve
case "$METHOD" in lpcvt|bamg) sgr=(${SIZE_GRADATION:+size_gradation="$SIZE_GRADATION"}) ;; esac
# the tools' provenance ("quadapt 0.1.0, commit SHA[ (dirty ...)]", as their reports give it):
# recorded at the start; a resume with other tools is warned about, not refused (loopctl params)
tools_id="$(dgsolve --version 2>/dev/null | awk 'NR == 1 {v = $NF} NR == 2 {sub(/^commit /, ""); c = $0} END {print "quadapt " v ", commit " c}')"
msg="$(ctl params "$OUT/loop.json" tools="$tools_id" case="$CASE" case_sha256="$case_sum" case_sha256_bytes="$case_bytes" mesh_sha256="$mesh_sum" p="$P" \
  method="$METHOD" mode="$MODE" growth="$GROWTH" fraction="$FRACTION" ff_by="$FF_BY" seed="$SEED" ${jit[@]+"${jit[@]}"} \
  smooth_bamg="$SMOOTH_BAMG" ${GEOMETRY:+geometry="$GEOMETRY" geometric_order="$ORDER"} \
  ${MAX_ANISO:+max_anisotropy="$MAX_ANISO"} ${ERROR_MODEL:+error_model="$ERROR_MODEL"} ${sjit[@]+"${sjit[@]}"} ${fitf[@]+"${fitf[@]}"} ${phs[@]+"${phs[@]}"} ${wls[@]+"${wls[@]}"} ${rcm[@]+"${rcm[@]}"} \
  ${sgr[@]+"${sgr[@]}"} 2>&1)" || die "$msg"
[ -z "$msg" ] || echo "$msg" >&2
# only now: a run refused for other parameters (status 2) keeps its loop.done (it was removed before
# the check, so a finished run looked unfinished to the study targets: a new-user review, session 38)
rm -f "$OUT/loop.done"

name="$(basename "$(dirname "$OUT")")/$(basename "$OUT")"
say() { echo "[$name] $*"; }

# run_tool STEPDIR LOGNAME OUTPUT INPUTS... -- COMMAND...
# Skips when OUTPUT and its report exist and no input is newer; else runs COMMAND with its
# (CASE is not listed as an input: its contents are the run's, checked above by case_sha256, so its
# file time says nothing; a touched or re-saved case file used to redo every step.)
# stderr in STEPDIR/LOGNAME.log and prints one line.
record_warnings() {  # record_warnings STEPDIR TOOL RC
  local dir="$1" tool="$2" rc="$3" log="$1/$2.log" w=() line content=""
  # the usual case without a process: exit 0, no "warning" in the log, no earlier warnings
  # (each fork costs ~1-2 ms; a loop runs ~40 tools)
  if [ "$rc" -eq 0 ] && [ ! -e "$dir/warnings.txt" ]; then
    IFS= read -r -d '' content < "$log" || true
    [[ ${content,,} != *warning:* ]] && return 0
  fi
  while IFS= read -r line; do w+=("$line"); done < <(
    { grep -i -E '(^|: )warning:' "$log" | sed -E 's/^([^ :]+: )?warning: //I'
      [ "$rc" -eq 1 ] && tail -n 1 "$log" | sed -E 's/^[^ :]+: //'
    } 2>/dev/null | awk '!seen[$0]++' | head -n 3)
  local f="$dir/warnings.txt" tmp="$dir/warnings.txt.tmp-$$"
  { [ -f "$f" ] && awk -v p="$tool: " 'index($0, p) != 1' "$f" || true; } > "$tmp"
  for line in "${w[@]+"${w[@]}"}"; do
    echo "$tool: $line" >> "$tmp"
    echo "loop: warning: ${dir##*/}: $tool: $line" >&2
  done
  if [ -s "$tmp" ]; then mv -f "$tmp" "$f"; else rm -f "$tmp" "$f"; fi
}

run_tool() {
  local dir="$1" logname="$2" out="$3"; shift 3
  local inputs=()
  while [ "$1" != "--" ]; do inputs+=("$1"); shift; done
  shift
  local report="${out%.*}.json" fresh=1 i
  if [ -s "$out" ] && [ -s "$report" ]; then
    for i in "${inputs[@]}"; do [ "$i" -nt "$out" ] && fresh=0; done
  else
    fresh=0
  fi
  if [ $fresh = 1 ]; then
    return 0
  fi
  local t0 t1 rc=0
  t0=${EPOCHREALTIME/[.,]/}  # microseconds, without a process
  # in the background, waited for: bash runs a trap only between commands, so a foreground tool
  # would keep running after a TERM to the loop (and hold the lock, fd 9, which it does not get)
  "$@" 2>"$dir/$logname.log" 9>&- &
  CHILD=$!
  wait "$CHILD" || rc=$?
  CHILD=""
  t1=${EPOCHREALTIME/[.,]/}
  if [ $rc -eq 0 ] || { [ $rc -eq 1 ] && [ -s "$out" ]; }; then
    # Warnings (a tool's "warning:" lines, and exit 1 = a valid output saved but a failure
    # reported, e.g. not converged) go on: shown here and kept in step-K/warnings.txt, which the
    # convergence table's `warnings` column reads.
    record_warnings "$dir" "$logname" $rc
  elif [ $rc -ne 0 ]; then
    echo "loop: error: ${dir##*/}: $logname failed (exit $rc):" >&2
    tail -n 5 "$dir/$logname.log" | sed 's/^/    /' >&2
    echo "  full log: $dir/$logname.log" >&2
    exit 1  # the EXIT trap says which steps are saved
  fi
  local cs=$(((t1 - t0 + 5000) / 10000)) secs  # hundredths of a second (no awk, no locale)
  printf -v secs '%d.%02d' $((cs / 100)) $((cs % 100))
  printf '[%s] %s: %-14s %7s s\n' "$name" "${dir##*/}" "$logname" "$secs"
}

link_into() {  # link_into SRC DST: DST = SRC (hard link, else copy), atomically; SRC in OUT
  local tmp="$2.tmp-$$"
  ln -f "$1" "$tmp" 2>/dev/null || cp -f "$1" "$tmp"
  mv -f "$tmp" "$2"
}
copy_into() {  # copy_into SRC DST: DST = a copy of SRC, atomically (the user's MESH: a hard link
  local tmp="$2.tmp-$$"  # would let an edit of either change the other)
  cp -f "$1" "$tmp"
  mv -f "$tmp" "$2"
}

say "CASE=$CASE P=$P METHOD=$METHOD MODE=$MODE STEPS=$STEPS GROWTH=$GROWTH MAXDOFS=$MAXDOFS -> $OUT"
say "tools: $tools_dir ($tools_id)"
mkdir -p "$OUT/step-0"
START="$MESH"
if [ "$START_JITTER" != 0 ]; then
  # another start: MESH's interior nodes moved at random from SEED (the same SEED, the same mesh)
  run_tool "$OUT/step-0" jitter "$OUT/step-0/start-jittered.msh" "$MESH" -- \
    meshconvert "$MESH" --jitter "$START_JITTER" --seed "$SEED" -o "$OUT/step-0/start-jittered.msh"
  START="$OUT/step-0/start-jittered.msh"
fi
if [ -n "$GEOMETRY" ]; then
  # step-K/straight.msh: the straight-sided mesh with its boundary nodes on the true curves (what
  # refine and the frame tools work on); step-K/mesh.msh: the same cells of order ORDER (dgsolve's)
  on_geometry() {  # on_geometry DIR SRC DST-DIR
    run_tool "$1" flat "$1/next-flat.msh" "$2" -- meshconvert "$2" --order 1 -o "$1/next-flat.msh"
    run_tool "$1" snap "$1/next-straight.msh" "$1/next-flat.msh" "$GEOMETRY" -- \
      meshconvert "$1/next-flat.msh" --geometry "$GEOMETRY" --order 1 -o "$1/next-straight.msh"
    run_tool "$1" curve "$1/next-curved.msh" "$1/next-straight.msh" -- \
      meshconvert "$1/next-straight.msh" --geometry "$GEOMETRY" --order "$ORDER" --straight-fallback -o "$1/next-curved.msh"
    mkdir -p "$3"
    if [ ! -s "$3/mesh.msh" ] || [ "$1/next-curved.msh" -nt "$3/mesh.msh" ]; then
      link_into "$1/next-straight.msh" "$3/straight.msh"
      link_into "$1/next-curved.msh" "$3/mesh.msh"
    fi
  }
  mkdir -p "$OUT/step-0/start"
  if [ ! -s "$OUT/step-0/start/mesh.msh" ]; then copy_into "$START" "$OUT/step-0/start/mesh.msh"; fi
  on_geometry "$OUT/step-0/start" "$OUT/step-0/start/mesh.msh" "$OUT/step-0"
elif [ ! -s "$OUT/step-0/mesh.msh" ]; then copy_into "$START" "$OUT/step-0/mesh.msh"; fi

k=0
last=0
finished=0
# From here on the run directory holds finished steps: any failure stops the loop with status 1
# (the steps before k are saved and valid; a rerun of the same command resumes at the first
# missing file). A signal keeps its own status (128+N).
stopped() {
  local rc=$?
  [ "$rc" -eq 0 ] && return 0
  [ "$rc" -ge 128 ] && exit "$rc"
  if [ -e "$OUT/loop.done" ] && [ "$finished" = 1 ]; then
    echo "loop: the steps finished (loop.done) but what followed failed (status 1)" >&2
    exit 1
  fi
  local saved="the files written so far"
  [ "$k" -eq 1 ] && saved="step-0 and the files written so far"
  [ "$k" -gt 1 ] && saved="step-0 .. step-$((k - 1)) and the files written so far"
  echo "loop: stopped in step-$k (status 1): $saved in $OUT are valid; rerun the same command to resume" >&2
  exit 1
}
trap stopped EXIT
while :; do
  d="$OUT/step-$k"
  mkdir -p "$d"
  run_tool "$d" dgsolve "$d/sol.msh" "$d/mesh.msh" -- dgsolve "$d/mesh.msh" -c "$CASE" -p "$P" -o "$d/sol.msh"
  say "step-$k: $(ctl summary "$d/sol.json")"
  last=$k
  ctl table "$OUT" --last $k >/dev/null
  stop=no
  if [ $k -ge "$STEPS" ]; then
    stop=yes; why="STEPS=$STEPS reached"
  elif [ "$(ctl stop "$OUT" $k "$MAXDOFS" "$METHOD" "$GROWTH")" = stop ]; then
    stop=yes; why="the DOF limit MAXDOFS=$MAXDOFS (this step's DOFs reach it, or the next step's would pass 1.25x it; docs/loop.md \"Stopping\")"
  fi
  if [ $stop = yes ]; then
    say "stopping after step-$k: $why"
    # goal mode: the adjoint on the final mesh too (its time and the error estimate for the table)
    if [ "$MODE" = goal ] && [ "$METHOD" != uniform ]; then
      run_tool "$d" adjoint "$d/dwr.msh" "$d/sol.msh" -- adjoint "$d/sol.msh" -c "$CASE" -o "$d/dwr.msh"
    fi
    break
  fi
  # ---- adapt: step k -> step k+1's mesh
  next="$d/adapted.msh"
  case "$METHOD" in
    uniform)
      if [ -n "$GEOMETRY" ]; then
        run_tool "$d" refine "$d/adapted.msh" "$d/straight.msh" -- refine "$d/straight.msh" --uniform \
          --geometry "$GEOMETRY" -o "$d/adapted.msh"
      else
        run_tool "$d" refine "$d/adapted.msh" "$d/mesh.msh" -- refine "$d/mesh.msh" --uniform -o "$d/adapted.msh"
      fi ;;
    fixed-fraction)
      # with GEOMETRY: refine splits the vertex view (hanging nodes kept, interior edges straight)
      # and snaps the new boundary nodes; the next step curves its boundary cells
      geo=()
      [ -n "$GEOMETRY" ] && geo=(--geometry "$GEOMETRY")
      if [ "$MODE" = goal ]; then
        run_tool "$d" adjoint "$d/dwr.msh" "$d/sol.msh" -- adjoint "$d/sol.msh" -c "$CASE" -o "$d/dwr.msh"
        ind="$d/dwr.msh"
        if [ -n "$GEOMETRY" ]; then
          ind="$d/dwr-straight.msh"
          run_tool "$d" straight "$ind" "$d/dwr.msh" -- meshconvert "$d/dwr.msh" --order 1 -o "$ind"
        fi
        run_tool "$d" refine "$d/adapted.msh" "$ind" -- \
          refine "$ind" --fraction "$FRACTION" --by "$FF_BY" ${geo[@]+"${geo[@]}"} -o "$d/adapted.msh"
      else
        run_tool "$d" estimate-frame "$d/shape.msh" "$d/sol.msh" -- estimate-frame "$d/sol.msh" -o "$d/shape.msh" ${ERROR_MODEL:+--model "$ERROR_MODEL"} ${thesis_floor[@]+"${thesis_floor[@]}"}
        ind="$d/shape.msh"
        if [ "$FF_BY" = A1h ]; then  # A1 |K|^((p+1)/2), the thesis solver's indicator (ff-indicator.py)
          ind="$d/indicator.msh"
          run_tool "$d" ff-indicator "$ind" "$d/shape.msh" -- "$PY" "$here/ff-indicator.py" "$d/shape.msh" "$P" -o "$ind"
        fi
        run_tool "$d" refine "$d/adapted.msh" "$ind" -- \
          refine "$ind" --fraction "$FRACTION" --by "$FF_BY" ${geo[@]+"${geo[@]}"} -o "$d/adapted.msh"
      fi ;;
    lpcvt|bamg)
      # estimate-frame reads the curved solution itself (the reconstruction on the map; its
      # SHAPE is the vertex view the frame tools mesh). Until session 31 it read the vertex view of
      # sol.msh (meshconvert --order 1), where u_h's values sit on straight cells: at a curved wall
      # the sagitta then showed as a misfit, and the observed-error floor raised B of the wall's
      # boundary-layer cells 64x (cylinder p = 3, step 5: 475 of 980 wall cells; 2 on the map)
      geo=() curved=""
      [ -n "$GEOMETRY" ] && geo=(--geometry "$GEOMETRY") curved=yes
      [ "$k" = 0 ] && [ "${curved_start:-}" = yes ] && curved=yes  # a curved MESH without GEOMETRY
      run_tool "$d" estimate-frame "$d/shape.msh" "$d/sol.msh" -- estimate-frame "$d/sol.msh" -o "$d/shape.msh" ${ERROR_MODEL:+--model "$ERROR_MODEL"} ${thesis_floor[@]+"${thesis_floor[@]}"}
      if [ "$MODE" = goal ]; then
        run_tool "$d" adjoint "$d/dwr.msh" "$d/sol.msh" -- adjoint "$d/sol.msh" -c "$CASE" -o "$d/dwr.msh"
        dwr="$d/dwr.msh"
        if [ -n "$curved" ]; then  # size-solve too (was: refused the curved indicator file, every step 0)
          dwr="$d/dwr-straight.msh"
          run_tool "$d" straight-dwr "$dwr" "$d/dwr.msh" -- meshconvert "$d/dwr.msh" --order 1 -o "$dwr"
        fi
        run_tool "$d" size-solve "$d/frame.msh" "$d/shape.msh" "$dwr" -- \
          size-solve "$d/shape.msh" --growth "$GROWTH" --dwr "$dwr" ${MAX_ANISO:+--max-anisotropy "$MAX_ANISO"} \
            ${R_MAX:+--r-max "$R_MAX"} ${C_MAX:+--c-max "$C_MAX"} ${SIZE_GRADATION:+--gradation "$SIZE_GRADATION"} -o "$d/frame.msh"
      else
        run_tool "$d" size-solve "$d/frame.msh" "$d/shape.msh" -- \
          size-solve "$d/shape.msh" --growth "$GROWTH" ${MAX_ANISO:+--max-anisotropy "$MAX_ANISO"} \
            ${SIZE_GRADATION:+--gradation "$SIZE_GRADATION"} -o "$d/frame.msh"
      fi
      if [ "$METHOD" = lpcvt ]; then
        fit="$d/frame.msh" wf=() qf=()
        [ "$FIT_FRAME" != capped ] || qf=(--fit-frame capped)  # quadsmooth caps the filtered frame itself
        if [ "$FIT_FRAME" = meshed ]; then  # quadsmooth fits the frame lpcvt meshed (after its filters)
          fit="$d/meshed-frame.msh" wf=(--write-frame "$fit")
          # a resumed step without it, or with one older than tri.msh (lpcvt stopped between the
          # two): lpcvt again
          { [ -f "$fit" ] && ! [ "$d/tri.msh" -nt "$fit" ]; } || rm -f "$d/tri.msh"
        fi
        run_tool "$d" lpcvt "$d/tri.msh" "$d/frame.msh" -- lpcvt "$d/frame.msh" -o "$d/tri.msh" --seed "$SEED" --jitter "$JITTER" ${PHASES:+--phases "$PHASES"} ${wf[@]+"${wf[@]}"} ${geo[@]+"${geo[@]}"}
        # the tools' defaults: recombine matches in the metric of the frame lpcvt attached to
        # tri.msh (no node moves; docs/recombine.md)
        run_tool "$d" recombine "$d/quad.msh" "$d/tri.msh" -- recombine "$d/tri.msh" -o "$d/quad.msh"
        run_tool "$d" quadsmooth "$d/adapted.msh" "$d/quad.msh" "$fit" -- \
          quadsmooth "$d/quad.msh" -o "$d/adapted.msh" --frame "$fit" ${WALLS:+--walls "$WALLS"} ${qf[@]+"${qf[@]}"}
      else
        run_tool "$d" bamgquad "$d/quad.msh" "$d/frame.msh" -- bamgquad "$d/frame.msh" -o "$d/quad.msh" ${geo[@]+"${geo[@]}"}
        if [ "$SMOOTH_BAMG" = yes ]; then
          run_tool "$d" quadsmooth "$d/adapted.msh" "$d/quad.msh" -- quadsmooth "$d/quad.msh" -o "$d/adapted.msh"
        else
          next="$d/quad.msh"
        fi
      fi ;;
  esac
  # step k+1's mesh = this step's result (hard link), unless already up to date
  nd="$OUT/step-$((k + 1))"
  mkdir -p "$nd"
  if [ -n "$GEOMETRY" ]; then
    on_geometry "$d" "$next" "$nd"
  elif [ ! -s "$nd/mesh.msh" ] || [ "$next" -nt "$nd/mesh.msh" ]; then link_into "$next" "$nd/mesh.msh"; fi
  k=$((k + 1))
done

rows="$(ctl table "$OUT" --last $last)"
echo "$last" > "$OUT/loop.done.tmp-$$" && mv -f "$OUT/loop.done.tmp-$$" "$OUT/loop.done"
finished=1

# ------------------------------------------------------------------ pictures (optional)
if [ "$PICTURES" = yes ]; then
  "$here/pictures.sh" "$OUT" ${WINDOW:+--window "$WINDOW"} ${THESIS_KEY:+--thesis-case "$THESIS_KEY"}
fi
say "done: $rows solves; table $OUT/convergence.csv"
exit
}
