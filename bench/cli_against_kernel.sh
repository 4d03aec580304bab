#!/usr/bin/env bash
# The event-driven CLI's collision rate against the kernel's (BM_EdGas3dShipped,
# bench/ed_gas_bench.cpp) on the same work: the shipped gas3d scene at phi = 0.30 and 0.45, from
# t = 2 to its run.t_end. The kernel times that stretch alone; the CLI's is the difference of
# two runs of one seed, to t = 2 and to t_end (the run is deterministic: both reach t = 2
# identically), in collisions per CPU-second of the loop (the summary's cpu_seconds), as Google
# Benchmark's rate counters are. Both runs sample the virial from t = 1.9 (gas.equilibration;
# the shipped 5 would leave the short run nothing to measure), so the whole stretch pays for the
# sampler. Interleaved, pinned to one core; prints each round and the medians.
#
# Usage: bench/cli_against_kernel.sh   (from the repository root, after building
# build/app/granjet and build/bench/granjet_bench). Environment: ROUNDS (default 3), CORE
# (default 0).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
rounds=${ROUNDS:-3}
core=${CORE:-0}
t_end=$(sed -n 's/^t_end = //p' "$root/scenes/gas3d.ini")
granjet=$root/build/app/granjet
bench=$root/build/bench/granjet_bench
for binary in "$granjet" "$bench"; do
  [ -x "$binary" ] || { echo "build $binary first" >&2; exit 1; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cli_run() {  # phi, t_end: prints "collisions cpu_seconds"
  taskset -c "$core" "$granjet" run "$root/scenes/gas3d.ini" --backend event_driven --quiet \
    --no-log --set gas.phi="$1" --set gas.equilibration=1.9 --set run.t_end="$2" \
    --out "$work/g.h5" --summary "$work/g.json" 2>"$work/stderr" || { cat "$work/stderr" >&2; exit 1; }
  python3 -c "import json; j = json.load(open('$work/g.json')); print(j['collisions'], j['cpu_seconds'])"
}

kernel_rate() {  # phi
  taskset -c "$core" "$bench" --benchmark_filter="BM_EdGas3dShipped/${1#0.}/" \
    --benchmark_format=json |
    python3 -c "import json, sys; print(json.load(sys.stdin)['benchmarks'][0]['collisions/s'])"
}

printf "%-6s %6s %14s %14s %13s\n" "phi" "round" "CLI" "kernel" "CLI / kernel"
for phi in 0.30 0.45; do
  cli=() kernel=()
  for ((r = 1; r <= rounds; ++r)); do
    short=$(cli_run "$phi" 2)
    long=$(cli_run "$phi" "$t_end")
    read -r c2 s2 <<<"$short"
    read -r c1 s1 <<<"$long"
    cli+=("$(python3 -c "print(($c1 - $c2) / ($s1 - $s2))")")
    kernel+=("$(kernel_rate "$phi")")
    printf "%-6s %6d %14.4g %14.4g %13.3f\n" "$phi" "$r" "${cli[-1]}" "${kernel[-1]}" \
      "$(python3 -c "print(${cli[-1]} / ${kernel[-1]})")"
  done
  python3 - "${cli[@]}" -- "${kernel[@]}" <<'MEDIAN'
import statistics, sys
args = sys.argv[1:]
cut = args.index("--")
cli, kernel = statistics.median(map(float, args[:cut])), statistics.median(map(float, args[cut + 1:]))
print(f"median: CLI {cli:.4g}, kernel {kernel:.4g}, CLI / kernel {cli / kernel:.3f}")
MEDIAN
done
