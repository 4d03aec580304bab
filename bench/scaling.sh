#!/usr/bin/env bash
# How one soft-DEM run scales with run.threads: the CLI's loop time for each thread count, its
# particle-steps per wall-second, the speed-up over one thread and the parallel efficiency
# (speed-up / threads), and the serial share of the loop from `granjet run --profile` (the part
# that ran on one thread; 1 / share bounds the speed-up at any count). Two scenes by default: jet3d with a fixed target to t = 40 (the 2e4-grain
# jet) and scenes/jet3d_large.ini (2e5 grains, to its t_end of 40). Rounds are interleaved over
# the thread counts and the fastest round of each is kept; every run is the same trajectory
# (thread counts give bit-identical results), so only the time differs.
#
# With LAYOUTS, each entry RANKSxTHREADS runs as `mpirun -n RANKS` with run.threads = THREADS
# (one soft-DEM run spread over ranks: the same trajectory again), each rank on THREADS cores.
#
# Usage: bench/scaling.sh   (from the repository root, after building build/app/granjet)
# Environment: THREADS (default "1 2 ... nproc"), LAYOUTS (e.g. "1x1 16x1 4x4 1x16"; default
# 1xN for each N of THREADS), MPIEXEC (default mpiexec), ROUNDS (default 2), T_END (overrides both
# scenes' run.t_end, e.g. 10 for a quick look), GRANJET (the command, default build/app/granjet),
# PROFILES (a folder: each run's summary, with its per-phase profile, is kept there as
# SCENE-tTHREADS-rROUND.json), SCENES (which of the two, default "jet3d jet3d_large").
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
read -ra granjet <<<"${GRANJET:-$root/build/app/granjet}"  # words: a loader may come first
[ -x "${granjet[0]}" ] || { echo "scaling.sh: build ${granjet[0]} first (or set GRANJET)" >&2; exit 1; }
threads=${THREADS:-$(seq -s ' ' 1 "$(nproc)")}
layouts=${LAYOUTS:-$(for n in $threads; do printf '1x%s ' "$n"; done)}
mpiexec=${MPIEXEC:-mpiexec}
rounds=${ROUNDS:-2}
work=$(mktemp -d)
[ -n "${PROFILES:-}" ] && mkdir -p "$PROFILES"
trap 'rm -rf "$work"' EXIT

# name, scene file, overrides
scenes=(
  "jet3d|$root/scenes/jet3d.ini|--set wall.kind=fixed --set run.t_end=40 --set output.interval=0"
  "jet3d_large|$root/scenes/jet3d_large.ini|"
)

one_run() {  # scene file, overrides, RANKSxTHREADS, label: prints "wall_seconds psteps_per_second serial_share"
  local extra=() launch=() ranks=${3%x*} n=${3#*x}
  [ -n "${T_END:-}" ] && extra=(--set "run.t_end=$T_END")
  [ "$ranks" -gt 1 ] && launch=(env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
    $mpiexec -n "$ranks" --map-by "slot:PE=$n" --bind-to core)
  # shellcheck disable=SC2086  # the overrides are words
  "${launch[@]}" "${granjet[@]}" run "$1" $2 "${extra[@]}" --set "run.threads=$n" --quiet --no-log --profile \
    --out "$work/run.h5" --summary "$work/run.json" >/dev/null 2>"$work/stderr" ||
    { cat "$work/stderr" >&2; exit 1; }
  [ -n "${PROFILES:-}" ] && cp "$work/run.json" "$PROFILES/$4.json"
  python3 -c 'import json, sys; s = json.load(open(sys.argv[1]))
print(s["wall_seconds"], s["particle_steps_per_second"], s["profile"]["serial_share"])' \
    "$work/run.json"
}

echo "CPU: $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) logical cores"
echo "rounds: $rounds (fastest kept), ranks x threads: $layouts${T_END:+, t_end: $T_END}"
printf '%-12s %7s %10s %14s %9s %10s %8s\n' scene layout wall_s psteps/s speed-up efficiency serial
for entry in "${scenes[@]}"; do
  IFS='|' read -r name file overrides <<<"$entry"
  [[ " ${SCENES:-jet3d jet3d_large} " == *" $name "* ]] || continue
  declare -A best=()
  for ((r = 0; r < rounds; ++r)); do
    for layout in $layouts; do
      read -r wall rate serial < <(one_run "$file" "$overrides" "$layout" "$name-$layout-r$r")
      if [ -z "${best[$layout]:-}" ] ||
        python3 -c "import sys; sys.exit(not $wall < ${best[$layout]%% *})"
      then best[$layout]="$wall $rate $serial"; fi
    done
  done
  first=${layouts%% *}
  base=${best[$first]%% *}
  for layout in $layouts; do
    read -r wall rate serial <<<"${best[$layout]}"
    python3 -c "import sys
name, layout, wall, rate, base, first, serial = sys.argv[1], sys.argv[2], float(sys.argv[3]), \
    float(sys.argv[4]), float(sys.argv[5]), sys.argv[6], float(sys.argv[7])
cores = lambda l: int(l.split('x')[0]) * int(l.split('x')[1])
speedup = base / wall * cores(first)
print(f'{name:<12} {layout:>7} {wall:>10.2f} {rate:>14.4g} {speedup:>9.3f} {speedup / cores(layout):>10.3f} {100 * serial:>7.2f}%')" \
      "$name" "$layout" "$wall" "$rate" "$base" "$first" "$serial"
  done
  unset best
done
