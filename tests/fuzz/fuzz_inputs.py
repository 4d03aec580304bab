#!/usr/bin/env python3
"""Fuzzes granjet with what users get wrong: random mutations of the shipped scenes (run) and
campaign files (campaign --dry-run), and damaged HDF5 run files (info, analyze).

The contract for every case:
  - the exit code is 0, 2 or 3 (done, bad input, blow-up): never a signal, never 1;
  - a file under a final name (RUN.h5) is complete (granjet info says "status: complete");
  - a refused command (exit 2) wrote nothing;
  - no input and no foreign file in the directory is changed (analyze may add its analysis to
    the run file it was given, only when it succeeds).
Runs still going after the per-case time limit are valid long runs (a mutation may ask for
1e6 time units); they are killed and counted, not failed.

  fuzz_inputs.py --granjet build/app/granjet [--seed S] [--cases N]
Environment: GRANJET_FUZZ_SEED, GRANJET_FUZZ_CASES (the longer mode: e.g. 2000).
"""
import argparse
import concurrent.futures
import hashlib
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
TIME_LIMIT = 20.0  # seconds a case may run before it counts as a valid long run

VALUES = ["", "0", "-1", "1", "2", "3", "0.5", "2.5", "1e-308", "1e308", "-1e308", "1e-17",
          "nan", "inf", "-inf", "4294967296", "4294967297", "9223372036854775807",
          "18446744073709551616", "abc", "true", "false", "1e6", "1,2", " 7 ", "0x10", "\u2603",
          "jet", "gas", "hcs", "binary", "plate", "fixed", "mono", "bi", "rectangle", "verlet"]
GARBAGE_LINES = ["[", "[section", "=3", "key", "[run]]", "\x00\x01\x02", "run.t_end == 3",
                 "# comment", ";", "[scene]\nkind = nothing"]

# Shrunk versions of the shipped scenes, so that an accepted mutation runs in a second or so.
SHRINK = {
    "jet": {"jet.grains": "300", "run.t_end": "3", "output.interval": "1",
            "analysis.window_start": "1", "analysis.window_end": "3",
            "analysis.sample_interval": "0.5", "run.progress_interval": "1"},
    "binary": {},
    "gas": {"gas.grains": "256", "run.t_end": "2", "gas.equilibration": "0.5"},
    "hcs": {"gas.grains": "256", "run.t_end": "2", "gas.equilibration": "0.5"},
}


def digest(path):
    return hashlib.sha256(Path(path).read_bytes()).hexdigest() if Path(path).is_file() else None


def parse_ini(text):
    """[(section, key, value) or (section, None, raw line)] keeping order."""
    rows, section = [], ""
    for line in text.splitlines():
        stripped = line.strip()
        m = re.fullmatch(r"\[(.*)\]", stripped)
        if m:
            section = m.group(1).strip()
            rows.append((section, None, line))
        elif "=" in stripped and not stripped.startswith("#"):
            key, value = stripped.split("=", 1)
            rows.append((section, key.strip(), value.strip()))
        else:
            rows.append((section, None, line))
    return rows


def render_ini(rows):
    out, section = [], None
    for sec, key, value in rows:
        if key is None:
            out.append(value)
            section = sec
            continue
        if sec != section:
            out.append(f"[{sec}]")
            section = sec
        out.append(f"{key} = {value}")
    return "\n".join(out) + "\n"


def set_key(rows, dotted, value):
    section, key = dotted.split(".", 1)
    for k, (sec, name, _) in enumerate(rows):
        if sec == section and name == key:
            rows[k] = (sec, key, value)
            return
    rows.append((section, key, value))


def scene_keys(granjet):
    help_text = subprocess.run([granjet, "--help"], capture_output=True, text=True).stdout
    return re.findall(r"^  ([a-z_]+\.[a-z_0-9]+) ", help_text, re.M)


