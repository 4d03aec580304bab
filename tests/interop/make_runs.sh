#!/usr/bin/env bash
# The runs the interop tests read, written to DIR:
#   jet3d.h5  20,000 grains to t = 60 with omega, force and contacts (grains leave the region
#             from t ~ 45 on, so removed rows are exercised); fields averaged over 30..60
#   jet2d.h5  the 2D jet to t = 30, fields over 10..30
#   gas3d.h5  a periodic gas of 2000 grains (a box)
# usage: make_runs.sh GRANJET SCENES_DIR DIR
set -euo pipefail
granjet=$1 scenes=$2 dir=$3
mkdir -p "$dir"
"$granjet" run "$scenes/jet3d.ini" --quiet --out "$dir/jet3d.h5" \
  --set run.t_end=60 --set output.interval=10 \
  --set analysis.window_start=30 --set analysis.window_end=60 \
  --set output.fields=position,velocity,radius,id,omega,force,contacts
"$granjet" run "$scenes/jet2d.ini" --quiet --out "$dir/jet2d.h5" \
  --set run.t_end=30 --set output.interval=10 \
  --set analysis.window_start=10 --set analysis.window_end=30 \
  --set output.fields=position,velocity,radius,id,contacts
"$granjet" run "$scenes/gas3d.ini" --quiet --out "$dir/gas3d.h5" \
  --set gas.grains=2000 --set run.t_end=7 --set output.interval=2
