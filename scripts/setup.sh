#!/usr/bin/env bash
# Installs the Debian packages phos needs (only the missing ones) and builds it in Release mode.
# GLFW + OpenGL build the --preview window; Xvfb and Mesa's software OpenGL let the tests open it
# without a screen. pybind11 and Debian's Python 3 (NumPy, matplotlib, pytest) build the Python
# module, which a .pth file in Debian's site directory makes importable (docs/python.md).
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
          libopenmpi-dev openmpi-bin
          python3 python3-dev pybind11-dev python3-pybind11 python3-numpy python3-matplotlib python3-pytest)
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

# `import phos` with Debian's python3: build/python named by a .pth file in its site directory
# (root only: elsewhere, PYTHONPATH=build/python; docs/python.md).
if [ -n "$(ls "$build"/python/phos*.so 2>/dev/null)" ] && [ -x /usr/bin/python3 ]; then
  site="$(/usr/bin/python3 -c 'import site; print(site.getsitepackages()[0])')"
  if [ -w "$(dirname "$site")" ] || [ "$(id -u)" -eq 0 ]; then
    mkdir -p "$site"
    echo "$(cd "$build/python" && pwd)" >"$site/phos.pth"
  else
    echo "phos: the Python module is in $build/python (set PYTHONPATH to it to import phos)" >&2
  fi
fi
