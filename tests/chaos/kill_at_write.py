"""A run killed between any two of its writes resumes to the run never killed (label long).

The LD_PRELOAD shim tests/chaos/kill_at_write.c counts a run's write calls to its .partial and
its checkpoint being written, and raises SIGKILL instead of making call number N. A kill
between two of HDF5's writes lands in the middle of a flush, where the file's metadata is half
written; a signal sent from outside (chaos_campaign.py) rarely meets one. For --points values of
N spread over the whole run, the killed run is resumed and its file compared with the straight
run's (h5diff, every dataset and attribute). A run killed before its first checkpoint is
written must be refused by resume (exit 2), and nothing else. With --ranks K the run is spread
over K MPI ranks (rank 0 writes the files, and its kill ends the job), and the killed runs are
resumed in turn on one process and over K ranks; there the count of writes varies by a few
from run to run (the checkpoint shares follow the timed cut), and a run that ends before the
write it was to be killed at must have written the straight run's file.

    /usr/bin/python3 tests/chaos/kill_at_write.py --granjet build/app/granjet \\
        --shim build/tests/libgranjet_kill_at_write.so [--points 40] [--ranks K --mpiexec PATH]
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent
# jet3d to t = 20 with a checkpoint every time unit, frames every time unit, inline analysis
# and contact output: every kind of write a run makes, a few seconds a run.
SETTINGS = ["jet.grains=3000", "run.t_end=20", "run.checkpoint_interval=1", "output.interval=1",
            "analysis.window_start=5", "analysis.window_end=20",
            "output.fields=position,velocity,radius,id,omega,force,contacts"]


def run_command(granjet, out):
    command = [granjet, "run", str(ROOT / "scenes" / "jet3d.ini"), "--quiet", "--no-log",
               "--out", str(out)]
    for setting in SETTINGS:
        command += ["--set", setting]
    return command


def over_ranks(args, ranks, command):
    """`command` started as `ranks` MPI ranks (as root, on a machine of any size)."""
    if ranks == 1:
        return command
    return [args.mpiexec, "--allow-run-as-root", "--oversubscribe", "-n", str(ranks)] + command


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--granjet", required=True)
    parser.add_argument("--shim", required=True)
    parser.add_argument("--points", type=int, default=40)
    parser.add_argument("--ranks", type=int, default=1)
    parser.add_argument("--mpiexec", default="mpiexec")
    args = parser.parse_args()
    granjet = str(Path(args.granjet).resolve())
    shim = str(Path(args.shim).resolve())
    work = Path(tempfile.mkdtemp(prefix="granjet_kill_at_write_"))
    try:
        straight = work / "straight.h5"
        subprocess.run(run_command(granjet, straight), check=True)
        counted = work / "writes.txt"
        env = dict(os.environ, LD_PRELOAD=shim, KILL_AT="0", GRANJET_WRITE_COUNT=str(counted))
        subprocess.run(over_ranks(args, args.ranks, run_command(granjet, work / "counted.h5")),
                       check=True, env=env)
        writes = int(counted.read_text())
        print(f"a run makes {writes} writes to its files; killed at {args.points} of them",
              flush=True)
        outcomes = {"resumed": 0, "before its first checkpoint": 0, "ended before the kill": 0}
        failures = []
        for k in range(args.points):
            n = 1 + k * (writes - 1) // max(args.points - 1, 1)
            out = work / f"killed{n}.h5"
            env["KILL_AT"] = str(n)
            env["GRANJET_WRITE_COUNT"] = str(work / f"killed{n}.writes")
            killed = subprocess.run(over_ranks(args, args.ranks, run_command(granjet, out)),
                                    env=env, capture_output=args.ranks > 1)
            # Over ranks mpiexec reports its rank's kill as a failure of its own.
            if killed.returncode != -9 and (args.ranks == 1 or killed.returncode == 0):
                made = work / f"killed{n}.writes"
                # Over ranks each rank's checkpoint share holds the grains the timed cut gave
                # it, so the count of writes varies from run to run by a few: a run that made
                # fewer than n ended whole, and its file must be the straight run's.
                if (args.ranks > 1 and killed.returncode == 0 and made.exists()
                        and int(made.read_text()) < n):
                    if subprocess.run(["h5diff", "-q", str(straight), str(out)]).returncode:
                        failures.append(f"write {n}: the run that ended before it differs from "
                                        "the straight run's")
                    else:
                        outcomes["ended before the kill"] += 1
                else:
                    failures.append(f"write {n}: the run was not killed "
                                    f"(exit {killed.returncode})")
                for leftover in work.glob(f"killed{n}.*"):
                    leftover.unlink()
                continue
            partial = Path(f"{out}.partial")
            resume_ranks = args.ranks if k % 2 else 1
            resumed = subprocess.run(
                over_ranks(args, resume_ranks,
                           [granjet, "resume", str(partial), "--quiet", "--no-log"]),
                capture_output=True, text=True)
            # Refused (no checkpoint; killed at the first write, not even an HDF5 file yet).
            if resumed.returncode == 2 and not Path(f"{out}.checkpoint").exists():
                outcomes["before its first checkpoint"] += 1
            elif resumed.returncode != 0:
                failures.append(f"write {n}: resume exits {resumed.returncode}: "
                                f"{resumed.stderr.strip()}")
            elif subprocess.run(["h5diff", "-q", str(straight), str(out)]).returncode != 0:
                failures.append(f"write {n}: the resumed file differs from the straight run's")
            else:
                outcomes["resumed"] += 1
            for leftover in work.glob(f"killed{n}.*"):
                leftover.unlink()
        print(", ".join(f"{count} {what}" for what, count in outcomes.items()), flush=True)
        if failures:
            sys.exit("\n".join(failures))
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
