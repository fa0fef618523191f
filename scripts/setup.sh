#!/usr/bin/env bash
# Installs every Debian package BHM Studio needs. Idempotent: silent when all is present.
# Works as root or through sudo. Usage: scripts/setup.sh
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libglfw3-dev libglm-dev libimgui-dev libstb-dev
  libosmesa6-dev libgl1-mesa-dri libgl-dev mesa-common-dev
  nlohmann-json3-dev doctest-dev python3-glad
  xvfb xauth
  fonts-dejavu-core
  calculix-ccx
  libopenmpi-dev openmpi-bin
  ffmpeg
  libnlopt-cxx-dev libpng-dev
  libeigen3-dev
  pybind11-dev python3-pybind11 python3-numpy python3-dev
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

if [ "$(id -u)" -eq 0 ]; then
  sudo_cmd=()
elif command -v sudo >/dev/null 2>&1; then
  sudo_cmd=(sudo)
else
  echo "setup.sh: need root or sudo to install: ${missing[*]}" >&2
  exit 1
fi

echo "setup.sh: installing ${missing[*]}" >&2
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends \
  "${missing[@]}" >/dev/null
