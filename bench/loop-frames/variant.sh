#!/usr/bin/env bash
# One mesher setting on one frame of a study loop, then one solve (and the adjoint for goal
# studies): the measurements of docs/lpcvt.md "Why smoothing 4 by default".
#
#   variant.sh BIN RUNS STUDY P STEP SETTING OUT
#
# FRAME = RUNS/STUDY/pP-lpcvt/step-STEP/frame.msh (a loop of `make -f Makefile.cases studies`).
# SETTING: "base" (the chain's defaults), "bamg" (bamgquad), "bamg-smooth" (bamgquad on the frame
# lpcvt --smooth 4 --gradation 0 writes with --write-frame), "fit-meshed" (the default chain with
# quadsmooth fitting the frame lpcvt meshed, its --write-frame, instead of FRAME), "recombine" followed
# by recombine options with '_' for spaces (e.g. recombine--interior-bonus_0), or lpcvt options with '_' for spaces
# (e.g. --smooth_4). Prints: STUDY pP sSTEP SETTING DOFs |functional error| sum|eta_K| (goal
# studies), or ... DOFs L2-error L2-error (feature studies). One OpenMP thread.
set -euo pipefail
BIN=$1 RUNS=$2 S=$3 P=$4 K=$5 V=$6 OUT=$7
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
export OMP_NUM_THREADS=1 PATH="$BIN:$PATH"
case $S in
  sshock-goal) C=$ROOT/examples/cases/sshock-advection.json ;;
  bl-goal) C=$ROOT/examples/cases/boundary-layer-advection.json ;;
  sshock-feature) C=$ROOT/examples/cases/sshock.json ;;
  bl-feature) C=$ROOT/examples/cases/boundary-layer.json ;;
  *) echo "variant.sh: unknown study '$S' (sshock-goal, bl-goal, sshock-feature, bl-feature)" >&2; exit 2 ;;
esac
F=$RUNS/$S/p$P-lpcvt/step-$K/frame.msh
[ -f "$F" ] || { echo "variant.sh: $F: no such frame" >&2; exit 2; }
d=$OUT/$S-p$P-s$K-$V
mkdir -p "$d"
case $V in
  bamg) bamgquad -q "$F" -o "$d/mesh.msh" ;;
  bamg-smooth)
    lpcvt -q "$F" -o "$d/tri.msh" --smooth 4 --gradation 0 --orientation frame --max-iterations 1 --max-cycles 1 --write-frame "$d/frame.msh"
    bamgquad -q "$d/frame.msh" -o "$d/mesh.msh" ;;
  *)
    # the L_p-CVT chain: lpcvt options (lp), recombine options (rc), the frame quadsmooth fits (SF)
    lp=() rc=() SF=$F
    case $V in
      base) ;;
      recombine*) t=${V#recombine}; read -r -a rc <<< "${t//_/ }" ;;
      fit-meshed) lp=(--write-frame "$d/frame.msh"); SF=$d/frame.msh ;;
      *) read -r -a lp <<< "${V//_/ }" ;;
    esac
    lpcvt -q "$F" -o "$d/tri.msh" ${lp[@]+"${lp[@]}"}
    recombine -q "$d/tri.msh" -o "$d/quad.msh" ${rc[@]+"${rc[@]}"}
    quadsmooth -q "$d/quad.msh" --frame "$SF" -o "$d/mesh.msh" ;;
esac
dgsolve -q "$d/mesh.msh" -c "$C" -p "$P" -o "$d/sol.msh"
case $S in
  *goal)
    adjoint -q "$d/sol.msh" -c "$C" -o "$d/dwr.msh" --report "$d/dwr.json"
    python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(sys.argv[2], d['dofs'], '%.4g' % abs(d['functional_error']), '%.4g' % d['sum_eta'])" "$d/dwr.json" "$S p$P s$K $V" ;;
  *)
    python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(sys.argv[2], d['dofs'], '%.4g' % d['l2_error'], '%.4g' % d['l2_error'])" "$d/sol.json" "$S p$P s$K $V" ;;
esac
