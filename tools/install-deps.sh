#!/usr/bin/env bash
# Installs what Photon needs on Debian 12 (bookworm): compilers and libraries from Debian, and
# Mesa 25 (lavapipe, the software Vulkan driver) from bookworm-backports, because Mesa 22's
# lavapipe miscompiles loops whose exit differs between SIMD lanes. nvcc is optional: the CUDA
# backend is built when /usr/local/cuda/bin/nvcc exists.
set -euo pipefail
if [ "$(id -u)" -ne 0 ]; then
  exec sudo "$0" "$@"
fi
export DEBIAN_FRONTEND=noninteractive
if ! grep -rqs "bookworm-backports" /etc/apt/sources.list /etc/apt/sources.list.d/; then
  echo "deb http://deb.debian.org/debian bookworm-backports main" > /etc/apt/sources.list.d/bookworm-backports.list
fi
apt-get update -q
apt-get install -y -q --no-install-recommends \
  build-essential cmake ninja-build pkg-config git ca-certificates \
  libglm-dev nlohmann-json3-dev libcli11-dev libstb-dev libtinyexr-dev libgtest-dev \
  libvulkan-dev vulkan-tools vulkan-validationlayers glslang-tools spirv-cross \
  libglfw3-dev libimgui-dev xvfb xauth x11-apps imagemagick \
  libtinyobjloader-dev libtinygltf-dev libmeshoptimizer-dev libdraco-dev gltfpack assimp-testmodels libbenchmark-dev \
  clang libclang-rt-14-dev zlib1g-dev libisal-dev libopenexr-dev libopenvdb-dev libboost-iostreams-dev python3-matplotlib \
  python3-dev pybind11-dev python3-numpy python3-pytest libopenmpi-dev openmpi-bin
apt-get install -y -q --no-install-recommends -t bookworm-backports mesa-vulkan-drivers
