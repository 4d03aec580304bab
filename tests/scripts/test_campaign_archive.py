#!/usr/bin/python3
"""Tests of scripts/campaign_archive.py on a real campaign: campaigns/smoke.ini run by the
granjet binary (a second or so), packed, unpacked elsewhere, continued and reported.

    /usr/bin/python3 tests/scripts/test_campaign_archive.py [--granjet PATH]

PATH defaults to build/app/granjet (CMake passes the built target). Prints "N passed,
M failed" last; exit code 0 only when all pass.
"""
import io
import json
import os
import re
import shutil
import subprocess
import sys
import tarfile
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPTS = os.path.join(ROOT, "scripts")
ARCHIVE = os.path.join(SCRIPTS, "campaign_archive.py")
REPORT = os.path.join(SCRIPTS, "reproduction_report.py")
SMOKE = os.path.join(ROOT, "campaigns", "smoke.ini")
sys.dont_write_bytecode = True  # no __pycache__ in scripts/
GRANJET = None  # the binary under test: script_tests.main_with_granjet sets it from --granjet
sys.path.insert(0, SCRIPTS)
import campaign_data  # noqa: E402
import script_tests  # noqa: E402

GROUPS = ["binary", "hard2d", "jet2d", "jet3d"]  # campaigns/smoke.ini's
RUNS = 10  # its runs; 4 of them 2D jets (FE.1's series stored)


def run(args, expect=0, timeout=120):
    result = subprocess.run(args, capture_output=True, text=True, timeout=timeout)
    assert result.returncode == expect, (f"{args}: exit {result.returncode}, not {expect}\n"
                                         f"{result.stdout}\n{result.stderr}")
    assert "Traceback" not in result.stderr, result.stderr
    return result


def archive(*args, expect=0):
    return run([sys.executable, ARCHIVE, *args], expect)


class Shared:
    """The smoke campaign, its archive and the archive unpacked, made once for all tests (the
    tests that change them work on copies)."""
    base = None

    @classmethod
    def path(cls, what):
        if cls.base is None:
            cls.base = tempfile.mkdtemp(prefix="granjet_archive_test_")
            campaign = os.path.join(cls.base, "campaign")
            run([GRANJET, "campaign", SMOKE, "--out", campaign, "--jobs", "2"])
            archive("pack", campaign, os.path.join(cls.base, "archive"))
            archive("unpack", os.path.join(cls.base, "archive"),
                    os.path.join(cls.base, "unpacked"))
        return os.path.join(cls.base, what)


def files_under(directory):
    """{relative path: bytes} of every file under a directory."""
    found = {}
    for parent, _, names in os.walk(directory):
        for name in names:
            path = os.path.join(parent, name)
            with open(path, "rb") as f:
                found[os.path.relpath(path, directory)] = f.read()
    return found


def run_files(directory):
    return sorted(os.path.join(group, name) for group in GROUPS
                  for name in os.listdir(os.path.join(directory, group))
                  if re.search(r"\.seed\d+\.h5$", name))


def datasets(f, skip="particles"):
    """{path: (value, attributes)} of every dataset of an open file outside /skip, and the
    attributes of every group."""
    found = {}

    def visit(name, item):
        if name.split("/")[0] == skip:
            return
        attrs = {k: np.asarray(v).tolist() for k, v in item.attrs.items()}
        value = item[()] if isinstance(item, h5py.Dataset) else None
        found[name] = (np.asarray(value).tobytes() if value is not None else None, attrs)
    f.visititems(visit)
    return found


def report(campaign_dir, out, *args):
    run([sys.executable, REPORT, campaign_dir, "--out", out, *args])
    with open(os.path.join(out, "reproduction.md"), "rb") as md, \
            open(os.path.join(out, "reproduction", "results.json"), "rb") as results:
        return md.read(), results.read()


def smoke_with_fe1(tmp):
    """campaigns/smoke.ini whose 2D soft jet also serves FE.1 (the section that reads frames):
    the same runs, for the report's --campaign."""
    with open(SMOKE, encoding="utf-8") as f:
        text = f.read().replace("../scenes/", os.path.join(ROOT, "scenes") + "/")
    assert "results = F6.3, F6.4\n" in text
    path = os.path.join(tmp, "smoke_fe1.ini")
    with open(path, "w", encoding="utf-8") as f:
        f.write(text.replace("results = F6.3, F6.4\n", "results = F6.3, F6.4, FE.1\n"))
    return path


