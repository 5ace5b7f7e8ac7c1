#!/usr/bin/env bash
# Installs the Debian 12 packages bundlelab needs, and only those that are missing, so that a second
# run costs a dpkg query and nothing else. Run as root (or with sudo available).
set -euo pipefail

packages=(
    cmake ninja-build g++ pkg-config git
    # Vulkan: loader, headers, lavapipe (the default device), validation layers, shader compiler
    libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools glslang-tools spirv-tools
    # Maths, geometry, images, configuration, command line, Mitsuba XML and glTF scenes
    libglm-dev libeigen3-dev libopenmesh-dev libopenexr-dev libstb-dev libtomlplusplus-dev
    libcli11-dev libtinyobjloader-dev libpugixml-dev libtinygltf-dev
    # CPU reference path tracer
    libembree-dev libtbb-dev
    # The Python module (pybind11) and its tests
    pybind11-dev python3-dev python3-pytest
    # `bundlelab view`: the window (GLFW) and the headless X server its tests run under
    libglfw3-dev xvfb xauth
    # `bundlelab run --slurm`: a single-node Slurm cluster the runner's test starts (scripts/local-slurm.sh)
    slurmctld slurmd slurm-client munge
    # glTF files written by real exporters for the importer's tests: the Khronos sample models and
    # assimp's own glTF 2.0 exporter
    assimp-testmodels assimp-utils
    # Tests, benchmarks, plots, and headless Chromium for the report's browser test
    libgtest-dev libgmock-dev libbenchmark-dev python3-matplotlib python3-numpy chromium
)

missing=()
for p in "${packages[@]}"; do
    status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
    [[ "$status" == "installed" ]] || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
    echo "install-deps: all ${#packages[@]} packages present"
    exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
