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
  libboost-context-dev                                           # the CPU reference's fibers
  gnuplot-nox                                                    # benchmark plots
  libopenmpi-dev openmpi-bin                                     # render --mpi (mpirun)
  libtinyobjloader-dev                                           # OBJ meshes in e500837 (scripts/*_against_base.sh)
  libzstd-dev                                                    # compressed render states
  libembree-dev                                                  # the bench's ray ceiling (optional in CMake)
  python3-dev python3-venv                                       # the Python module (python/)
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

# The Python module's build and test tools, from PyPI, in a virtual
# environment of the machine's python3 (python/requirements.txt); CMake
# builds the module for that interpreter, so `python3` imports it too.
venv=build/python-venv
if [[ ! -x $venv/bin/python ]] || ! cmp -s python/requirements.txt "$venv/requirements.txt"; then
  python3 -m venv --clear "$venv"
  "$venv/bin/python" -m pip install -q --disable-pip-version-check -r python/requirements.txt
  cp python/requirements.txt "$venv/requirements.txt"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE="$PWD/$venv/bin/python" ${SPECTRACE_CMAKE_ARGS:-}
cmake --build build -j "$(nproc)"