def mtimes(directory):
    return {n: os.stat(os.path.join(directory, n)).st_mtime_ns for n in os.listdir(directory)}


# ---- The archive -----------------------------------------------------------------------------
def test_archive_holds_every_run_without_frames_or_sidecars(tmp):
    names = sorted(os.listdir(Shared.path("archive")))
    assert names == sorted([g + ".tar.xz" for g in GROUPS] + ["index.json", "manifest.json"])
    with open(os.path.join(Shared.path("archive"), "index.json"), encoding="utf-8") as f:
        index = json.load(f)
    runs = [n for g in GROUPS for n in index[g] if ".seed" in n]
    assert len(runs) == RUNS and sorted(index) == GROUPS, index
    for group in GROUPS:
        with tarfile.open(os.path.join(Shared.path("archive"), group + ".tar.xz")) as tar:
            members = tar.getmembers()
        inside = [m.name for m in members]
        assert inside == sorted(inside), inside
        assert all(m.mtime == 0 and m.uid == 0 and m.gid == 0 and m.isreg() for m in members)
        assert not any(n.endswith((".xmf", ".partial")) for n in inside), inside
        for summary in index[group]:  # each run: .json .ini .log .h5; each ensemble .json .h5
            stem = f"{group}/{summary[:-5]}"
            wanted = (".json", ".ini", ".log", ".h5") if ".seed" in summary else (".json", ".h5")
            assert all(stem + e in inside for e in wanted), (stem, inside)
    total = sum(os.path.getsize(os.path.join(Shared.path("archive"), n)) for n in names)
    assert total < 400_000, total  # the campaign directory is ~5.7 MB


def test_stripped_files_have_no_frames_but_granjet_reads_them(tmp):
    files = run_files(Shared.path("unpacked"))
    assert len(files) == RUNS, files
    for name in files:
        original = os.path.join(Shared.path("campaign"), name)
        stripped = os.path.join(Shared.path("unpacked"), name)
        info = run([GRANJET, "info", stripped]).stdout
        assert "status: complete" in info and "frames: 0, up to" in info, info
        before = run([GRANJET, "info", original]).stdout
        assert re.sub(r"frames: .*", "", before) == re.sub(r"frames: .*", "", info)
        with h5py.File(original, "r") as a, h5py.File(stripped, "r") as b:
            assert campaign_data.frame_count(a) > 0 and campaign_data.frame_count(b) == 0
            kept = datasets(b)
            series = kept.pop("archive/layer_a_temperature/time", None)
            kept.pop("archive/layer_a_temperature/value", None)
            kept.pop("archive/layer_a_temperature", None)
            kept.pop("archive", None)
            assert datasets(a) == kept, name  # everything but /particles, as it was
            assert (series is not None) == ("2d/" in name), name

            def particles(f):
                found = {}
                f["particles"].visititems(lambda n, item: found.__setitem__(n, item))
                return found
            pa, pb = particles(a), particles(b)
            assert sorted(pa) == sorted(pb), name
            for key, item in pa.items():
                other = pb[key]
                assert sorted(item.attrs) == sorted(other.attrs), key
                for attr in item.attrs:
                    assert np.array_equal(item.attrs[attr], other.attrs[attr]), (key, attr)
                    assert item.attrs.get_id(attr).get_type().get_size() == \
                        other.attrs.get_id(attr).get_type().get_size(), (key, attr)
                if isinstance(item, h5py.Dataset):
                    assert other.dtype == item.dtype and other.chunks == item.chunks, key
                    assert other.shape == (0,) + item.shape[1:], (key, other.shape)
                    assert other.maxshape == (None,) + item.maxshape[1:], (key, other.maxshape)
            # The frame steps and times stay one dataset linked from each particle group.
            grains = b["particles/all"]
            assert grains["id/step"] == grains["position/step"] == grains["velocity/step"]
            frames = "observables/frame_grains/step"
            assert b[frames].shape == a[frames].shape  # the observables keep their rows


