#!/usr/bin/env bash
# Installs the readers the interop tests drive, from Debian, if missing (as root): ParaView
# (pvpython: python3-paraview, only recommended by paraview), xvfb (an X display for its
# offscreen rendering, with Mesa's software OpenGL) and MDAnalysis.
set -euo pipefail
bash "$(dirname "$0")/../../scripts/debian_packages.sh" paraview python3-paraview xvfb xauth libgl1-mesa-dri \
  python3-mdanalysis
