"""What a `granjet campaign` directory holds, read for scripts/reproduction_report.py.

The plan is rebuilt from the campaign file exactly as campaign/campaign_plan.cpp builds it (groups,
swept keys and their product, point labels, seed lists, --quick keeping the first seed), so
groups added to the file after the campaign ran are listed as not run. The files are where
the campaign writes them: DIR/<group>/<point>.h5 (the ensemble of the point's seeds, read with
plot_analysis.Analysis), DIR/<group>/<point>.seed<N>.{h5,json,ini} (one run each: its analysis,
summary and resolved scene) and DIR/manifest.json (invocations: host, commit, start times;
runs: start, finish, wall seconds). Run files packed by scripts/campaign_archive.py have no
frames; the one measure taken from frames (FE.1's layer_a_series) is stored in them instead.
"""
import configparser
import datetime
import functools
import itertools
import json
import math
import os
import re
from typing import NamedTuple

import h5py
import numpy as np

import plot_analysis

CAMPAIGN_SECTION = "campaign"
GROUP_SETTINGS = ("scene", "results", "backend", "seeds", "quick_fraction", "description")


class Measured(NamedTuple):
    """A value and its error bar (the spread over seeds unless a section says otherwise);
    NaN where there is none (one seed)."""
    value: float
    error: float

    def json(self):
        return [finite_or_none(self.value), finite_or_none(self.error)]


NOT_MEASURED = Measured(math.nan, math.nan)


def finite_or_none(x):
    return float(x) if x is not None and math.isfinite(x) else None


def spread_over_seeds(values):
    """Mean and sample standard deviation (n - 1, as analysis/table.cpp) of the finite values."""
    x = np.array([v for v in values if v is not None and math.isfinite(v)], dtype=float)
    if x.size == 0:
        return NOT_MEASURED
    return Measured(float(x.mean()), float(x.std(ddof=1)) if x.size > 1 else math.nan)


# ---- The campaign file ------------------------------------------------------------------------
def split_list(text):
    return [v.strip() for v in text.split(",") if v.strip()]


def parse_seeds(text):
    """run/seed_list.cpp: a range A..B or a list a, b, c."""
    if ".." in text:
        first, last = (int(v) for v in text.split(".."))
        return list(range(first, last + 1))
    return [int(v) for v in split_list(text)]


def group_comments(path):
    """The comment lines right above each [section] of the campaign file, joined."""
    comments, pending = {}, []
    with open(path, encoding="utf-8") as f:
        for line in f:
            stripped = line.strip()
            if stripped.startswith("#"):
                pending.append(stripped.lstrip("#").strip())
            elif stripped.startswith("["):
                comments[stripped.strip("[]")] = " ".join(pending)
                pending = []
            elif stripped:
                pending = []
    return comments


class Group:
    """One [group] of the campaign file: its settings, scene keys and comment."""

    def __init__(self, name, entries, defaults, base_dir, comment):
        self.name = name
        self.comment = comment
        self.results = split_list(entries.get("results", ""))
        self.backend = entries.get("backend", defaults.get("backend", "soft_dem"))
        seeds = entries.get("seeds", defaults.get("seeds"))
        self.seeds = parse_seeds(seeds) if seeds else []
        self.scene_file = os.path.normpath(os.path.join(base_dir, entries.get("scene", "")))
        self.keys = [(k, split_list(v)) for k, v in entries.items() if k not in GROUP_SETTINGS]

    def scene_value(self, section, key, fallback=None):
        """A key of the group's scene file, before the group's overrides."""
        ini = configparser.ConfigParser(interpolation=None, inline_comment_prefixes=("#",))
        ini.read(self.scene_file, encoding="utf-8")
        return ini.get(section, key, fallback=fallback)

    def dimension(self):
        for key, values in self.keys:
            if key == "scene.dimension":
                return int(values[0])
        return int(self.scene_value("scene", "dimension", "3"))

    def points(self):
        """(label, {key: value}) of every combination of the swept keys, the first swept key
        varying slowest, labelled as campaign/campaign_plan.cpp's point_label."""
        swept = [(k, v) for k, v in self.keys if len(v) > 1]
        fixed = {k: v[0] for k, v in self.keys if len(v) == 1}
        short = [k.rsplit(".", 1)[-1] for k, _ in swept]
        shared = len(set(short)) < len(short)
        for choice in itertools.product(*(v for _, v in swept)):
            label = "_".join(f"{k if shared else s}-{value}"
                             for (k, _), s, value in zip(swept, short, choice))
            params = dict(fixed)
            params.update({k: value for (k, _), value in zip(swept, choice)})
            yield (label or self.name), params


