#!/usr/bin/env bash
# Installs what is missing, builds phos (and its Python module: `import phos`, docs/python.md) and
# renders the bundled default scene with the photon mapper.
# Usage: scripts/run.sh [output image]   (default: out/default.png)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$here/out/default.png}"
"$here/scripts/setup.sh" "$here/build" phos phos_python
mkdir -p "$(dirname "$out")"
"$here/build/phos" render "$here/scenes/default.scn" --integrator photonmap -o "$out"
