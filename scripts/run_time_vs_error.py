#!/usr/bin/python3
"""Run time against error, the framework's headline result.

    /usr/bin/python3 scripts/run_time_vs_error.py [--granjet build/app/granjet] [--docs docs]
                                                  [--work DIR] [--parts abc] [--quick]
                                                  [--reuse DIR/results.json]

Runs the granjet command on three problems, each setting once and one after the other, timing
every run with time.perf_counter around the subprocess (so start-up, set-up, inline analysis
and HDF5 output are included; the children's CPU time is recorded beside it), and measures
each run's error against a reference:

 (a) scenes/binary.ini (3D, head-on, e = 0.75, t_c = 0.1): the restitution and contact time
     measured from the trajectory (summary measured.restitution, measured.contact_time)
     against the requested ones, at dt/t_c from 0.005 to 0.4, integrators ab2 and verlet;
 (b) scenes/hcs3d.ini (4,000 spheres, phi = 0.05, e = 0.9): the Haff cooling rate
     measured.cooling_rate of soft grains at several t_c and dt against the event-driven
     (hard-sphere, the t_c -> 0 limit) rate of the same start;
 (c) scenes/jet2d.ini with a fixed target, t_end and analysis window shortened: the P and T_g
     profiles (/fields/{P,T_g}/mean, both layers, 20 bins) against soft DEM at the scene's
     t_c = 0.1 with dt = 0.005 t_c, for soft DEM at several dt and t_c and for the
     event-driven backend with each restitution law.

Writes DOCS/run_time_vs_error.md (tables, machine, commit, conclusions) and
DOCS/run_time_vs_error.png (one panel per part, error against run time, log-log, the Pareto
front marked), and WORK/results.json with every measurement; --reuse results.json redraws
both from such a file without running anything. --quick runs tiny versions of all three parts
(well under a minute) and checks the outputs: the end-to-end test of this script.
Needs Debian's python3-h5py, -matplotlib and -numpy (hence /usr/bin/python3).
"""
import argparse
import datetime
import json
import math
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = os.path.join(ROOT, "scenes")
STEM = "run_time_vs_error"


# ---- The plans: what each part runs --------------------------------------------------------
def setting(label, backend="soft_dem", **sets):
    """One run: a label, a backend and the scene keys it sets (dots as double underscores)."""
    return {"label": label, "backend": backend,
            "sets": {k.replace("__", "."): v for k, v in sets.items()}}


def soft(t_c, ratio, integrator="ab2", **sets):
    """Soft DEM at contact time t_c and dt = ratio * t_c."""
    label = f"soft t_c={t_c:g} dt={ratio:g}t_c" + ("" if integrator == "ab2" else f" {integrator}")
    s = setting(label, contact__contact_time=t_c, run__dt=_fmt(ratio * t_c),
                run__integrator=integrator, run__threads=1, **sets)  # one core, as ED
    s.update(t_c=t_c, dt_over_tc=ratio, integrator=integrator)
    return s


def ed(law, **sets):
    s = setting(f"ED {law}", "event_driven", ed__restitution_law=law, **sets)
    s.update(law=law)
    return s


def _fmt(x):
    return f"{x:.6g}"


def plan(quick):
    """The settings of each part. Full: about 10-15 minutes on one core of this machine."""
    if quick:
        binary_ratios, phases = [0.02, 0.2], 2
        hcs = dict(scene="hcs3d.ini", common={"gas.grains": 500, "run.t_end": 8,
                                               "gas.equilibration": 1, "gas.sample_interval": 0.5},
                   soft=[(0.1, 0.05), (0.03, 0.1)])
        jet = dict(common={"jet.grains": 600, "run.t_end": 30, "analysis.window_start": 15,
                           "analysis.window_end": 30},
                   reference=(0.1, 0.01), soft=[(0.1, 0.05, "ab2"), (0.05, 0.1, "ab2")],
                   laws=["velocity_dependent"])
    else:
        binary_ratios, phases = [0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.4], 8
        hcs = dict(scene="hcs3d.ini", common={},
                   soft=[(0.1, 0.02), (0.1, 0.05), (0.1, 0.1), (0.1, 0.2), (0.03, 0.02),
                         (0.03, 0.05), (0.03, 0.1), (0.03, 0.05, "verlet"), (0.03, 0.1, "verlet"),
                         (0.01, 0.02), (0.01, 0.05), (0.01, 0.1), (0.003, 0.05), (0.003, 0.1)])
        # The scene as the study runs it (t_end = 300, averaged over 180..300), target fixed.
        jet = dict(common={}, reference=(0.1, 0.005),
                   soft=[(0.1, 0.01, "ab2"), (0.1, 0.02, "ab2"), (0.1, 0.05, "ab2"),
                         (0.1, 0.1, "ab2"), (0.1, 0.2, "ab2"), (0.1, 0.4, "ab2"),
                         (0.1, 0.05, "verlet"),
                         (0.1, 0.1, "verlet"), (0.05, 0.02, "ab2"), (0.05, 0.05, "ab2"),
                         (0.02, 0.05, "ab2"), (0.02, 0.1, "ab2"), (0.01, 0.1, "ab2")],
                   laws=["constant", "velocity_dependent", "tc_model"])
    quiet_output = {"output.interval": 0}  # first and last frames only: no trajectory I/O
    parts = {}
    # The contact starts at a random point of a step in a real run, and the integrators' error
    # depends on where (ab2 at dt = 0.1 t_c: e from 0.735 to 0.782 for e0 = 0.75): each dt
    # is run at `phases` onset phases, the initial gap moved by k/phases of a step's travel.
    gap, speed = 0.0537, 1.0  # binary.ini
    parts["a"] = dict(
        title="(a) binary collision", scene="binary.ini",
        settings=[dict(soft(0.1, r, integ, output__interval=0,
                            binary__gap=_fmt(gap + k / phases * r * 0.1 * speed)), phase=k)
                  for integ in ("ab2", "verlet") for r in binary_ratios for k in range(phases)])
    common_b = dict(hcs["common"], **quiet_output)
    ref_b = dict(ed("constant", **_kw(common_b)), role="reference")
    noise_b = dict(ed("constant", run__seed=2, **_kw(common_b)), role="noise",
                   label="ED constant, seed 2")
    # What the integrator does to one collision at the gas's e (frictionless, head-on, over the
    # onset phases): the mean e it gives predicts the cooling rate's dt bias, (1 - e^2) per
    # collision, before any many-body effect of a finite t_c.
    e_gas = scene_value(hcs["scene"], "contact", "restitution")
    pairs = sorted({(t[2] if len(t) > 2 else "ab2", t[1]) for t in hcs["soft"]})
    parts["b"] = dict(
        title="(b) homogeneous cooling", scene=hcs["scene"], restitution=e_gas,
        settings=[ref_b, noise_b] + [soft(*t, **_kw(common_b)) for t in hcs["soft"]],
        binary=[dict(soft(0.1, r, integ, output__interval=0, contact__restitution=e_gas,
                          contact__friction=0,
                          binary__gap=_fmt(gap + k / phases * r * 0.1 * speed)), phase=k,
                     part="b", role="binary")
                for integ, r in pairs for k in range(phases)])
    # Same target for both backends: ED cannot tether it (model §4), so the soft runs fix it too.
    common_c = dict(jet["common"], **{"wall.kind": "fixed"}, **quiet_output)
    t_c, r = jet["reference"]
    ref_c = dict(soft(t_c, r, **_kw(common_c)), role="reference")
    noise_c = dict(soft(t_c, r, run__seed=2, **_kw(common_c)), role="noise")
    noise_c["label"] += ", seed 2"
    parts["c"] = dict(
        title="(c) jet2d profiles", scene="jet2d.ini",
        settings=[ref_c, noise_c]
        + [soft(t_c, r, integ, **_kw(common_c)) for t_c, r, integ in jet["soft"]]
        + [ed(law, **_kw(common_c)) for law in jet["laws"]])
    for key, part in parts.items():
        for s in part["settings"]:
            s.setdefault("role", "test")
            s["part"] = key
    return parts