def test_campaign_finds_every_archived_run_complete(tmp):
    campaign = os.path.join(tmp, "continued")
    shutil.copytree(Shared.path("unpacked"), campaign)
    before = files_under(campaign)
    out = run([GRANJET, "campaign", SMOKE, "--out", campaign, "--jobs", "1"]).stdout
    line = re.search(r"campaign smoke: (\d+) runs, (\d+) already done, (\d+) to run", out)
    assert line and line.groups() == (str(RUNS), str(RUNS), "0"), out
    assert "seeds combined into" not in out, out  # no ensemble merged again
    after = files_under(campaign)
    changed = sorted(n for n in after if before.get(n) != after[n])
    # Only the invocation is recorded (campaign.lock: the empty file a running campaign locks).
    assert changed == ["campaign.lock", "manifest.json"], changed


def test_report_from_the_archive_is_the_same(tmp):
    fe1 = smoke_with_fe1(tmp)
    for name, args in (("default", ()), ("fe1", ("--campaign", fe1))):
        original = report(Shared.path("campaign"), os.path.join(tmp, name, "a"), *args)
        unpacked = report(Shared.path("unpacked"), os.path.join(tmp, name, "b"), *args)
        assert original == unpacked, f"{name}: the reports differ"
    results = json.loads(original[1])
    assert results["FE.1"]["status"] == "complete", results["FE.1"]
    row = results["FE.1"]["tables"]["bursts"][0]
    assert all(v[0] is not None for k, v in row.items() if k not in ("t_c", "e")), row


def test_layer_a_series_from_the_archive_equals_the_frames(tmp):
    campaign = campaign_data.Campaign(Shared.path("campaign"), smoke_with_fe1(tmp))
    compared = 0
    for group in ("jet2d", "hard2d"):
        for point in campaign.points(group):
            for seed in point.seeds_done():
                name = os.path.relpath(point.seed_path(seed, "h5"), Shared.path("campaign"))
                times, values = campaign_data.layer_a_series(point.seed_path(seed, "h5"))
                stored = os.path.join(Shared.path("unpacked"), name)
                again = campaign_data.layer_a_series(stored)
                assert times.size == 3 and np.isfinite(values).all(), (name, times, values)
                assert np.array_equal(times, again[0]) and np.array_equal(values, again[1])
                with h5py.File(stored, "r") as f:  # what it is, said in the file
                    note = f["archive/layer_a_temperature"].attrs["description"].decode()
                    assert "layer (a)" in note and "layer_a_series" in note, note
                compared += 1
    assert compared == 6, compared


# ---- Churn: what repacking changes --------------------------------------------------------
def test_repacking_changes_no_byte(tmp):
    packed = os.path.join(tmp, "archive")
    shutil.copytree(Shared.path("archive"), packed)
    before, stamps = files_under(packed), mtimes(packed)
    out = archive("pack", Shared.path("campaign"), packed).stdout
    assert out.count("(unchanged)") == len(GROUPS), out
    assert files_under(packed) == before and mtimes(packed) == stamps
    # The unpacked directory packs into the same archive, from nothing: the same bytes.
    again = os.path.join(tmp, "again")
    archive("pack", Shared.path("unpacked"), again)
    assert files_under(again) == before
    archive("pack", Shared.path("campaign"), again, "--force")  # rebuilt: still the same
    assert files_under(again) == before


def test_a_changed_summary_repacks_only_its_group(tmp):
    campaign, packed = os.path.join(tmp, "campaign"), os.path.join(tmp, "archive")
    shutil.copytree(Shared.path("campaign"), campaign)
    shutil.copytree(Shared.path("archive"), packed)
    before, stamps = files_under(packed), mtimes(packed)
    summary = os.path.join(campaign, "jet3d", "jet3d.seed2.json")
    with open(summary, encoding="utf-8") as f:
        data = json.load(f)
    data["wall_seconds"] += 1.0  # as if seed 2 had run again
    with open(summary, "w", encoding="utf-8") as f:
        json.dump(data, f, indent=2)
    out = archive("pack", campaign, packed).stdout
    assert re.search(r"^jet3d: 2 runs, 1 ensembles, .* \(written\)$", out, re.M), out
    assert out.count("(unchanged)") == len(GROUPS) - 1, out
    after = files_under(packed)
    changed = sorted(n for n in after if after[n] != before[n])
    assert changed == ["index.json", "jet3d.tar.xz"], changed
    assert all(mtimes(packed)[n] == stamps[n] for n in stamps if n not in changed)
    with tarfile.open(os.path.join(packed, "jet3d.tar.xz")) as tar:
        assert json.load(tar.extractfile("jet3d/jet3d.seed2.json")) == data
        with tarfile.open(os.path.join(Shared.path("archive"), "jet3d.tar.xz")) as old:
            for name in tar.getnames():  # the other members as they were
                if name != "jet3d/jet3d.seed2.json":
                    assert tar.extractfile(name).read() == old.extractfile(name).read(), name
    # A run that is no longer complete leaves the archive.
    data["status"] = "failed"
    with open(summary, "w", encoding="utf-8") as f:
        json.dump(data, f, indent=2)
    archive("pack", campaign, packed)
    with tarfile.open(os.path.join(packed, "jet3d.tar.xz")) as tar:
        assert not any(n.startswith("jet3d/jet3d.seed2.") for n in tar.getnames())


