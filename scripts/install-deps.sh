#!/usr/bin/env bash
# Installs exactly the Debian 12 packages hpsf needs that are not installed yet; safe to run again.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libembree-dev libtbb-dev libglm-dev libopenimageio-dev openimageio-tools
  nlohmann-json3-dev libtinyobjloader-dev libcli11-dev libnanoflann-dev
  libgtest-dev libgmock-dev librapidcheck-dev libbenchmark-dev libboost-math-dev libcgal-dev
  libvulkan-dev glslang-tools glslang-dev spirv-tools libspirv-cross-c-shared-dev mesa-vulkan-drivers vulkan-tools
  libopencv-contrib-dev fonts-dejavu-core libctemplate-dev chromium libxml2-utils libvalijson-dev libyaml-cpp-dev
  slurm-wlm munge
  clang-15 libfuzzer-15-dev llvm-15 clang-format-15
)

missing=()
for package in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$package" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$package")
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
[[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
