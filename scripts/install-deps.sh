#!/usr/bin/env bash
# Installs the Debian 12 packages the project builds, tests and renders with.
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config
  libfmt-dev libcli11-dev catch2 libglm-dev libstb-dev libtinygltf-dev
  libepoxy-dev libglfw3-dev libimgui-dev libembree-dev
  libegl-dev libegl-mesa0 libgl1-mesa-dri libgles-dev libgbm1
  glslang-tools xvfb xauth
  clang-14 libfuzzer-14-dev
  python3-matplotlib  # scripts/plot_discrepancy.py
  assimp-testmodels  # glTF sample models the render test and docs/gallery.md use
)
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${packages[@]}"