# ---- unpack ----------------------------------------------------------------------------------
def test_unpack_leaves_differing_files_alone_unless_forced(tmp):
    campaign = os.path.join(tmp, "campaign")
    shutil.copytree(Shared.path("unpacked"), campaign)
    log = os.path.join(campaign, "jet2d", "friction-0.seed1.log")
    with open(log, "a", encoding="utf-8") as f:
        f.write("edited here\n")
    os.remove(os.path.join(campaign, "jet3d", "jet3d.seed1.ini"))
    result = archive("unpack", Shared.path("archive"), campaign, expect=1)
    assert log in result.stderr and "--force" in result.stderr, result.stderr
    assert not os.path.exists(os.path.join(campaign, "jet3d", "jet3d.seed1.ini"))  # none
    with open(log, encoding="utf-8") as f:
        assert f.read().endswith("edited here\n")
    result = archive("unpack", Shared.path("archive"), campaign, "--force")
    assert f"replaced (--force): {log}" in result.stdout, result.stdout
    assert files_under(campaign) == files_under(Shared.path("unpacked"))


def test_unpack_over_the_original_keeps_its_frames(tmp):
    campaign = os.path.join(tmp, "campaign")
    shutil.copytree(Shared.path("campaign"), campaign)
    before = files_under(campaign)
    out = archive("unpack", Shared.path("archive"), campaign).stdout
    assert "unpacked 0 files" in out, out
    assert files_under(campaign) == before  # the same runs: the files with frames stay


def test_unpack_refuses_members_outside_the_campaign(tmp):
    for bad in ("../escaped.txt", "evil/../../escaped.txt", "/tmp/escaped.txt",
                "other/file.txt", "evil"):
        packed = os.path.join(tmp, "archive")
        shutil.rmtree(packed, ignore_errors=True)
        os.makedirs(packed)
        with tarfile.open(os.path.join(packed, "evil.tar.xz"), "w:xz") as tar:
            info = tarfile.TarInfo(bad)
            info.size = 3
            tar.addfile(info, io.BytesIO(b"bad"))
        target = os.path.join(tmp, "deep", "campaign")
        result = archive("unpack", packed, target, expect=2)
        assert "refused member" in result.stderr, result.stderr
        assert not os.path.exists(os.path.join(tmp, "deep")), bad
        assert not os.path.exists(os.path.join(tmp, "escaped.txt")), bad
    with tarfile.open(os.path.join(packed, "evil.tar.xz"), "w:xz") as tar:
        link = tarfile.TarInfo("evil/link")
        link.type, link.linkname = tarfile.SYMTYPE, "/etc/passwd"
        tar.addfile(link)
    result = archive("unpack", packed, os.path.join(tmp, "campaign"), expect=2)
    assert "not a regular file" in result.stderr, result.stderr


def test_bad_input_exits_2(tmp):
    missing = os.path.join(tmp, "none")
    result = archive("pack", missing, os.path.join(tmp, "archive"), expect=2)
    assert "is not a directory" in result.stderr, result.stderr
    assert not os.path.exists(os.path.join(tmp, "archive"))
    result = archive("unpack", missing, os.path.join(tmp, "campaign"), expect=2)
    assert "is not a directory" in result.stderr, result.stderr
    result = archive("pack", tmp, os.path.join(tmp, "archive"), expect=2)
    assert "not a campaign directory" in result.stderr, result.stderr
    result = archive("unpack", Shared.path("campaign"), os.path.join(tmp, "c"), expect=2)
    assert "not a campaign archive" in result.stderr, result.stderr
    assert not os.path.exists(os.path.join(tmp, "c"))


def cleanup():
    if Shared.base:
        shutil.rmtree(Shared.base, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(script_tests.main_with_granjet(globals(), ROOT, cleanup))