def shrunk_scenes():
    bases = {}
    for ini in sorted((ROOT / "scenes").glob("*.ini")):
        rows = parse_ini(ini.read_text())
        kind = next((v for s, k, v in rows if s == "scene" and k == "kind"), "jet")
        for key, value in SHRINK.get(kind, {}).items():
            set_key(rows, key, value)
        bases[ini.stem] = rows
    return bases


def mutate_text(rng, text, keys):
    """One to three mutations of an INI text."""
    rows = parse_ini(text)
    for _ in range(rng.randint(1, 3)):
        op = rng.choice(["value", "value", "value", "insert", "delete", "duplicate", "garbage",
                         "truncate"])
        assigned = [k for k, row in enumerate(rows) if row[1] is not None]
        if op == "value" and assigned:
            k = rng.choice(assigned)
            rows[k] = (rows[k][0], rows[k][1], rng.choice(VALUES))
        elif op == "insert" and keys:
            set_key(rows, rng.choice(keys), rng.choice(VALUES))
        elif op == "delete" and rows:
            del rows[rng.randrange(len(rows))]
        elif op == "duplicate" and assigned:
            k = rng.choice(assigned)
            rows.insert(k + 1, rows[k])
        elif op == "garbage":
            rows.insert(rng.randrange(len(rows) + 1), ("", None, rng.choice(GARBAGE_LINES)))
    text = render_ini(rows)
    if rng.random() < 0.05:
        text = text[: rng.randrange(len(text) + 1)]
    return text


def run(cmd, cwd):
    """(exit code, stderr); exit code None when the case ran past TIME_LIMIT (a long run)."""
    proc = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            start_new_session=True)
    try:
        _, err = proc.communicate(timeout=TIME_LIMIT)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, 9)
        proc.communicate()
        return None, ""
    return proc.returncode, err.decode(errors="replace")


def complete(granjet, h5):
    out = subprocess.run([granjet, "info", str(h5)], capture_output=True, text=True)
    return out.returncode == 0 and "status: complete" in out.stdout


class Case:
    """One command in its own directory, with a foreign file that nothing may touch."""

    def __init__(self, root, name):
        self.dir = Path(root) / name
        self.dir.mkdir()
        (self.dir / "foreign.txt").write_text("not granjet's\n")

    def snapshot(self):
        return {p.name: digest(p) for p in self.dir.iterdir()}


def check(granjet, case, code, err, before, allowed_changes=()):
    """The contract; returns (outcome, problem or None)."""
    if code is None:
        return "long", None
    if code not in (0, 2, 3):
        return f"exit {code}", f"exit code {code}: {err.strip()[-300:]}"
    after = case.snapshot()
    for name, sha in before.items():
        if after.get(name) != sha and not (code == 0 and name in allowed_changes):
            return f"exit {code}", f"{name} was changed or removed"
    if code == 2:
        new = sorted(set(after) - set(before))
        if new:
            return "exit 2", f"refused, yet wrote {new}"
    for h5 in case.dir.glob("*.h5"):
        if h5.name not in before and not complete(granjet, h5):
            return f"exit {code}", f"{h5.name} is under its final name but not complete"
    return f"exit {code}", None


def scene_case(granjet, root, index, rng, bases, keys):
    name, rows = rng.choice(sorted(bases.items()))
    case = Case(root, f"scene{index}")
    scene = case.dir / "scene.ini"
    scene.write_text(mutate_text(rng, render_ini(rows), keys))
    cmd = [granjet, "run", str(scene), "--quiet", "--out", "out.h5", "--summary", "out.json"]
    if rng.random() < 0.4:
        cmd += ["--backend", "event_driven"]
    if rng.random() < 0.2:
        cmd += ["--set", f"{rng.choice(keys)}={rng.choice(VALUES)}"]
    before = case.snapshot()
    code, err = run(cmd, case.dir)
    return ("run", f"{name}: " + " ".join(cmd[2:])) + check(granjet, case, code, err, before)