def scene_value(scene, section, key):
    import configparser
    ini = configparser.ConfigParser(interpolation=None, inline_comment_prefixes=("#",))
    ini.read(os.path.join(SCENES, scene))
    return ini.getfloat(section, key)


def _kw(sets):
    return {k.replace(".", "__"): v for k, v in sets.items()}


# ---- Running granjet -------------------------------------------------------------------------
class Runner:
    def __init__(self, granjet, work):
        self.granjet = granjet
        self.work = work
        self.count = 0

    def run(self, scene, s):
        self.count += 1
        tag = f"{s['part']}{self.count:02d}"
        h5 = os.path.join(self.work, tag + ".h5")
        summary = os.path.join(self.work, tag + ".json")
        cmd = [self.granjet, "run", os.path.join(SCENES, scene), "--backend", s["backend"],
               "--out", h5, "--summary", summary, "--quiet"]
        for key, value in s["sets"].items():
            cmd += ["--set", f"{key}={value}"]
        before = os.times()
        start = time.perf_counter()
        proc = subprocess.run(cmd, capture_output=True, text=True)
        wall = time.perf_counter() - start
        after = os.times()
        cpu = (after.children_user - before.children_user) + \
              (after.children_system - before.children_system)
        result = dict(s, command=" ".join(cmd), wall=wall, cpu=cpu, exit=proc.returncode,
                      h5=h5)
        if proc.returncode not in (0, 3):  # 3: blow-up or collapse, a result; else a bug here
            sys.exit(f"{STEM}: '{' '.join(cmd)}' failed with exit code {proc.returncode}:\n"
                     f"{proc.stderr}")
        with open(summary) as f:
            result["summary"] = json.load(f)
        result["status"] = result["summary"].get("status", "?")
        if proc.returncode == 3:
            lines = [l for l in proc.stderr.splitlines() if l.strip()]
            result["status"] = lines[0] if lines else result["status"]
        if s.get("phase", 0) == 0 or proc.returncode != 0:
            print(f"  {s['label']:<40} {wall:8.2f} s  "
                  f"{'' if proc.returncode == 0 else 'FAILED: ' + result['status'][:80]}",
                  flush=True)
        return result


# ---- Errors ----------------------------------------------------------------------------------
def relative_l2(x, ref):
    """||x - ref|| / ||ref|| over the bins where both are finite."""
    x, ref = np.ravel(x), np.ravel(ref)
    keep = np.isfinite(x) & np.isfinite(ref)
    if not keep.any():
        return math.nan
    return float(np.linalg.norm(x[keep] - ref[keep]) / np.linalg.norm(ref[keep]))


def profiles(path):
    with h5py.File(path, "r") as f:
        return {k: f[f"fields/{k}/mean"][()].astype(float) for k in ("P", "T_g")}


def errors_a(r):
    m, q = r["summary"].get("measured"), r["summary"].get("requested")
    if r["exit"] != 0 or not m or "contact_time" not in m:
        return dict(err_e=math.nan, err_tc=math.nan, err=math.nan)
    err_e = abs(m["restitution"] / q["restitution"] - 1)
    err_tc = abs(m["contact_time"] / q["contact_time"] - 1)
    return dict(e=m["restitution"], tc=m["contact_time"], err_e=err_e, err_tc=err_tc,
                err=max(err_e, err_tc), cost=1.0 / r["dt_over_tc"])


def phase_rows(runs):
    """One row per integrator and dt: the mean and the worst over the contact onset phases."""
    rows = []
    for r in runs:
        if r["phase"] == 0:
            rows.append(dict(r, phases=[]))
        rows[-1]["phases"].append(r)
    for row in rows:
        ph = row.pop("phases")
        done = [p for p in ph if np.isfinite(p["err"])]
        row.update(label=row["label"], phase_count=len(ph), failed=len(ph) - len(done),
                   wall=float(np.mean([p["wall"] for p in ph])),
                   cpu=float(np.mean([p["cpu"] for p in ph])),
                   exit=max(p["exit"] for p in ph),
                   status="; ".join(sorted({p["status"] for p in ph if p["exit"] != 0})) or
                   "complete")
        if not done:
            row.update(err_e=math.nan, err_tc=math.nan, err=math.nan)
            continue
        e = [p["e"] for p in done]
        tc = [p["tc"] for p in done]
        row.update(e=float(np.mean(e)), e_min=min(e), e_max=max(e), tc=float(np.mean(tc)),
                   tc_min=min(tc), tc_max=max(tc),
                   err_e=max(p["err_e"] for p in done), err_tc=max(p["err_tc"] for p in done),
                   bias_e=float(np.mean(e)) / done[0]["summary"]["requested"]["restitution"] - 1,
                   err=max(p["err"] for p in done), exit=0 if not row["failed"] else 3)
        row.pop("summary", None)
        row.pop("command", None)
    return rows


def errors_b(r, ref):
    if r["exit"] != 0:
        return dict(rate=math.nan, err=math.nan, signed=math.nan)
    rate = r["summary"]["measured"]["cooling_rate"]
    return dict(rate=rate, signed=rate / ref - 1, err=abs(rate / ref - 1))


