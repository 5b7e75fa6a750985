#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs what is missing (Debian packages), builds Release, and simulates a real scene.
#   tools/setup.sh [SCENE.json] [elan run options...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"

packages=(build-essential cmake libeigen3-dev libtbb-dev nlohmann-json3-dev libgtest-dev
          libgmock-dev libbenchmark-dev libbullet-dev libtinyobjloader-dev clang-format python3
          gnuplot-nox
          # the Python module (import elan) and its tests
          pybind11-dev python3-dev python3-numpy python3-pytest
          python3-distributed python3-pandas python3-tqdm python3-yaml python3-matplotlib  # elan batch, examples
          # the viewer (elan view), its off-screen pictures and tools/make_pictures.sh
          libglfw3-dev libimgui-dev libstb-dev libgl-dev libgl1-mesa-dri xvfb xauth imagemagick)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}" >&2
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq "${missing[@]}" >&2
fi

jobs=$(nproc)
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release -DELAN_NATIVE=ON >&2
cmake --build build/release -j"$jobs" >&2

scene=${1:-scenes/pile1k.json}
[ $# -gt 0 ] && shift
echo "running: build/release/tools/elan run $scene $*" >&2
build/release/tools/elan run "$scene" "$@"