def campaign_case(granjet, root, index, rng, keys):
    case = Case(root, f"campaign{index}")
    (case.dir / "campaigns").mkdir()
    (case.dir / "scenes").symlink_to(ROOT / "scenes")
    source = ROOT / "campaigns" / rng.choice(["smoke.ini", "thesis.ini"])
    campaign = case.dir / "campaigns" / "c.ini"
    campaign.write_text(mutate_text(rng, source.read_text(), keys))
    cmd = [granjet, "campaign", str(campaign), "--dry-run", "--out", str(case.dir / "out")]
    before = case.snapshot()
    code, err = run(cmd, case.dir)
    return ("campaign", f"{source.name}") + check(granjet, case, code, err, before)


def damage(rng, data):
    data = bytearray(data)
    how = rng.choice(["truncate", "flip", "zero", "flip"])
    if how == "truncate":
        return bytes(data[: rng.randrange(len(data))])
    if how == "zero":
        start = rng.randrange(len(data))
        data[start:start + 4096] = bytes(len(data[start:start + 4096]))
        return bytes(data)
    for _ in range(rng.randint(1, 64)):
        data[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
    return bytes(data)


def hdf5_case(granjet, root, index, rng, good):
    case = Case(root, f"hdf5_{index}")
    run_file = case.dir / "run.h5"
    run_file.write_bytes(damage(rng, good.read_bytes()))
    command = rng.choice([["info"], ["info", "--scene"], ["analyze"],
                          ["analyze", "--window", "1:3", "--summary", "a.json"]])
    cmd = [granjet, command[0], str(run_file)] + command[1:]
    before = case.snapshot()
    code, err = run(cmd, case.dir)
    allowed = ("run.h5",) if command[0] == "analyze" else ()
    return ("hdf5", " ".join(command)) + check(granjet, case, code, err, before, allowed)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--granjet", required=True)
    parser.add_argument("--seed", type=int,
                        default=int(os.environ.get("GRANJET_FUZZ_SEED", time.time_ns() % 2**31)))
    parser.add_argument("--cases", type=int, default=int(os.environ.get("GRANJET_FUZZ_CASES", 400)))
    args = parser.parse_args()
    granjet = str(Path(args.granjet).resolve())
    print(f"fuzz seed {args.seed} (GRANJET_FUZZ_SEED={args.seed} repeats it), {args.cases} cases",
          flush=True)
    rng = random.Random(args.seed)
    keys = scene_keys(granjet)
    bases = shrunk_scenes()
    root = Path(tempfile.mkdtemp(prefix="granjet_fuzz_"))
    try:
        good = root / "good.h5"
        jet2d = render_ini(bases["jet2d"])
        (root / "jet2d.ini").write_text(jet2d)
        subprocess.run([granjet, "run", str(root / "jet2d.ini"), "--quiet", "--out", str(good)],
                       check=True, capture_output=True)
        jobs = []
        with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
            for k in range(args.cases):
                case_rng = random.Random(rng.getrandbits(64))
                kind = rng.random()
                if kind < 0.55:
                    jobs.append(pool.submit(scene_case, granjet, root, k, case_rng, bases, keys))
                elif kind < 0.8:
                    jobs.append(pool.submit(hdf5_case, granjet, root, k, case_rng, good))
                else:
                    jobs.append(pool.submit(campaign_case, granjet, root, k, case_rng, keys))
            results = [job.result() for job in jobs]
    finally:
        shutil.rmtree(root, ignore_errors=True)
    outcomes = Counter((kind, outcome) for kind, _, outcome, _ in results)
    for (kind, outcome), count in sorted(outcomes.items()):
        print(f"  {kind:9s} {outcome:8s} {count}")
    problems = [(kind, what, problem) for kind, what, _, problem in results if problem]
    for kind, what, problem in problems:
        print(f"FAIL {kind} [{what}]: {problem}")
    print(f"{len(results) - len(problems)} of {len(results)} cases kept the contract (seed {args.seed})")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