def errors_c(r, ref):
    if r["exit"] != 0:
        return dict(err_P=math.nan, err_T=math.nan, err=math.nan)
    p = profiles(r["h5"])
    e_p, e_t = relative_l2(p["P"], ref["P"]), relative_l2(p["T_g"], ref["T_g"])
    return dict(err_P=e_p, err_T=e_t, err=max(e_p, e_t), bias_P=bias(p["P"], ref["P"]),
                bias_T=bias(p["T_g"], ref["T_g"]))


def bias(x, ref):
    """sum x / sum ref - 1 over the bins where both are finite: the profile's overall shift."""
    keep = np.isfinite(x) & np.isfinite(ref)
    return float(x[keep].sum() / ref[keep].sum() - 1) if keep.any() else math.nan


def measure(parts, runner, only):
    results = {}
    for key, part in parts.items():
        if key not in only:
            continue
        print(f"{part['title']}: {len(part['settings'])} runs", flush=True)
        runs = [runner.run(part["scene"], s) for s in part["settings"]]
        if key == "a":
            for r in runs:
                r.update(errors_a(r))
            runs = phase_rows(runs)
        elif key == "b":
            ref = next(r for r in runs if r["role"] == "reference")
            if ref["exit"] != 0:
                sys.exit(f"{STEM}: the reference run of part (b) failed: {ref['status']}")
            rate = ref["summary"]["measured"]["cooling_rate"]
            for r in runs:
                r.update(errors_b(r, rate))
            part["reference_value"] = rate
            binary = [runner.run("binary.ini", s) for s in part["binary"]]
            for r in binary:
                r.update(errors_a(r))
            e0 = part["restitution"]
            rows = {(row["integrator"], row["dt_over_tc"]): row for row in phase_rows(binary)}
            for r in runs:
                row = rows.get((r.get("integrator"), r.get("dt_over_tc")))
                if r["backend"] == "soft_dem" and row:
                    r["predicted"] = (1 - row["e"] ** 2) / (1 - e0 ** 2) - 1 \
                        if np.isfinite(row["err"]) else math.nan
                    r["predicted_blowups"] = row["failed"]
                    r["predicted_phases"] = row["phase_count"]
        else:
            ref = next(r for r in runs if r["role"] == "reference")
            if ref["exit"] != 0:
                sys.exit(f"{STEM}: the reference run of part (c) failed: {ref['status']}")
            ref_profiles = profiles(ref["h5"])
            for r in runs:
                r.update(errors_c(r, ref_profiles))
        for r in runs:
            r.pop("h5", None)
            if "summary" in r:
                r["summary"] = {k: v for k, v in r["summary"].items() if k != "analysis"}
        results[key] = dict(title=part["title"], scene=part["scene"], runs=runs,
                            reference_value=part.get("reference_value"),
                            restitution=part.get("restitution"))
    return results


def pareto(points):
    """Indices of the points no other point beats in both cost and error (cost ascending)."""
    order = sorted((i for i, (c, e) in enumerate(points) if np.isfinite(e) and e > 0),
                   key=lambda i: (points[i][0], points[i][1]))
    front, best = [], math.inf
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


def tests_of(part):
    return [r for r in part["runs"] if r["role"] != "reference"]


def cost_of(key, r):
    return r["cost"] if key == "a" else r["wall"]


def mark_pareto(results):
    for key, part in results.items():
        runs = [r for r in tests_of(part) if r["role"] == "test" and not r.get("failed")]
        front = pareto([(cost_of(key, r), r["err"]) for r in runs])
        for r in part["runs"]:
            r["pareto"] = False
        for i in front:
            runs[i]["pareto"] = True


# ---- Machine and commit ----------------------------------------------------------------------
def machine():
    info = {"uname": " ".join(platform.uname()[i] for i in (0, 2, 4))}
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
        fields = dict(line.split(":", 1) for line in out.splitlines() if ":" in line)
        info["cpu"] = fields.get("Model name", "?").strip()
        info["cpus"] = fields.get("CPU(s)", "?").strip()
        info["hypervisor"] = fields.get("Hypervisor vendor", "").strip()
    except OSError:
        info["cpu"] = platform.processor() or "?"
    try:
        info["load_before"] = os.getloadavg()
    except OSError:
        pass
    git = ["git", "-C", ROOT]
    info["commit"] = subprocess.run(git + ["rev-parse", "--short", "HEAD"], capture_output=True,
                                    text=True).stdout.strip() or "?"
    return info


def granjet_version(granjet):
    out = subprocess.run([granjet, "--version"], capture_output=True, text=True)
    return (out.stdout or out.stderr).strip().splitlines()[0] if out.returncode == 0 else "?"


# ---- Figure ----------------------------------------------------------------------------------
COLOURS = {0.1: "tab:blue", 0.05: "tab:cyan", 0.03: "tab:green", 0.02: "tab:olive",
           0.01: "tab:orange", 0.003: "tab:red"}
DT_MARKERS = {0.02: "o", 0.05: "s", 0.1: "^", 0.2: "v"}
LAW_COLOURS = {"constant": "tab:purple", "velocity_dependent": "tab:brown",
               "tc_model": "tab:pink"}


def short_label(key, r):
    if r["backend"] == "event_driven":
        return {"constant": "ED const", "velocity_dependent": "ED v-dep",
                "tc_model": "ED tc"}.get(r.get("law"), "ED") + (" s2" if r["role"] == "noise" else "")
    text = f"{r['dt_over_tc']:g}" if key == "a" else f"{r['t_c']:g}/{r['dt_over_tc']:g}"
    if r.get("integrator") == "verlet" and key != "a":
        text += " vv"
    return text + (" s2" if r["role"] == "noise" else "")


def draw_front(ax, key, part):
    front = sorted((r for r in part["runs"] if r.get("pareto")), key=lambda r: cost_of(key, r))
    if front:
        x = [cost_of(key, r) for r in front]
        y = [r["err"] for r in front]
        ax.step(x, y, where="post", color="k", lw=1.0, alpha=0.5, zorder=1,
                label="Pareto front")
        ax.scatter(x, y, s=160, facecolors="none", edgecolors="k", lw=1.2, zorder=4)


def annotate(ax, x, y, text):
    ax.annotate(text, (x, y), textcoords="offset points", xytext=(4, 3), fontsize=7)


