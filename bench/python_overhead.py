"""What driving granjet from Python costs: the shipped jet3d scene advanced by
granjet.Simulator.advance_to in steps of 0.1 against `granjet run` of the same scene, in
particle-steps per wall-second of the loop (the CLI's summary; for Python the advance_to calls
alone). The CLI's loop also samples the inline analysis and prints progress rows, so a ratio
above 1 is possible. Interleaved rounds, both pinned to one core; prints each round and the
median ratio Python / CLI.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py [--rounds 3] [--t-end 20]
        [--core 0]
"""
import argparse
import json
import os
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import granjet

ROOT = Path(__file__).resolve().parent.parent
SCENE = ROOT / "scenes" / "jet3d.ini"


def cli_rate(overrides, work):
    summary = Path(work) / "cli.json"
    subprocess.run([str(ROOT / "build" / "app" / "granjet"), "run", str(SCENE), "--quiet",
                    "--no-log", "--out", str(Path(work) / "cli.h5"), "--summary", str(summary)]
                   + sum((["--set", o] for o in overrides), []), check=True, capture_output=True)
    return json.loads(summary.read_text())["particle_steps_per_second"]


def python_rate(overrides, t_end):
    sim = granjet.Simulator(granjet.Scene.from_file(str(SCENE), overrides))
    start = time.perf_counter()
    for k in range(1, round(t_end / 0.1) + 1):
        sim.advance_to(0.1 * k)
    return sim.stats()["particle_steps"] / (time.perf_counter() - start)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--t-end", type=float, default=20.0)
    parser.add_argument("--core", type=int, default=0)
    args = parser.parse_args()
    os.sched_setaffinity(0, {args.core})  # the CLI child inherits it
    overrides = [f"run.t_end={args.t_end:g}", "run.threads=1", "output.interval=0"]
    ratios = []
    with tempfile.TemporaryDirectory() as work:
        for r in range(args.rounds):
            cli = cli_rate(overrides, work)
            py = python_rate(overrides, args.t_end)
            ratios.append(py / cli)
            print(f"round {r + 1}: CLI {cli:.4g}, Python {py:.4g} particle-steps/s, "
                  f"Python/CLI {py / cli:.3f}", flush=True)
    print(f"median Python/CLI {statistics.median(ratios):.3f} over {args.rounds} rounds "
          f"(jet3d, t_end {args.t_end:g}, one core)")


if __name__ == "__main__":
    main()
