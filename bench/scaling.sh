#!/usr/bin/env bash
# How one soft-DEM run scales with run.threads: the CLI's loop time for each thread count, its
# particle-steps per wall-second, the speed-up over one thread and the parallel efficiency
# (speed-up / threads), and the serial share of the loop from `granjet run --profile` (the part
# that ran on one thread; 1 / share bounds the speed-up at any count). Two scenes by default: jet3d with a fixed target to t = 40 (the 2e4-grain
# jet) and scenes/jet3d_large.ini (2e5 grains, to its t_end of 40). Rounds are interleaved over
# the thread counts and the fastest round of each is kept; every run is the same trajectory
# (thread counts give bit-identical results), so only the time differs.
#
# Usage: bench/scaling.sh   (from the repository root, after building build/app/granjet)
# Environment: THREADS (default "1 2 ... nproc"), ROUNDS (default 2), T_END (overrides both
# scenes' run.t_end, e.g. 10 for a quick look), GRANJET (the binary, default build/app/granjet),
# PROFILES (a folder: each run's summary, with its per-phase profile, is kept there as
# SCENE-tTHREADS-rROUND.json), SCENES (which of the two, default "jet3d jet3d_large").
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
granjet=${GRANJET:-$root/build/app/granjet}
[ -x "$granjet" ] || { echo "scaling.sh: build $granjet first (or set GRANJET)" >&2; exit 1; }
threads=${THREADS:-$(seq -s ' ' 1 "$(nproc)")}
rounds=${ROUNDS:-2}
work=$(mktemp -d)
[ -n "${PROFILES:-}" ] && mkdir -p "$PROFILES"
trap 'rm -rf "$work"' EXIT

# name, scene file, overrides
scenes=(
  "jet3d|$root/scenes/jet3d.ini|--set wall.kind=fixed --set run.t_end=40 --set output.interval=0"
  "jet3d_large|$root/scenes/jet3d_large.ini|"
)

one_run() {  # scene file, overrides, threads, label: prints "wall_seconds psteps_per_second serial_share"
  local extra=()
  [ -n "${T_END:-}" ] && extra=(--set "run.t_end=$T_END")
  # shellcheck disable=SC2086  # the overrides are words
  "$granjet" run "$1" $2 "${extra[@]}" --set "run.threads=$3" --quiet --no-log --profile \
    --out "$work/run.h5" --summary "$work/run.json" >/dev/null 2>"$work/stderr" ||
    { cat "$work/stderr" >&2; exit 1; }
  [ -n "${PROFILES:-}" ] && cp "$work/run.json" "$PROFILES/$4.json"
  python3 -c 'import json, sys; s = json.load(open(sys.argv[1]))
print(s["wall_seconds"], s["particle_steps_per_second"], s["profile"]["serial_share"])' \
    "$work/run.json"
}

echo "CPU: $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) logical cores"
echo "rounds: $rounds (fastest kept), threads: $threads${T_END:+, t_end: $T_END}"
printf '%-12s %7s %10s %14s %9s %10s %8s\n' scene threads wall_s psteps/s speed-up efficiency serial
for entry in "${scenes[@]}"; do
  IFS='|' read -r name file overrides <<<"$entry"
  [[ " ${SCENES:-jet3d jet3d_large} " == *" $name "* ]] || continue
  declare -A best=()
  for ((r = 0; r < rounds; ++r)); do
    for n in $threads; do
      read -r wall rate serial < <(one_run "$file" "$overrides" "$n" "$name-t$n-r$r")
      if [ -z "${best[$n]:-}" ] || python3 -c "import sys; sys.exit(not $wall < ${best[$n]%% *})"
      then best[$n]="$wall $rate $serial"; fi
    done
  done
  first=${threads%% *}
  base=${best[$first]%% *}
  for n in $threads; do
    read -r wall rate serial <<<"${best[$n]}"
    python3 -c "import sys
name, n, wall, rate, base, first, serial = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), \
    float(sys.argv[4]), float(sys.argv[5]), int(sys.argv[6]), float(sys.argv[7])
speedup = base / wall * first
print(f'{name:<12} {n:>7} {wall:>10.2f} {rate:>14.4g} {speedup:>9.3f} {speedup / n:>10.3f} {100 * serial:>7.2f}%')" \
      "$name" "$n" "$wall" "$rate" "$base" "$first" "$serial"
  done
  unset best
done