class CampaignFile:
    def __init__(self, path):
        ini = configparser.ConfigParser(interpolation=None, inline_comment_prefixes=("#",),
                                        strict=True)
        ini.optionxform = str  # keys are case-sensitive scene keys
        ini.read(path, encoding="utf-8")
        self.path = path
        defaults = dict(ini[CAMPAIGN_SECTION]) if ini.has_section(CAMPAIGN_SECTION) else {}
        comments = group_comments(path)
        base = os.path.dirname(os.path.abspath(path))
        self.groups = [Group(name, dict(ini[name]), defaults, base, comments.get(name, ""))
                       for name in ini.sections() if name != CAMPAIGN_SECTION]

    def groups_for(self, result_id):
        return [g for g in self.groups if result_id in g.results]

    def group(self, name):
        return next((g for g in self.groups if g.name == name), None)


# ---- The campaign directory ----------------------------------------------------------------
def read_ini(path):
    ini = configparser.ConfigParser(interpolation=None, inline_comment_prefixes=("#",))
    ini.read(path, encoding="utf-8")
    return ini


class Point:
    """One parameter point of a group: its ensemble file and its seeds' run files."""

    def __init__(self, directory, group, label, params, seeds):
        self.group, self.label, self.params, self.seeds = group, label, params, seeds
        self.base = os.path.join(directory, group.name, label)
        self._ensemble = None
        self._seed_cache = {}

    @property
    def name(self):
        return f"{self.group.name}/{self.label}"

    def seed_path(self, seed, extension):
        return f"{self.base}.seed{seed}.{extension}"

    def seeds_done(self):
        """Seeds whose run completed: the summary says so (a run file under its final name is
        complete too, but binary runs write no analysis worth reading)."""
        done = []
        for seed in self.seeds:
            try:
                with open(self.seed_path(seed, "json"), encoding="utf-8") as f:
                    if json.load(f).get("status") == "complete":
                        done.append(seed)
            except (OSError, ValueError):
                pass
        return done

    def seeds_combined(self):
        """Seeds merged into the ensemble file (0 without one)."""
        try:
            with h5py.File(self.base + ".h5", "r") as f:
                return int(f["fields"].attrs.get("seeds", 0))
        except (OSError, KeyError):
            return 0

    def analysed(self):
        """Whether the campaign merges this point's seeds into an ensemble (analysed jets)."""
        return self.param("scene.kind") == "jet" and self.param("analysis.enabled") != "false"

    def state(self):
        """'complete' (every planned seed in the ensemble, or finished for points without
        analysis), 'partial' or 'missing'."""
        done = self.seeds_combined() if self.analysed() else len(self.seeds_done())
        if done == 0:
            return "missing"
        return "complete" if done >= len(self.seeds) else "partial"

    def param(self, key, fallback=None):
        """A scene key of this point: the campaign's override, else the resolved scene of a
        finished seed, else the group's scene file."""
        if key in self.params:
            return self.params[key]
        section, name = key.split(".", 1)
        for seed in self.seeds:
            path = self.seed_path(seed, "ini")
            if os.path.isfile(path):
                return read_ini(path).get(section, name, fallback=fallback)
        return self.group.scene_value(section, name, fallback)

    def number(self, key, fallback=math.nan):
        value = self.param(key)
        return float(value) if value not in (None, "") else fallback

    def ensemble(self):
        """plot_analysis.Analysis of the ensemble file, or None."""
        if self._ensemble is None and os.path.isfile(self.base + ".h5"):
            try:
                self._ensemble = plot_analysis.Analysis(self.base + ".h5")
            except plot_analysis.NotAnalysisFile:
                return None
        return self._ensemble

    def per_seed(self, metric):
        """{seed: metric(Analysis of that seed's run file)} over the finished seeds; metric is
        called once per seed and file (cached by the function object)."""
        values = {}
        for seed in self.seeds:
            path = self.seed_path(seed, "h5")
            if not os.path.isfile(path):
                continue
            key = (seed, metric)
            if key not in self._seed_cache:
                self._seed_cache[key] = evaluate_on_file(path, metric)
            values[seed] = self._seed_cache[key]
        return values

    def over_seeds(self, metric):
        """A scalar metric over the finished seeds, as mean ± std."""
        return spread_over_seeds(self.per_seed(metric).values())

    def close(self):
        if self._ensemble is not None:
            self._ensemble.h5.close()
            self._ensemble = None


def seed_fields(*names):
    """A metric for Point.per_seed: the raw [layers][lateral] means of some fields of one run
    (None when one is absent). The same names give the same function, so the cache holds."""
    return _seed_fields(tuple(names))


@functools.lru_cache(maxsize=None)
def _seed_fields(names):
    def metric(analysis):
        fields = [analysis.field(n, quiet=True) for n in names]
        return None if any(f is None for f in fields) else [f[0] for f in fields]
    return metric


def evaluate_on_file(path, metric):
    try:
        analysis = plot_analysis.Analysis(path)
    except plot_analysis.NotAnalysisFile:
        return None
    with analysis.h5:
        return metric(analysis)