def panel_a(ax, part):
    for integ, marker in (("ab2", "o"), ("verlet", "s")):
        runs = [r for r in part["runs"] if r["integrator"] == integ and np.isfinite(r["err"])]
        x = [r["cost"] for r in runs]
        ax.plot(x, [max(r["err_e"], 1e-7) for r in runs], marker=marker, color="tab:blue",
                ls="-", label=f"{integ}: worst |e/e0 - 1|")
        ax.plot(x, [max(r["err_tc"], 1e-7) for r in runs], marker=marker, color="tab:orange",
                ls="--", mfc="none", label=f"{integ}: worst |t_c/t_c0 - 1|")
        for r in runs:
            annotate(ax, r["cost"], r["err"], short_label("a", r))
    draw_front(ax, "a", part)
    ax.set_xlabel(r"steps per contact $t_c/dt$ (run time $\propto$ this; labels: $dt/t_c$)")
    ax.set_ylabel("relative error (front: the larger of the two)")


def panel_b(ax, part):
    ref = next(r for r in part["runs"] if r["role"] == "reference")
    noise = [r for r in part["runs"] if r["role"] == "noise"]
    for r in part["runs"]:
        if r["role"] == "reference" or not np.isfinite(r["err"]):
            continue
        if r["backend"] == "event_driven":
            ax.scatter(r["wall"], r["err"], marker="x", color="k", zorder=3)
        else:
            ax.scatter(r["wall"], r["err"], color=COLOURS.get(r["t_c"], "gray"),
                       marker=DT_MARKERS.get(r["dt_over_tc"], "D"), zorder=3)
        annotate(ax, r["wall"], r["err"], short_label("b", r))
    for r in noise:
        if np.isfinite(r["err"]):
            ax.axhline(r["err"], color="gray", ls=":", lw=1,
                       label="ED seed 2 vs seed 1 (statistical spread)")
    ax.axvline(ref["wall"], color="k", ls="--", lw=1, label=f"ED reference: {ref['wall']:.2f} s")
    for t_c, colour in COLOURS.items():
        if any(r.get("t_c") == t_c and r["backend"] == "soft_dem" for r in part["runs"]):
            ax.scatter([], [], color=colour, label=f"soft $t_c$ = {t_c:g}")
    for ratio, marker in DT_MARKERS.items():
        if any(r.get("dt_over_tc") == ratio for r in part["runs"]):
            ax.scatter([], [], color="gray", marker=marker, label=f"$dt$ = {ratio:g} $t_c$")
    draw_front(ax, "b", part)
    ax.set_xlabel("wall time of the run [s]  (labels: $t_c$ / $dt/t_c$, vv: verlet)")
    ax.set_ylabel("|cooling rate / ED rate - 1|")


def panel_c(ax, part):
    ref = next(r for r in part["runs"] if r["role"] == "reference")
    for r in part["runs"]:
        if r["role"] == "reference" or not np.isfinite(r["err"]):
            continue
        colour = LAW_COLOURS.get(r.get("law"), "k") if r["backend"] == "event_driven" else \
            COLOURS.get(r["t_c"], "gray")
        marker = "D" if r["backend"] == "event_driven" else \
            ("s" if r.get("integrator") == "verlet" else "o")
        ax.plot([r["wall"]] * 2, [r["err_P"], r["err_T"]], color=colour, lw=0.6, alpha=0.6)
        ax.scatter(r["wall"], r["err_P"], color=colour, marker=marker, zorder=3)
        ax.scatter(r["wall"], r["err_T"], facecolors="none", edgecolors=colour, marker=marker,
                   zorder=3)
        annotate(ax, r["wall"], r["err"], short_label("c", r))
    for r in part["runs"]:
        if r["role"] == "noise" and np.isfinite(r["err"]):
            ax.axhline(r["err_P"], color="gray", ls=":", lw=1, label="seed 2 vs reference: P")
            ax.axhline(r["err_T"], color="gray", ls="-.", lw=1, label="seed 2 vs reference: $T_g$")
    ax.axvline(ref["wall"], color="k", ls="--", lw=1,
               label=f"reference (t_c={ref['t_c']:g}, dt={ref['dt_over_tc']:g} t_c): "
                     f"{ref['wall']:.0f} s")
    ax.scatter([], [], color="gray", label="P (filled)")
    ax.scatter([], [], facecolors="none", edgecolors="gray", label="$T_g$ (open)")
    for t_c, colour in COLOURS.items():
        if any(r.get("t_c") == t_c and r["backend"] == "soft_dem" for r in part["runs"]):
            ax.scatter([], [], color=colour, label=f"soft $t_c$ = {t_c:g} (square: verlet)")
    for law, colour in LAW_COLOURS.items():
        if any(r.get("law") == law for r in part["runs"]):
            ax.scatter([], [], color=colour, marker="D", label=f"ED {law}")
    draw_front(ax, "c", part)
    ax.set_xlabel("wall time of the run [s]  (labels: $t_c$ / $dt/t_c$)")
    ax.set_ylabel(r"relative $L_2$ error of the profile (front: larger of P, $T_g$)")


