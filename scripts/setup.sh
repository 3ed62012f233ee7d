#!/usr/bin/env bash
# Installs the Debian packages phos needs (only the missing ones) and builds it in Release mode.
# GLFW + OpenGL build the --preview window; Xvfb and Mesa's software OpenGL let the tests open it
# without a screen.
# Usage: scripts/setup.sh [build-dir [cmake targets...]]   (default: build, all targets)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
shift || true
targets=()
for t in "$@"; do targets+=(--target "$t"); done

packages=(build-essential cmake pkg-config libembree-dev libtbb-dev libopenexr-dev libpng-dev libstb-dev
          libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev libnanoflann-dev libtinyobjloader-dev
          libopenvdb-dev libnanovdb-dev libboost-iostreams-dev libblosc-dev zlib1g-dev
          libglfw3-dev libgl-dev libgl1-mesa-dri libglx-mesa0 xvfb xauth xdotool
          libopenmpi-dev openmpi-bin)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "phos: installing ${missing[*]}" >&2
  if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# PHOS_WERROR=1 (CI): warnings are errors. PHOS_CMAKE_ARGS: more cmake arguments, split on spaces
# (scripts/test.sh --sanitize passes -DPHOS_SANITIZE=... there).
read -ra extra <<<"${PHOS_CMAKE_ARGS:-}"
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -DPHOS_WERROR="${PHOS_WERROR:-0}" "${extra[@]}" >/dev/null
cmake --build "$build" -j"$(nproc)" "${targets[@]}"