class Campaign:
    """The campaign directory, its manifest and the plan of its campaign file."""

    def __init__(self, directory, campaign_file=None):
        self.directory = os.path.abspath(directory)
        manifest_path = os.path.join(self.directory, "manifest.json")
        self.manifest = {}
        if os.path.isfile(manifest_path):
            with open(manifest_path, encoding="utf-8") as f:
                self.manifest = json.load(f)
        path = campaign_file or self.manifest.get("file")
        if not path or not os.path.isfile(path):
            raise FileNotFoundError(f"no campaign file: '{path}' (pass --campaign FILE)")
        self.file = CampaignFile(path)
        self.quick = any(i.get("quick") for i in self.manifest.get("invocations", []))
        self._points = {}
        for group in self.file.groups:
            seeds = group.seeds or [1]
            if self.quick:
                seeds = seeds[:1]
            self._points[group.name] = [Point(self.directory, group, label, params, seeds)
                                        for label, params in group.points()]

    def points(self, group_name):
        """The points of a group ([] when the campaign file has no such group)."""
        return self._points.get(group_name, [])

    def points_for(self, result_id):
        return [p for g in self.file.groups_for(result_id) for p in self.points(g.name)]

    def all_points(self):
        return [p for g in self.file.groups for p in self.points(g.name)]

    def close(self):
        for p in self.all_points():
            p.close()


# ---- FE.1: T_g(t) in layer (a), from a run's frames ------------------------------------------
# Where scripts/campaign_archive.py stores layer_a_series of a run whose frames it drops.
LAYER_A_SERIES = "archive/layer_a_temperature"


class ResolvedScene:
    """The keys of one run's resolved scene (INI text, e.g. the file's
    /parameters/granjet/scene), with Point's param/number: what layer_a_series needs of a run
    without its campaign file."""

    def __init__(self, ini_text):
        self.ini = configparser.ConfigParser(interpolation=None, inline_comment_prefixes=("#",))
        self.ini.read_string(ini_text)

    @classmethod
    def of_run_file(cls, path):
        with h5py.File(path, "r") as f:
            return cls(plot_analysis.text(f["parameters/granjet/scene"][()]))

    def param(self, key, fallback=None):
        section, name = key.split(".", 1)
        return self.ini.get(section, name, fallback=fallback)

    def number(self, key, fallback=math.nan):
        value = self.param(key)
        return float(value) if value not in (None, "") else fallback


def frame_count(f):
    """Frames stored in an open run file (0 without /particles, or packed without frames)."""
    grains = f.get("particles/all")
    return 0 if grains is None or "position" not in grains else grains["position/time"].shape[0]


def layer_a_series(path):
    """FE.1's T_g(t) in layer (a), -dy < y < 0, of a 2D jet run: from its stored frames inside
    the analysis window by granjet's own measure (analysis/layer_temperature.cpp, through the
    Python module), or, for a file without frames, the series stored at LAYER_A_SERIES
    (campaign_archive.py); else none."""
    with h5py.File(path, "r") as f:
        if frame_count(f) == 0:
            stored = f.get(LAYER_A_SERIES)
            if stored is None:
                return np.empty(0), np.empty(0)
            return stored["time"][()], stored["value"][()]
    return plot_analysis.granjet.open(path).layer_a_temperature()


# ---- What ran where, when and with which commit ---------------------------------------------
def parse_time(text):
    return datetime.datetime.strptime(text, "%Y-%m-%dT%H:%M:%SZ")


def campaign_wall_seconds(manifest):
    """Sum over invocations of their wall time, and the runs' summed wall seconds (the
    CPU-slot time). An invocation that recorded no wall_seconds (older granjet, or stopped)
    counts from its start to the last finish of a run it started (a run belongs to the latest
    invocation started before it)."""
    invocations = manifest.get("invocations", [])
    recorded = sum(float(i["wall_seconds"]) for i in invocations if "wall_seconds" in i)
    starts = sorted((parse_time(i["started"]), "wall_seconds" in i) for i in invocations
                    if "started" in i)
    last_finish = {}
    slot_seconds = 0.0
    for run in manifest.get("runs", {}).values():
        if "started" not in run or "finished" not in run:
            continue
        started = parse_time(run["started"])
        owner = max((s for s in starts if s[0] <= started), default=None)
        if owner is not None and not owner[1]:
            start = owner[0]
            last_finish[start] = max(last_finish.get(start, start), parse_time(run["finished"]))
        slot_seconds += float(run.get("wall_seconds", 0.0))
    estimated = sum((finish - start).total_seconds() for start, finish in last_finish.items())
    return recorded + estimated, slot_seconds


def creator_version(path):
    """The granjet version (0.1.0+<commit>) that wrote a run file, or None."""
    try:
        with h5py.File(path, "r") as f:
            return plot_analysis.text(f["h5md/creator"].attrs["version"])
    except (OSError, KeyError):
        return None


def cpu_model():
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            models = re.findall(r"^model name\s*:\s*(.+)$", f.read(), re.M)
    except OSError:
        return "unknown", 0
    return (models[0].strip() if models else "unknown"), len(models)
