#!/usr/bin/env bash
# Installs the Debian 12 packages exdyn needs that are missing (run as root).
#   scripts/install_deps.sh           build and run dependencies
#   scripts/install_deps.sh --test    also ParaView, xvfb and the Python packages of the tests
#   scripts/install_deps.sh --mesher  also the gmsh program (scripts/make_meshes.sh)
#   scripts/install_deps.sh --fuzz    also clang 14, its libFuzzer runtime and llvm-symbolizer (scripts/fuzz.sh)
#   scripts/install_deps.sh --perf    also Linux perf (scripts/serial_fraction.py)
set -euo pipefail
packages=(cmake g++ make pkg-config libeigen3-dev libhdf5-dev libopenmpi-dev openmpi-bin libhdf5-openmpi-dev
          libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libgmsh-dev libmetis-dev
          libgtest-dev libbenchmark-dev hdf5-tools python3-numpy python3-h5py python3-matplotlib)
for option in "$@"; do
  case "$option" in
    --test) packages+=(paraview python3-paraview xvfb xauth) ;;
    --mesher) packages+=(gmsh) ;;
    --fuzz) packages+=(clang-14 libclang-rt-14-dev llvm-14) ;;
    --perf) packages+=(linux-perf) ;;
    *) echo "usage: scripts/install_deps.sh [--test] [--mesher] [--fuzz] [--perf]" >&2; exit 2 ;;
  esac
done
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages present"
  exit 0
fi
echo "install_deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install_deps: done"
