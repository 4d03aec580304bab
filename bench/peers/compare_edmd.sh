#!/usr/bin/env bash
# Runs Smallenburg's EDMD "Single" (github.com/FSmallenburg/EDMD: neighbour lists of shell
# 1.5 sigma, one event per particle) and granjet's BM_EdGas3d (bench/ed_gas_bench.cpp) on the
# same elastic hard-sphere gas: N = 10,976 spheres from an fcc lattice, k T = m = sigma = 1,
# phi = 0.30 and 0.45, thermostat off. Both are pinned to one core and run interleaved A/B for
# several rounds; prints collisions per CPU-second of each, the ratio granjet / EDMD, and the
# medians over the rounds.
#
# EDMD is configured on a temporary copy of the checkout (its parameters are globals at the top
# of mdSingle.c; nothing of it enters granjet), built by its own Makefile (-Ofast -funroll-loops
# -march=native), and its screen line (printed every unit of time) gets the process CPU time.
# Both count collisions only: EDMD's colcounter is raised in collision() after the stale-partner
# test, never for neighbour-list updates; granjet's counter never counts cell crossings or stale
# predictions. Both skip the melting of the lattice: EDMD is measured from t = 2 to t_end, and
# BM_EdGas3d advances to t = 2 outside its timed loop.
#
# Usage: bench/peers/compare_edmd.sh EDMD_DIR   (from the repository root, after building
# build/bench/granjet_bench). Environment: ROUNDS (default 3), CORE (default 0).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
edmd=$(cd "${1:?usage: compare_edmd.sh EDMD_DIR}" && pwd)
rounds=${ROUNDS:-3}
core=${CORE:-0}
bench=$root/build/bench/granjet_bench
[ -x "$bench" ] || { echo "build $bench first" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Simulated time of each EDMD run: about 3 CPU-seconds after t = 2 at either density.
declare -A t_end=([0.30]=32 [0.45]=20)
declare -A percent=([0.30]=30 [0.45]=45)

configure() {  # phi: a configured, built copy of Single in $work/edmd-$phi
  local dir=$work/edmd-$1
  cp -r "$edmd/Single" "$dir"
  local c=$dir/mdSingle.c
  sed -i -e 's/^double maxtime = [0-9.]*;/double maxtime = '"${t_end[$1]}"';/' \
    -e 's/^int initialconfig = 0;/int initialconfig = 1;/' \
    -e 's/^double packfrac = [0-9.]*;/double packfrac = '"$1"';/' \
    -e 's/^int N = [0-9]*;/int N = 10976;/' \
    -e 's/^const int usethermostat = 1;/const int usethermostat = 0;/' \
    -e 's/printf("Simtime: %lf, /printf("CPU: %.6f, Simtime: %lf, /' \
    -e 's/^\( *\)simtime, colcounter, pressnow,/\1(double)clock() \/ CLOCKS_PER_SEC, simtime, colcounter, pressnow,/' \
    "$c"
  sed -i '1i #include <time.h>' "$c"
  # Every edit must have taken: a newer EDMD with other lines fails here, not silently.
  for line in 'double maxtime = '"${t_end[$1]}"';' 'int initialconfig = 1;' \
    'double packfrac = '"$1"';' 'int N = 10976;' 'const int usethermostat = 0;' \
    'printf("CPU: %.6f, Simtime' '(double)clock() / CLOCKS_PER_SEC, simtime'; do
    grep -qF "$line" "$c" || { echo "EDMD edit failed: $line" >&2; exit 1; }
  done
  make -s -C "$dir" >/dev/null 2>&1 || make -C "$dir"
}

edmd_rate() {  # phi: collisions per CPU-second from t = 2 to t_end
  local dir=$work/edmd-$1
  (cd "$dir" && taskset -c "$core" ./md >run.log)
  python3 - "$dir/run.log" <<'RATE'
import re, sys
rows = [tuple(float(v) for v in m.groups()) for m in
        re.finditer(r"CPU: ([0-9.]+), Simtime: ([0-9.]+), Collisions: ([0-9]+)", open(sys.argv[1]).read())]
start = next(r for r in rows if r[1] >= 2.0 - 1e-9)
end = rows[-1]
print("%.4g" % ((end[2] - start[2]) / (end[0] - start[0])))
RATE
}

granjet_rate() {  # phi: BM_EdGas3d's collisions/s (per CPU-second)
  taskset -c "$core" "$bench" --benchmark_filter="^BM_EdGas3d/${percent[$1]}\$" \
    --benchmark_min_time=3 --benchmark_format=json 2>/dev/null |
    python3 -c "import json, sys; print('%.4g' % json.load(sys.stdin)['benchmarks'][0]['collisions/s'])"
}

for phi in 0.30 0.45; do configure "$phi"; done
printf "%-6s %-5s %12s %12s %7s\n" round phi granjet EDMD ratio
declare -A ratios
for round in $(seq 1 "$rounds"); do
  for phi in 0.30 0.45; do
    # Alternate which code runs first, so that neither always follows the other.
    if ((round % 2)); then
      g=$(granjet_rate "$phi")
      e=$(edmd_rate "$phi")
    else
      e=$(edmd_rate "$phi")
      g=$(granjet_rate "$phi")
    fi
    r=$(python3 -c "print('%.3f' % ($g / $e))")
    ratios[$phi]+="$g $e $r;"
    printf "%-6s %-5s %12s %12s %7s\n" "$round" "$phi" "$g" "$e" "$r"
  done
done
for phi in 0.30 0.45; do
  python3 - "$phi" "${ratios[$phi]}" <<'MEDIAN'
import statistics, sys
rows = [[float(v) for v in r.split()] for r in sys.argv[2].split(";") if r.strip()]
g, e, r = (statistics.median(c) for c in zip(*rows))
print("median phi %s: granjet %.4g  EDMD %.4g  ratio %.3f" % (sys.argv[1], g, e, r))
MEDIAN
done
