#!/usr/bin/env bash
# Installs what snh needs on Debian 12 (as root, or through sudo when present),
# then configures and builds. Usage: scripts/setup.sh [build-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${1:-build}"

packages=(cmake g++ make pkg-config clang-format ccache
          ocl-icd-opencl-dev opencl-headers pocl-opencl-icd clinfo
          libviennacl-dev libeigen3-dev libgtest-dev
          nlohmann-json3-dev libcli11-dev python3-matplotlib
          gmsh python3-meshio libassimp-dev
          python3-dev pybind11-dev python3-numpy python3-pytest
          libboost-dev blender)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# pocl keeps compiled kernels here; any writable folder will do.
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/$build_dir/pocl-cache}"
mkdir -p "$POCL_CACHE_DIR"

cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release
cmake --build "$build_dir" -j"$(nproc)"
