#!/usr/bin/env bash
# Install quadapt's build and run-time dependencies from Debian packages (idempotent).
# Usage: sudo scripts/install-deps.sh      (root needed; does nothing when all are present)
# python3-vtk9: the ParaView (.vtu) round-trip test; xvfb: Gmsh screenshots without a display.
set -euo pipefail
PKGS=(build-essential cmake pkg-config
      libeigen3-dev libcgal-dev libgmsh-dev gmsh libcli11-dev nlohmann-json3-dev
      doctest-dev liblbfgspp-dev liblemon-dev libsuitesparse-dev freefem++ python3 python3-matplotlib python3-numpy
      librsvg2-bin python3-vtk9 xvfb
      clang libclang-rt-14-dev)  # libFuzzer targets (tests/fuzz, docs/fuzzing.md)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PKGS[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO=sudo
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
echo "install-deps: done"
