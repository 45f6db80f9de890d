#!/usr/bin/env bash
# Installs what spectrace needs on Debian 12 (as root), then configures and
# builds it into build/. Idempotent: re-running only rebuilds what changed.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  cmake g++ make pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-tools glslang-tools   # Vulkan loader, lavapipe, glslang
  libglm-dev libopenexr-dev libpng-dev                           # maths and image files
  nlohmann-json3-dev libcli11-dev libfmt-dev libssl-dev          # scene files, CLI, formatting, SHA-256
  librandom123-dev libgtest-dev libboost-dev                     # Philox, tests, chi-square p-values
  gnuplot-nox                                                    # benchmark plots
  libopenmpi-dev openmpi-bin                                     # render --mpi (mpirun)
  libtinyobjloader-dev                                           # OBJ meshes of scene objects
  libzstd-dev                                                    # compressed render states
  libembree-dev                                                  # the bench's ray ceiling (optional in CMake)
)
# SPECTRACE_VALIDATION=1 and validation_test need the Khronos layer.
packages+=(vulkan-validationlayers)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release ${SPECTRACE_CMAKE_ARGS:-}
cmake --build build -j "$(nproc)"
