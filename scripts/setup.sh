#!/usr/bin/env bash
# Installs the Debian packages bounce needs to build, test and run.
# Idempotent: when everything is present it only checks and returns.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git clang-format
  libembree-dev libtbb-dev libglm-dev
  libtinyobjloader-dev libtinygltf-dev nlohmann-json3-dev libstb-dev
  libopenexr-dev libcli11-dev libfmt-dev libzip-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  python3-matplotlib
  # GNU parallel: the scale-out test runs a split reference through it (docs/scale-out.md).
  parallel
  libglfw3-dev libimgui-dev libepoxy-dev
  xvfb xauth libgl1-mesa-dri libglx-mesa0
  # Quake 3 levels for tests and benchmarks: the maps, their textures, and openarena-data for
  # the shader scripts (pak0.pk3) that make most of their lights.
  openarena-081-maps openarena-081-textures openarena-data
  # Real glTF and OBJ files, many deliberately broken, for the loaders' corpus test.
  assimp-testmodels
  # The sanitizer build (the asan preset) and its libFuzzer targets: clang and its runtimes.
  clang libclang-rt-14-dev
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
if [[ $(id -u) -ne 0 ]]; then
  echo "setup: need root to install packages (run as root or with sudo)" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
