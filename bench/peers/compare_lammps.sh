#!/usr/bin/env bash
# Runs LAMMPS (Debian package lammps, binary lmp) and granjet on the same jet scenes, one core
# each, one after the other, and prints particle-steps/s and the ratio granjet / LAMMPS.
# The peer inputs live in bench/peers/lammps (see its README); scenes: fixed target, t = 0..40
# (20,000 steps of dt = 0.002), LAMMPS gran/hooke/history ("gh", its fastest route).
# Usage: bench/peers/compare_lammps.sh [PEERS_DIR]   (run from the repository root, after
# scripts/setup.sh). Installs lammps if it is missing. Environment: GRANJET, the granjet binary
# to measure (default build/app/granjet; e.g. one built for another -march).
# With RANKS=K (K > 1; not under taskset, each rank needs its own core) it runs jet3d alone, on
# one process and on K MPI ranks (mpirun --bind-to core) with each code, ROUNDS times (default
# 3) in turn, and prints each round's particle-steps/s, the speed-ups of K ranks over one
# process, and granjet over LAMMPS on K ranks. LAMMPS runs over the ranks twice: on its fixed
# processor grid, and with its balancer moving the cut along the jet axis every 1,000 steps
# (`-var balance 1000`, see jet3d.lmp).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
peers=$(cd "${1:-$root/bench/peers/lammps}" && pwd)
granjet=${GRANJET:-$root/build/app/granjet}
[ -x "$granjet" ] || { echo "no granjet binary at $granjet: run scripts/setup.sh first" >&2; exit 1; }
command -v lmp >/dev/null || { apt-get update -qq && apt-get install -y -qq lammps >/dev/null; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$peers"/*.lmp "$peers"/gen_data.py "$work"/
(cd "$work" && python3 gen_data.py >/dev/null)
# granjet spreads a lattice of spacing 1 d by a relative 1e-9 about its front centre
# (kLatticeClearance, core/initial_state.cpp), so that rounding does not turn touching
# neighbours into contacts; LAMMPS gets jet3d spread the same way: one initial state for both.
# (On the data as generated, LAMMPS is about 6% slower.)
(cd "$work" && python3 - <<'SPREAD'
lines, atoms = open("jet3d.data").read().split("\n"), False
for n, line in enumerate(lines):
    f = line.split()
    atoms = line.startswith("Atoms") or (atoms and not line.startswith("Velocities"))
    if atoms and len(f) == 7 and f[1] == "1":  # id type d rho x y z; type 1 is the jet
        x, y, z = (v * (1 + 1e-9) for v in (float(f[4]), float(f[5]), float(f[6]) - 2.0))
        lines[n] = " ".join(f[:4] + ["%.12f" % v for v in (x, y, z + 2.0)])
open("jet3d.data", "w").write("\n".join(lines))
SPREAD
)

on_ranks=()  # how the next run starts: empty for one process, else an mpirun command line

lammps_rate() {  # input, grains, extra -var args...
  local input=$1 grains=$2
  shift 2
  (cd "$work" && "${on_ranks[@]}" lmp -in "$input" -log run.log -screen none -var model gh "$@")
  awk -v n="$grains" '/^Loop time of/ {printf "%.4g\n", n * $9 / $4}' "$work/run.log"
}

granjet_rate() {  # scene, --set args...
  local scene=$1
  shift
  "${on_ranks[@]}" "$granjet" run "$root/scenes/$scene" --quiet --out "$work/g.h5" \
    --summary "$work/g.json" --set run.t_end=40 --set wall.kind=fixed --set output.interval=0 "$@" \
    2>"$work/g.err" || { cat "$work/g.err" >&2; exit 1; }  # quiet: t_end is before the window
  python3 -c "import json; print('%.4g' % json.load(open('$work/g.json'))['particle_steps_per_second'])"
}

ranks=${RANKS:-1}
if [ "$ranks" -gt 1 ]; then
  echo "CPU: $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) logical cores;" \
    "jet3d mu_p=0.2 on 1 process and on $ranks ranks, particle-steps/s"
  printf "%-5s %10s %10s %8s %10s %10s %8s %10s %8s %14s\n" round "granjet 1" "granjet K" \
    "speed-up" "LAMMPS 1" "LAMMPS K" "speed-up" "balanced" "speed-up" "granjet/LAMMPS"
  for ((round = 1; round <= ${ROUNDS:-3}; ++round)); do
    on_ranks=()
    g1=$(granjet_rate jet3d.ini)
    l1=$(lammps_rate jet3d.lmp 20000 -var skin 0.4)
    on_ranks=(env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
      mpirun -n "$ranks" --bind-to core)
    gk=$(granjet_rate jet3d.ini)
    lk=$(lammps_rate jet3d.lmp 20000 -var skin 0.4)
    lb=$(lammps_rate jet3d.lmp 20000 -var skin 0.4 -var balance 1000)
    python3 -c "import sys; r, g1, gk, l1, lk, lb = sys.argv[1:]; g1, gk, l1, lk, lb = map(float, (g1, gk, l1, lk, lb))
print('%-5s %10.4g %10.4g %8.2f %10.4g %10.4g %8.2f %10.4g %8.2f %14.2f' % (r, g1, gk, gk / g1, l1, lk, lk / l1, lb, lb / l1, gk / max(lk, lb)))" \
      "$round" "$g1" "$gk" "$l1" "$lk" "$lb"
  done
  exit 0
fi

printf "%-22s %14s %14s %8s\n" "scene" "granjet" "LAMMPS gh" "ratio"
row() {  # label, granjet rate, lammps rate
  printf "%-22s %14s %14s %8.2f\n" "$1" "$2" "$3" "$(python3 -c "print($2 / $3)")"
}
row "jet3d mu_p=0.2" "$(granjet_rate jet3d.ini)" "$(lammps_rate jet3d.lmp 20000 -var skin 0.4)"
row "jet2d mu_p=0.2" "$(granjet_rate jet2d.ini --set contact.friction=0.2)" \
  "$(lammps_rate jet2d.lmp 8000 -var fric 1 -var skin 0.1)"
row "jet2d mu_p=0" "$(granjet_rate jet2d.ini --set contact.friction=0)" \
  "$(lammps_rate jet2d.lmp 8000 -var fric 0 -var skin 0.3)"