def figure(results, meta, path):
    keys = [k for k in "abc" if k in results]
    fig, axes = plt.subplots(1, len(keys), figsize=(6.6 * len(keys), 6.0), squeeze=False)
    for ax, key in zip(axes[0], keys):
        part = results[key]
        {"a": panel_a, "b": panel_b, "c": panel_c}[key](ax, part)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.25)
        ax.set_title(f"{part['title']} ({part['scene']})")
        ax.legend(fontsize=7, loc="best")
    fig.suptitle(f"granjet run time against error: commit {meta['machine']['commit']}, "
                 f"{meta['machine']['cpu']}, one core per run; {meta['date']}", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ---- Document --------------------------------------------------------------------------------
def pct(x, digits=2):
    if x is None or not np.isfinite(x):
        return "-"
    value = 100 * x
    if value == 0:
        return "0"
    return f"{value:.{digits}g}%" if value < 1 else f"{value:.{max(digits, 2)}g}%" if value < 10 \
        else f"{value:.0f}%"


def secs(x):
    return f"{x:.3g}" if x < 100 else f"{x:.0f}"


def status_text(r):
    if r["exit"] == 0:
        return ""
    text = r["status"].replace("granjet: ", "").replace("|", "/")
    return " (" + (text if len(text) <= 100 else text[:100].rsplit(" ", 1)[0] + " ...") + ")"


def table_a(part):
    rows = ["| integrator | dt/t_c | steps per contact | wall per run [s] | e: mean (min-max) | "
            "t_c: mean (min-max) | worst error e | worst error t_c | Pareto |",
            "|---|---|---|---|---|---|---|---|---|"]
    for r in part["runs"]:
        ok = np.isfinite(r["err"])
        head = f"| {r['integrator']} | {r['dt_over_tc']:g} | {1 / r['dt_over_tc']:g} | " \
               f"{secs(r['wall'])} | "
        rows.append(head + (f"{r['e']:.4f} ({r['e_min']:.4f}-{r['e_max']:.4f}) | "
                            f"{r['tc']:.5f} ({r['tc_min']:.5f}-{r['tc_max']:.5f}) | "
                            f"{pct(r['err_e'])} | {pct(r['err_tc'])} | "
                            f"{'*' if r.get('pareto') else ''}"
                            + (f" {r['failed']} of {r['phase_count']} failed{status_text(r)}"
                               if r["failed"] else "") + " |"
                            if ok else f"- | - | - | - | {status_text(r)} |"))
    return "\n".join(rows)


def role_tag(run):
    """How a table names the reference run and the independent-start (noise) run."""
    return {"reference": " **reference**", "noise": " (statistical spread)"}.get(run["role"], "")


def table_b(part):
    rows = ["| setting | backend | t_c | dt/t_c | wall [s] | CPU [s] | cooling rate | "
            "rate / ED - 1 | binary's (1-e^2) bias | Pareto |",
            "|---|---|---|---|---|---|---|---|---|---|"]
    for r in part["runs"]:
        tag = role_tag(r)
        soft_run = r["backend"] == "soft_dem"
        rate = f"{r['rate']:.5f}" if np.isfinite(r.get("rate", math.nan)) else "-"
        signed = "0 (by definition)" if r["role"] == "reference" else \
            (f"{100 * r['signed']:+.2f}%" if np.isfinite(r["signed"]) else "-")
        rows.append(f"| {r['label']}{tag}{status_text(r)} | {r['backend']} | "
                    f"{r['t_c'] if soft_run else '-'} | {r['dt_over_tc'] if soft_run else '-'} | "
                    f"{secs(r['wall'])} | {secs(r['cpu'])} | {rate} | {signed} | "
                    + (f"{100 * r['predicted']:+.2f}%" if np.isfinite(r.get("predicted", math.nan))
                       else "blow-up" if r.get("predicted_blowups") else "-")
                    + (f" ({r['predicted_blowups']} of {r['predicted_phases']} phases blow up)"
                       if r.get("predicted_blowups") and np.isfinite(r.get("predicted", math.nan))
                       else "")
                    + f" | {'*' if r.get('pareto') else ''} |")
    return "\n".join(rows)


def table_c(part):
    rows = ["| setting | backend | t_c | dt/t_c | integrator / law | wall [s] | CPU [s] | "
            "error P (shift) | error T_g (shift) | Pareto |",
            "|---|---|---|---|---|---|---|---|---|---|"]
    for r in part["runs"]:
        tag = role_tag(r)
        soft_run = r["backend"] == "soft_dem"
        ref = r["role"] == "reference"
        rows.append(f"| {r['label']}{tag}{status_text(r)} | {r['backend']} | "
                    f"{r['t_c'] if soft_run else '-'} | {r['dt_over_tc'] if soft_run else '-'} | "
                    f"{r['integrator'] if soft_run else r['law']} | {secs(r['wall'])} | "
                    f"{secs(r['cpu'])} | {'0' if ref else shifted(r['err_P'], r.get('bias_P'))} | "
                    f"{'0' if ref else shifted(r['err_T'], r.get('bias_T'))} | "
                    f"{'*' if r.get('pareto') else ''} |")
    return "\n".join(rows)


def shifted(err, shift):
    if not np.isfinite(err):
        return "-"
    return f"{pct(err)} ({100 * shift:+.1f}%)" if shift is not None and np.isfinite(shift) else \
        pct(err)


def front_text(key, part):
    front = sorted((r for r in part["runs"] if r.get("pareto")), key=lambda r: cost_of(key, r))
    if key == "a":
        return ", ".join(f"{r['integrator']} dt = {r['dt_over_tc']:g} t_c ({pct(r['err'])})"
                         for r in front)
    return ", ".join(f"{r['label']} ({secs(r['wall'])} s, {pct(r['err'])})" for r in front)


def largest_ratio(runs, limit, field="err"):
    """The largest dt/t_c up to which every run (ascending dt) has its error below limit."""
    best = math.nan
    for r in sorted(runs, key=lambda r: r["dt_over_tc"]):
        if not (np.isfinite(r[field]) and r[field] < limit):
            break
        best = r["dt_over_tc"]
    return best


def span(values, fmt="{:+.1f}%"):
    """'a' or 'a to b' of percentages."""
    v = sorted(100 * x for x in values if np.isfinite(x))
    if not v:
        return "-"
    return fmt.format(v[0]) if len(v) == 1 or abs(v[-1] - v[0]) < 0.05 else \
        f"{fmt.format(v[0])} to {fmt.format(v[-1])}"


def lesson_b(part):
    ref = next(r for r in part["runs"] if r["role"] == "reference")
    noise = next((r for r in part["runs"] if r["role"] == "noise"), None)
    soft_runs = [r for r in part["runs"] if r["backend"] == "soft_dem" and np.isfinite(r["err"])]
    if not soft_runs:
        return f"**Homogeneous cooling:** no soft run finished."
    ab2 = [r for r in soft_runs if r["integrator"] == "ab2"]
    fine = sorted((r for r in ab2 if r["dt_over_tc"] <= 0.02 + 1e-12), key=lambda r: -r["t_c"])
    ratios = sorted({r["dt_over_tc"] for r in soft_runs if r["dt_over_tc"] >= 0.1 - 1e-12})
    within = [r for r in soft_runs if r["err"] < 0.01]
    cheap = min(within, key=lambda r: r["wall"]) if within else None
    text = (f"**Homogeneous cooling (dilute gas):** the event-driven backend gives the exact "
            f"hard-sphere rate fastest, in {secs(ref['wall'])} s"
            + (f" (an independent start moves it by {pct(noise['err'])})" if noise else "")
            + ". Soft grains miss it two ways. Softness: at dt = 0.02 t_c the rate is off by "
            + ", ".join(f"{100 * r['signed']:+.1f}% at t_c = {r['t_c']:g}" for r in fine))
    if noise and len(fine) > 1 and max(r["err"] for r in fine[1:]) < 0.5 * fine[0]["err"]:
        text += (f": a clear softness bias at t_c = {fine[0]['t_c']:g} only; below it the "
                 f"differences ({span([r['signed'] for r in fine[1:]])}) are of the order of "
                 f"the run-to-run scatter")
    text += (". Step: at coarse steps the integrator's restitution, averaged over where a "
              "contact starts within a step, is off, and the dissipation 1 - e^2 with it, "
              "whatever t_c (")
    text += "; ".join(
        f"dt = {k:g} t_c: " + ", ".join(
            f"{integ} {span([r['signed'] for r in soft_runs if r['dt_over_tc'] == k and r['integrator'] == integ])}"
            + (f" (binary collision predicts {100 * pred:+.0f}%)" if np.isfinite(pred) else
               " (where the binary collision stops as a blow-up, its kinetic energy rising "
               "above the start: the gas's total never does, so it runs on)" if blow else "")
            for integ in ("ab2", "verlet")
            if any(r["dt_over_tc"] == k and r["integrator"] == integ for r in soft_runs)
            for pred, blow in [next((r.get("predicted", math.nan), r.get("predicted_blowups", 0))
                                    for r in soft_runs
                                    if r["dt_over_tc"] == k and r["integrator"] == integ)])
        for k in ratios)
    coarse_sign = {i: [np.sign(r["signed"]) for r in soft_runs if r["integrator"] == i and
                       r["dt_over_tc"] >= 0.1 - 1e-12] for i in ("ab2", "verlet")}
    if coarse_sign["ab2"] and coarse_sign["verlet"] and all(x < 0 for x in coarse_sign["ab2"]) \
            and all(x > 0 for x in coarse_sign["verlet"]):
        text += "): ab2 errs towards too little cooling, verlet towards too much. "
    else:
        text += "). "
    if cheap:
        text += (f"The cheapest soft run within 1% is {cheap['label']} ({pct(cheap['err'])}, "
                 f"{secs(cheap['wall'])} s, {cheap['wall'] / ref['wall']:.0f} times the "
                 f"event-driven time). For a dilute gas, use the event-driven backend; a soft "
                 f"run there needs t_c and dt both small.")
    return text


def lessons_c(part):
    out = []
    ref = next(r for r in part["runs"] if r["role"] == "reference")
    noise = next(r for r in part["runs"] if r["role"] == "noise")
    tests = [r for r in part["runs"] if r["role"] == "test"]
    same_tc = [r for r in tests if r["backend"] == "soft_dem" and r["t_c"] == ref["t_c"]]
    done = [r for r in same_tc if np.isfinite(r["err"])]
    blown = [r for r in tests if r["exit"] != 0]
    study = next((r for r in done if r["dt_over_tc"] == 0.02 and r["integrator"] == "ab2"), None)
    if done:
        cheapest = min(done, key=lambda r: r["wall"])
        out.append(
            f"**jet2d profiles (dense flow):** one run's time-averaged profile carries a "
            f"statistical error: an independent start (seed 2) differs by {pct(noise['err_P'])} "
            f"in P and {pct(noise['err_T'])} in T_g bin by bin, though its overall level only by "
            f"{100 * noise['bias_P']:+.1f}% and {100 * noise['bias_T']:+.1f}%. At the study's "
            f"t_c = {ref['t_c']:g}, every dt from {min(r['dt_over_tc'] for r in done):g} to "
            f"{max(r['dt_over_tc'] for r in done):g} t_c (both integrators) differs from the "
            f"reference by as much and no more: P {span([r['err_P'] for r in done], '{:.1f}%')}"
            f" (level {span([r['bias_P'] for r in done])}), T_g "
            f"{span([r['err_T'] for r in done], '{:.0f}%')} (level "
            f"{span([r['bias_T'] for r in done])}). The profiles cannot tell these steps apart, "
            f"so the cheapest ({cheapest['label']}, {secs(cheapest['wall'])} s) gives what the "
            f"study's dt = 0.02 t_c"
            + (f" ({secs(study['wall'])} s)" if study else "")
            + " gives"
            + (", while " + "; ".join(f"{r['label']} ended in a {status_text(r).strip(' ()')}"
                                      for r in blown) if blown else "")
            + ". A smaller dt buys nothing visible here: to sharpen a profile, average longer or "
              "over seeds (`--seeds`); keep dt <= 0.05 t_c where the dissipation itself is the "
              "answer, as in (b).")
    stiff = sorted((r for r in tests if r["backend"] == "soft_dem" and r["t_c"] != ref["t_c"]
                    and np.isfinite(r["err"])), key=lambda r: -r["t_c"])
    hard = [r for r in tests if r["backend"] == "event_driven" and np.isfinite(r["err"])]
    if (stiff or hard) and done:
        # Levels against the mean of all runs at the reference t_c (reference, seed 2, every
        # dt): one run's level scatters by a few per cent, the mean of many much less.
        base = [ref, noise] + done
        mean_t = np.mean([1 + (0 if r is ref else r["bias_T"]) for r in base])
        mean_p = np.mean([1 + (0 if r is ref else r["bias_P"]) for r in base])
        spread_t = np.std([1 + (0 if r is ref else r["bias_T"]) for r in base]) / mean_t

        def level_t(r):
            return (1 + r["bias_T"]) / mean_t - 1

        def level_p(r):
            return (1 + r["bias_P"]) / mean_p - 1
        by_tc = {}
        for r in stiff:
            by_tc.setdefault(r["t_c"], []).append(level_t(r))
        text = (f"The model, not the step, moves the profiles, and mostly the level of T_g. "
                f"Against the mean level of the {len(base)} soft runs at t_c = {ref['t_c']:g} "
                f"(one run's T_g level scatters by {100 * spread_t:.0f}% about it): "
                + ("stiffer grains run colder, T_g level "
                   + ", ".join(f"{span(v)} at t_c = {t:g}" for t, v in by_tc.items())
                   if stiff else ""))
        if hard:
            text += ("; " if stiff else "") + "hard spheres " + ", ".join(
                f"{r['law']} {100 * level_t(r):+.0f}% ({secs(r['wall'])} s)" for r in hard)
        others = [r for r in stiff + hard if r.get("law") != "tc_model"]
        text += (f". The P level moves by {span([level_p(r) for r in others])} for these, "
                 f"within a run's spread. So as t_c shrinks the soft model walks to the "
                 f"hard-core answer, at a cost growing as 1/t_c.")
        vd = next((r for r in hard if r["law"] == "velocity_dependent"), None)
        stiffest = stiff[-1] if stiff else None
        if vd and stiffest:
            gap = abs(level_t(stiffest) - level_t(vd))
            text += (f" For the hard-core question (model HC) the event-driven backend answers "
                     f"in {secs(vd['wall'])} s; soft DEM at t_c = {stiffest['t_c']:g} takes "
                     f"{secs(stiffest['wall'])} s and "
                     + (f"comes within the spread of it ({100 * level_t(stiffest):+.0f}% "
                        f"against {100 * level_t(vd):+.0f}%)" if gap < 2 * spread_t else
                        f"is still {100 * gap:.0f} points of T_g level away")
                     + f". To reproduce the study it has to be soft DEM at the study's t_c: the "
                       f"hard-core T_g is {abs(100 * level_t(vd)):.0f}% "
                       f"{'lower' if level_t(vd) < 0 else 'higher'}.")
        tc = next((r for r in hard if r["law"] == "tc_model"), None)
        if tc:
            text += (f" The tc_model law (ed.tc = 0.1) is fastest ({secs(tc['wall'])} s) but "
                     f"not the same physics: a collision is elastic whenever either grain "
                     f"collided less than ed.tc ago, which in the dense zone switches off much of "
                     f"the dissipation (T_g level {100 * level_t(tc):+.0f}%).")
        out.append(text)
    return out


def lessons(results):
    """The 'what this teaches' bullets, each computed from the numbers of this run."""
    out = []
    if "a" in results:
        runs = results["a"]["runs"]
        by = {i: [r for r in runs if r["integrator"] == i] for i in ("ab2", "verlet")}
        one = {i: largest_ratio(rs, 0.01) for i, rs in by.items()}
        text = []
        for integ, rs in by.items():
            at = {r["dt_over_tc"]: r for r in rs}
            coarse = at.get(0.1) or max(rs, key=lambda r: r["dt_over_tc"])
            text.append(
                f"{integ} keeps e and t_c within 1% for every onset phase up to dt = "
                f"{one[integ]:g} t_c and within 0.1% "
                + (f"up to {largest_ratio(rs, 0.001):g} t_c; "
                   if np.isfinite(largest_ratio(rs, 0.001)) else "at none of these steps; ")
                + f"at dt = {coarse['dt_over_tc']:g} t_c e spreads over "
                f"{coarse['e_min']:.3f}-{coarse['e_max']:.3f} with the onset phase")
        study = {i: next((r for r in rs if r["dt_over_tc"] == 0.02), None) for i, rs in by.items()}
        tc_note = ""
        if all(study.values()) and study["verlet"]["err_tc"] > 0:
            tc_note = (f" At the study's dt = 0.02 t_c verlet's contact time is "
                       f"{study['ab2']['err_tc'] / study['verlet']['err_tc']:.0f} times closer "
                       f"than ab2's ({pct(study['verlet']['err_tc'])} against "
                       f"{pct(study['ab2']['err_tc'])}), e equally good.")
        for r in runs:
            if r.get("failed"):
                text.append(f"{r['integrator']} at dt = {r['dt_over_tc']:g} t_c stops as a "
                            f"blow-up at {r['failed']} of {r['phase_count']} onset phases")
        gain = [r for r in runs if np.isfinite(r["err"]) and r["e_max"] > 1]
        if gain:
            worst = max(gain, key=lambda r: r["e_max"])
            text.append(f"{worst['integrator']} at dt = {worst['dt_over_tc']:g} t_c even gains "
                        f"energy in a collision (e up to {worst['e_max']:.2f})")
        out.append("**Binary collision (soft DEM's accuracy per step):** " + "; ".join(text)
                   + f". The study's dt = 0.02 t_c is {min(one.values()) / 0.02:.1f} times finer "
                     "than 1% accuracy needs, and a soft run's cost is proportional to t_c/dt."
                   + tc_note)
    if "b" in results:
        out.append(lesson_b(results["b"]))
    if "c" in results:
        out += lessons_c(results["c"])
    return out


def document(results, meta, path, png):
    m = meta["machine"]
    lines = [
        "# Run time against error",
        "",
        "The framework's headline result: what each backend and setting costs "
        "and how far its answer is from a reference. Regenerate with",
        "",
        "    /usr/bin/python3 scripts/run_time_vs_error.py --granjet build/app/granjet",
        "",
        f"![run time against error]({os.path.basename(png)})",
        "",
        "## Where it was measured",
        "",
        f"- commit `{m['commit']}` ({meta['version']}), {meta['date']}",
        f"- {m['cpu']}, {m['cpus']} CPUs"
        + (f" ({m['hypervisor']} virtual machine)" if m.get("hypervisor") else "")
        + f", {m['uname']}",
        f"- every run on one core (soft DEM with `run.threads = 1`), one after the other; wall time = time.perf_counter "
        f"around the `granjet run` process (start-up, set-up, inline analysis and HDF5 output "
        f"included), CPU = the child's user + system time. "
        + ("The machine was running other jobs (load average "
           f"{meta['load'][0]:.1f} at the start, {meta['load'][1]:.1f} at the end), so wall times "
           "carry that noise; where wall and CPU time differ, the machine was busy."
           if meta.get("shared") else ""),
        f"- the whole command took {meta['total_seconds'] / 60:.1f} minutes "
        f"({meta['total_seconds']:.0f} s)"
        + (" (--quick)" if meta.get("quick") else ""),
        "",
        "## What this teaches a user choosing a backend",
        "",
    ]
    lines += [f"- {text}" for text in lessons(results)]
    if "a" in results:
        part = results["a"]
        lines += [
            "", "## (a) Binary collision: error in e and t_c against dt/t_c", "",
            "scenes/binary.ini: two spheres head-on at u0, requested e = 0.75, t_c = 0.1; e and "
            "t_c measured from the trajectory (the gap sampled every step, its zero crossings "
            "interpolated linearly). In a real run a contact starts anywhere within a step, and "
            "at coarse steps the result depends on where: each dt is run at "
            f"{part['runs'][0].get('phase_count', 1)} onset phases (binary.gap moved by "
            f"k/{part['runs'][0].get('phase_count', 1)} of one step's travel) and the table gives the mean, the range and the worst "
            "error over them. The run of two grains takes milliseconds, all of it start-up, so "
            "the panel puts the steps per contact, t_c/dt, on the cost axis: the run time of any "
            "soft DEM run at a given t_c is proportional to it.", "",
            table_a(part), "",
            f"Pareto front (cost t_c/dt, error the larger of the two worst errors): "
            f"{front_text('a', part)}."]
    if "b" in results:
        part = results["b"]
        lines += [
            "", "## (b) Homogeneous cooling: soft DEM against the hard-sphere limit", "",
            f"scenes/{part['scene']}"
            + (" (shrunk: " + ", ".join(f"{k} = {v}" for k, v in part["runs"][0]["sets"].items()
                                       if k not in ("ed.restitution_law", "output.interval"))
               + ")" if any(k not in ("ed.restitution_law", "output.interval")
                            for k in part["runs"][0]["sets"]) else "")
            + ": a dilute periodic gas (phi = 0.05, e = 0.9) cooling from T = 1. Error: the "
              "Haff cooling rate `measured.cooling_rate` (-d ln T/dt at T0, from the "
              "least-squares slope of T^(-1/2) in t over the whole run after the equilibration) "
              "against the event-driven rate from the same start (seed 1), the exact hard-sphere "
              "result, i.e. the t_c -> 0 limit of the soft model. The soft runs share the start "
              "too, so their difference from the reference is mostly systematic; the seed-2 row "
              "shows how far an independent start moves the rate. Last column: the same "
              "integrator and dt/t_c on one frictionless head-on collision at the gas's e = "
              f"{part.get('restitution') or 0:g}, averaged over the contact onset phases as in "
              "(a); (1 - e^2)/(1 - e0^2) - 1 is the bias that alone puts on the cooling rate "
              "(it leaves out what a finite t_c does in a gas).", "",
            table_b(part), "",
            f"Pareto front: {front_text('b', part)}."]
    if "c" in results:
        part = results["c"]
        ref = next(r for r in part["runs"] if r["role"] == "reference")
        common = {k: v for k, v in ref["sets"].items()
                  if k not in ("contact.contact_time", "run.dt", "run.integrator", "run.threads")}
        lines += [
            "", "## (c) jet2d: P and T_g profiles against a converged reference", "",
            f"scenes/jet2d.ini (8,000 bidisperse frictionless disks, e = 0.75, t_end = 300, "
            f"profiles averaged over 180 <= t < 300 as in the study) with "
            + ", ".join(f"`{k} = {v}`" for k, v in common.items())
            + ": the target is fixed for both backends (the event-driven backend cannot tether "
              "it, model §4); the runs' output is the first and last frame and the inline "
              "analysis. Error: the relative L2 distance "
              "||x - x_ref|| / ||x_ref|| of the P and of the T_g profile over both layers' 20 "
              "bins; in brackets the shift sum(x)/sum(x_ref) - 1 (the sign says hotter or "
              "colder). Reference: soft DEM at the scene's t_c = "
              f"{ref['t_c']:g} with dt = {ref['dt_over_tc']:g} t_c (ab2, seed 1). Every run "
              "starts from the same grains (seed 1) except the seed-2 row, the statistical "
              "spread of one run's time average; the flow is chaotic, so even runs from the same "
              "start differ by about that much. The event-driven runs use e0 = 0.75 with the "
              "scene's ed.v0 = 0.1 (velocity_dependent) and ed.tc = 0.1 (tc_model).", "",
            table_c(part), "",
            f"Pareto front (error the larger of P and T_g): {front_text('c', part)}. Among "
            f"the soft runs at t_c = {ref['t_c']:g} the errors are single runs of a chaotic "
            f"flow, within the seed-2 spread of each other, so which of them lie on the front "
            f"is chance; the front says how cheap that spread can be had."]
    lines += ["", "Raw numbers: the script keeps every summary in its work directory "
              "(`--work DIR`, `DIR/results.json`); `--reuse DIR/results.json` redraws this page "
              "and the figure from them.", ""]
    with open(path, "w") as f:
        f.write("\n".join(lines))


# ---- Checks of --quick -----------------------------------------------------------------------
def check(results, md, png):
    problems = []
    for key in "abc":
        if key not in results:
            problems.append(f"part ({key}) missing")
            continue
        ok = [r for r in results[key]["runs"] if r["role"] == "test" and np.isfinite(r["err"])]
        if not ok:
            problems.append(f"part ({key}): no finite error")
        if not any(r.get("pareto") for r in results[key]["runs"]):
            problems.append(f"part ({key}): empty Pareto front")
    if "a" in results:
        for r in results["a"]["runs"]:
            if r["dt_over_tc"] <= 0.02 and not r["err"] < 0.005:
                problems.append(f"binary {r['label']}: error {r['err']} (tests demand 0.5%)")
    with open(png, "rb") as f:
        if f.read(8) != b"\x89PNG\r\n\x1a\n":
            problems.append(f"{png} is not a PNG")
    image = plt.imread(png)
    if image.shape[0] < 300 or image.std() < 0.01:
        problems.append(f"{png} looks empty")
    with open(md) as f:
        text = f.read()
    for needed in ("## (a)", "## (b)", "## (c)", "What this teaches", "commit `", "Pareto"):
        if needed not in text:
            problems.append(f"{md} lacks '{needed}'")
    return problems


# ---- Main ------------------------------------------------------------------------------------
def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--granjet", default=os.path.join(ROOT, "build", "app", "granjet"))
    ap.add_argument("--docs", default=os.path.join(ROOT, "docs"),
                    help="where the .md and .png go (default: docs/)")
    ap.add_argument("--work", help="keep the runs' files here (default: a temporary directory)")
    ap.add_argument("--parts", default="abc", help="which parts to run, e.g. ac")
    ap.add_argument("--quick", action="store_true", help="tiny settings; checks the outputs")
    ap.add_argument("--reuse", help="results.json of an earlier run: redraw without running")
    args = ap.parse_args()

    os.makedirs(args.docs, exist_ok=True)
    md = os.path.join(args.docs, STEM + ".md")
    png = os.path.join(args.docs, STEM + ".png")
    if args.reuse:
        with open(args.reuse) as f:
            saved = json.load(f)
        results, meta = saved["results"], saved["meta"]
    else:
        granjet = os.path.abspath(args.granjet)
        if not os.access(granjet, os.X_OK):
            sys.exit(f"{STEM}: no granjet executable at {granjet} (--granjet PATH)")
        work = args.work or tempfile.mkdtemp(prefix="granjet_pareto_")
        os.makedirs(work, exist_ok=True)
        meta = dict(machine=machine(), version=granjet_version(granjet), quick=args.quick,
                    date=datetime.datetime.now().strftime("%Y-%m-%d %H:%M"), granjet=granjet)
        start = time.perf_counter()
        load_before = os.getloadavg()[0]
        try:
            results = measure(plan(args.quick), Runner(granjet, work), set(args.parts))
            mark_pareto(results)
        finally:
            if not args.work:
                shutil.rmtree(work, ignore_errors=True)
        meta["total_seconds"] = time.perf_counter() - start
        meta["load"] = (load_before, os.getloadavg()[0])
        meta["shared"] = max(meta["load"]) > 1.2
        if args.work:
            with open(os.path.join(work, "results.json"), "w") as f:
                json.dump(dict(results=results, meta=meta), f, indent=1, default=float)
    figure(results, meta, png)
    document(results, meta, md, png)
    print(md)
    print(png)
    print(f"{STEM}: {meta['total_seconds']:.0f} s in all", file=sys.stderr)
    if args.quick:
        problems = check(results, md, png)
        for p in problems:
            print(f"{STEM}: check failed: {p}", file=sys.stderr)
        return 1 if problems else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
