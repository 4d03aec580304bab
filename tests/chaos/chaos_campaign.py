"""Chaos test of `granjet campaign` (label long): a campaign hit by faults at random until it
completes, whose files must then be those of a campaign never hit (h5diff, every dataset and
attribute).

The campaign is campaigns/smoke.ini with its 3D jet made long enough to be hit mid-run (the
shipped 20,000-grain jet to t = 80, a checkpoint every time unit). Faults, drawn at random 0.5-3 s into each
invocation: kill -9 of a running run (the campaign queues it again once), kill -9 of the
campaign itself (its runs die with it), SIGINT to the campaign (it stops its runs at their
checkpoints), and, where a tmpfs may be mounted (root), a disk that fills: the campaign's DIR on
a tmpfs too small for it, enlarged again after the fault. Runs may be killed again and again
within an invocation; any other fault ends it, and the campaign is run again, until --faults
(12) are dealt and an invocation exits 0. Prints the faults dealt and the invocations it took.

    /usr/bin/python3 tests/chaos/chaos_campaign.py --granjet build/app/granjet [--seed S]
"""
import argparse
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent
SMOKE = ROOT / "campaigns" / "smoke.ini"


def long_smoke(work):
    text = SMOKE.read_text().replace("../scenes/", f"{ROOT}/scenes/")
    text = text.replace("jet.grains = 300\njet.diameter = 4\nwall.diameter = 8",
                        "jet.grains = 20000\njet.diameter = 30\nwall.diameter = 66\n"
                        "run.checkpoint_interval = 1")
    text = text.replace("region.radius = 16", "region.radius = 132")
    text = text.replace("run.t_end = 10", "run.t_end = 80")
    path = work / "chaos.ini"
    path.write_text(text)
    return path


def campaign(granjet, file, out):
    return [granjet, "campaign", str(file), "--quiet", "--jobs", "2", "--out", str(out)]


def mount(directory, size):
    """Mounts (or remounts) a tmpfs of `size` at `directory`; False where it may not."""
    options = ["-o", f"size={size}"] if not os.path.ismount(directory) else \
        ["-o", f"remount,size={size}"]
    return subprocess.run(["mount", "-t", "tmpfs", *options, "tmpfs", str(directory)],
                          capture_output=True).returncode == 0


def running_runs():
    """Process ids of granjet runs of the chaos campaign."""
    found = subprocess.run(["pgrep", "-f", r"(run|resume) .*chaos[.]out"], capture_output=True,
                           text=True).stdout.split()
    return [int(p) for p in found]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--granjet", required=True)
    parser.add_argument("--seed", type=int, default=int(time.time()) % 100000)
    parser.add_argument("--faults", type=int, default=12)
    parser.add_argument("--max-invocations", type=int, default=60)
    args = parser.parse_args()
    granjet = str(Path(args.granjet).resolve())
    rng = random.Random(args.seed)
    print(f"chaos seed {args.seed}", flush=True)
    work = Path(tempfile.mkdtemp(prefix="granjet_chaos_"))
    try:
        file = long_smoke(work)
        clean = work / "clean"
        subprocess.run(campaign(granjet, file, clean), check=True, capture_output=True)
        disk = work / "chaos.out"
        disk.mkdir()
        can_fill = mount(disk, "1g")
        faults = Counter()
        invocations = 0
        while True:
            invocations += 1
            if invocations > args.max_invocations:
                sys.exit(f"no complete campaign after {args.max_invocations} invocations")
            process = subprocess.Popen(campaign(granjet, file, disk / "c"),
                                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            filled = False
            # Faults until this invocation ends, or until enough were dealt (then it may finish).
            while sum(faults.values()) < args.faults:
                time.sleep(rng.uniform(0.5, 3.0))
                if process.poll() is not None:
                    break
                fault = rng.choice(["kill run", "kill run", "kill campaign", "interrupt"] +
                                   (["full disk"] if can_fill else []))
                if fault == "kill run":
                    runs = running_runs()
                    if not runs:
                        continue
                    os.kill(rng.choice(runs), signal.SIGKILL)
                elif fault == "kill campaign":
                    os.kill(process.pid, signal.SIGKILL)
                elif fault == "interrupt":
                    os.kill(process.pid, signal.SIGINT)
                else:
                    used = sum(f.stat().st_size for f in disk.rglob("*") if f.is_file())
                    mount(disk, f"{used // 1024 + 1024}k")  # about 1 MB left
                    filled = True
                faults[fault] += 1
                if os.environ.get("CHAOS_VERBOSE"):
                    print(f"  invocation {invocations}: {fault}", flush=True)
                if fault != "kill run":
                    break
            code = process.wait()
            if filled:
                mount(disk, "1g")
            if code == 0:
                break
        different = []
        for f in sorted(clean.rglob("*.h5")):
            twin = disk / "c" / f.relative_to(clean)
            if subprocess.run(["h5diff", "-q", str(f), str(twin)]).returncode != 0:
                different.append(str(f.relative_to(clean)))
        dealt = ", ".join(f"{n} {k}" for k, n in sorted(faults.items()) if k != "none")
        print(f"{invocations} invocations, faults dealt: {dealt or 'none'}; "
              f"{len(list(clean.rglob('*.h5')))} files compared", flush=True)
        if different:
            sys.exit("files differ from the clean campaign's: " + ", ".join(different))
        print("every file is the clean campaign's")
    finally:
        if os.path.ismount(work / "chaos.out"):
            subprocess.run(["umount", str(work / "chaos.out")])
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
