#!/usr/bin/python3
"""A campaign's results without its trajectories: small enough to keep in git, so that a
campaign longer than one sitting carries over to a fresh machine.

    /usr/bin/python3 scripts/campaign_archive.py pack CAMPAIGN_DIR ARCHIVE_DIR [--force]
    /usr/bin/python3 scripts/campaign_archive.py unpack ARCHIVE_DIR CAMPAIGN_DIR [--force]

The run files' frames (/particles, and /connectivity and /contacts when stored) are nearly all of a campaign's bytes, and nothing but FE.1
reads them. `pack` writes ARCHIVE_DIR/<group>.tar.xz per group of CAMPAIGN_DIR with every
complete run (its summary says so) and every ensemble: the .json, .ini and .log as they are and
the .h5 with /particles emptied: same groups, datasets, types and attributes, zero frames (so
`granjet info` reads it and `granjet campaign` finds the run complete). For 2D jet runs the
one measure taken from frames, FE.1's T_g(t) in layer (a) (campaign_data.layer_a_series), is
stored at /archive/layer_a_temperature first. .xmf sidecars (they point at the frames) and
.partial files are left out; DIR/manifest.json is copied. ARCHIVE_DIR/index.json maps each
group to {summary file: sha256 of that .json}; a group's tar is rewritten only when that
changes (--force: always), so repacking an unchanged campaign changes no byte. Tars are
reproducible: sorted members, mtime 0, owner 0, written to a temporary file and renamed.
Groups of the archive no longer in CAMPAIGN_DIR are kept (and named). Runs that blew up are
not archived (their .h5.partial neither): a campaign continued from the archive runs them again.

`unpack` extracts every group tar into CAMPAIGN_DIR (created if need be); a file already there
with other content is left alone and named (exit 1) unless --force replaces it; the manifest
is copied if CAMPAIGN_DIR has none. Then `granjet campaign FILE --out CAMPAIGN_DIR` continues
the campaign (0 runs to do for what the archive holds) and scripts/reproduction_report.py
gives the same report as from the original directory.

Exit codes: 0 done; 1 unpack found files that differ (nothing written); 2 bad input (a missing
directory, not a campaign directory or archive, an unsafe or inconsistent tar member).
"""
import argparse
import hashlib
import io
import json
import os
import re
import sys
import tarfile
import tempfile

import h5py
import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in scripts/
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import campaign_data  # noqa: E402

INDEX = "index.json"
MANIFEST = "manifest.json"
TAR_SUFFIX = ".tar.xz"
RUN_SUMMARY = re.compile(r"^.+\.seed\d+\.json$")
RUN_FILES = (".json", ".ini", ".log", ".h5")
ENSEMBLE_FILES = (".json", ".h5")
CONTACT_GROUPS = ("connectivity", "contacts")  # output.fields = contacts: frames too
XZ_PRESET = 9  # the archive's size matters more than packing time; 9 needs ~700 MB to pack
SERIES_PARENT, SERIES_NAME = campaign_data.LAYER_A_SERIES.split("/")
SERIES_NOTE = ("FE.1's T_g(t) in layer (a), -dy < y < 0, inside the analysis window "
               "(scripts/campaign_data.py layer_a_series), computed from this run's frames "
               "before scripts/campaign_archive.py dropped them (source_frames: how many)")


class BadInput(Exception):
    """A problem with the command's input: exit code 2, the message on stderr."""


def sha256(data):
    return hashlib.sha256(data).hexdigest()


def read_bytes(path):
    with open(path, "rb") as f:
        return f.read()


def write_atomically(path, data):
    directory = os.path.dirname(path) or "."
    fd, tmp = tempfile.mkstemp(dir=directory, prefix="." + os.path.basename(path) + ".")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise


def human(size):
    for unit in ("B", "kB", "MB", "GB"):
        if size < 1000 or unit == "GB":
            return f"{size:.0f} {unit}" if unit == "B" else f"{size:.1f} {unit}"
        size /= 1000
    return ""


# ---- Stripping a run file's frames ----------------------------------------------------------
def copy_attributes(source, target):
    """Every attribute of one HDF5 object onto another, with its exact file type (string
    padding and length included)."""
    for i in range(h5py.h5a.get_num_attrs(source)):
        attribute = h5py.h5a.open(source, index=i)
        file_type = attribute.get_type()
        if h5py.check_ref_dtype(attribute.dtype) is not None:
            copy_reference(attribute, source, target)
            continue
        variable = h5py.check_vlen_dtype(attribute.dtype) is not None or (
            h5py.check_string_dtype(attribute.dtype) is not None
            and h5py.check_string_dtype(attribute.dtype).length is None)
        memory_type = None if variable else file_type
        data = np.empty(attribute.shape, dtype=attribute.dtype)
        attribute.read(data, mtype=memory_type)
        copy = h5py.h5a.create(target, attribute.name, file_type, attribute.get_space())
        copy.write(data, mtype=memory_type)


def copy_reference(attribute, source, target):
    """An object reference attribute (H5MD's particles_group) points into its own file: the
    copy points at the object of the same path in the target file, which must exist."""
    refs = np.empty(attribute.shape, dtype=attribute.dtype)
    attribute.read(refs)
    target_file = h5py.h5i.get_file_id(target)
    copied = np.array([h5py.h5r.create(target_file, h5py.h5r.get_name(ref, source), h5py.h5r.OBJECT)
                       for ref in refs.flat], dtype=attribute.dtype).reshape(attribute.shape)
    copy = h5py.h5a.create(target, attribute.name, attribute.get_type(), attribute.get_space())
    copy.write(copied)


def empty_frames(source, target_group, name):
    """A dataset like `source` whose first (frame) axis is unlimited and has 0 entries: the same
    type, other dimensions, chunks, filters, fill value and attributes."""
    shape = (0,) + source.shape[1:]
    maxshape = tuple(h5py.h5s.UNLIMITED if n is None else n for n in source.maxshape)
    space = h5py.h5s.create_simple(shape, maxshape)
    dcpl = source.id.get_create_plist()
    dcpl.set_obj_track_times(False)  # no creation time: the same input gives the same bytes
    dataset = h5py.h5d.create(target_group.id, name.encode(), source.id.get_type(), space,
                              dcpl=dcpl)
    copy_attributes(source.id, dataset)


def copy_without_frames(source, target_parent, name, made):
    """The group `source` (/particles) as `name` under target_parent, with its groups, links and
    attributes, each dataset with an unlimited first axis emptied (others copied). Objects
    linked from several places inside it stay one object (made: source address -> new path)."""
    gcpl = source.id.get_create_plist()
    gcpl.set_obj_track_times(False)
    group = h5py.Group(h5py.h5g.create(target_parent.id, name.encode(), gcpl=gcpl))
    made[h5py.h5o.get_info(source.id).addr] = group.name
    copy_attributes(source.id, group.id)
    for key in source:  # name order: deterministic
        link = source.get(key, getlink=True)
        if isinstance(link, (h5py.SoftLink, h5py.ExternalLink)):
            group[key] = link
            continue
        item = source[key]
        address = h5py.h5o.get_info(item.id).addr
        if address in made:
            group[key] = group.file[made[address]]  # a hard link, as in the source
        elif isinstance(item, h5py.Group):
            copy_without_frames(item, group, key, made)
        elif isinstance(item, h5py.Dataset) and item.maxshape and item.maxshape[0] is None:
            empty_frames(item, group, key)
            made[address] = group[key].name
        else:
            h5py.h5o.copy(source.id, key.encode(), group.id, key.encode())
            made[address] = group[key].name


def layer_a_series_of(path):
    """(times, values, frames) of FE.1's series for a 2D jet run file: computed from its frames
    (campaign_data.layer_a_series, by the file's own resolved scene), or the stored one of a
    file packed before; None for other files."""
    with h5py.File(path, "r") as f:
        frames = campaign_data.frame_count(f)
        stored = f.get(campaign_data.LAYER_A_SERIES)
        if frames == 0:
            if stored is None:
                return None
            frames = int(stored.attrs.get("source_frames", 0))
            return stored["time"][()], stored["value"][()], frames
        grains = f["particles/all"]
        if "parameters/granjet/scene" not in f or not all(k in grains for k in ("id", "velocity")):
            return None
    scene = campaign_data.ResolvedScene.of_run_file(path)
    if scene.param("scene.kind") != "jet" or scene.param("scene.dimension") != "2":
        return None
    return (*campaign_data.layer_a_series(path), frames)


def untracked_group(parent, name):
    gcpl = h5py.h5p.create(h5py.h5p.GROUP_CREATE)
    gcpl.set_obj_track_times(False)  # no creation time: the same input gives the same bytes
    return h5py.Group(h5py.h5g.create(parent.id, name.encode(), gcpl=gcpl))


def strip_frames(source, target):
    """Writes `target`: the run file `source` without frames (see the module's docstring), with
    FE.1's series stored when `source` has the frames for it (or had: a file packed before
    gives the same bytes again). Returns whether it stored one."""
    series = layer_a_series_of(source)
    with h5py.File(source, "r") as src, h5py.File(target, "w") as dst:
        copy_attributes(src["/"].id, dst["/"].id)
        made = {}  # frame groups share the frames' step and time
        for key in src:
            if key == SERIES_PARENT and series is not None or key in CONTACT_GROUPS:
                continue  # written below
            link = src.get(key, getlink=True)
            if isinstance(link, (h5py.SoftLink, h5py.ExternalLink)):
                dst[key] = link
            elif key == "particles":
                copy_without_frames(src[key], dst, key, made)
            else:
                h5py.h5o.copy(src.id, key.encode(), dst.id, key.encode())
        # After /particles, which their step, time and particles_group point at.
        for key in CONTACT_GROUPS:
            if key in src:
                copy_without_frames(src[key], dst, key, made)
        if series is not None:
            times, values, frames = series
            stored = untracked_group(untracked_group(dst, SERIES_PARENT), SERIES_NAME)
            stored.attrs.create("description", np.bytes_(SERIES_NOTE))
            stored.attrs.create("source_frames", np.int64(frames))
            stored.create_dataset("time", data=np.asarray(times, dtype=np.float64),
                                  track_times=False)
            stored.create_dataset("value", data=np.asarray(values, dtype=np.float64),
                                  track_times=False)
    return series is not None


# ---- pack ------------------------------------------------------------------------------------
class Member:
    """A complete run or an ensemble of a group: its files and the hash of its summary."""

    def __init__(self, directory, summary, kind, summary_bytes):
        self.kind = kind
        self.summary = summary  # the .json's name: the key in index.json
        self.stem = summary[: -len(".json")]
        self.sha = sha256(summary_bytes)
        extensions = RUN_FILES if kind == "run" else ENSEMBLE_FILES
        self.files = [self.stem + e for e in extensions
                      if os.path.isfile(os.path.join(directory, self.stem + e))]


def group_members(directory):
    """The complete runs and the ensembles in a group's directory, by summary name."""
    members = {}
    for name in sorted(os.listdir(directory)):
        path = os.path.join(directory, name)
        if not name.endswith(".json") or not os.path.isfile(path):
            continue
        data = read_bytes(path)
        if RUN_SUMMARY.match(name):
            try:
                complete = json.loads(data).get("status") == "complete"
            except (ValueError, AttributeError):
                complete = False
            if not complete:
                continue
            member = Member(directory, name, "run", data)
            if member.stem + ".h5" not in member.files:
                print(f"  {name}: complete but no {member.stem}.h5; left out", file=sys.stderr)
                continue
        else:
            member = Member(directory, name, "ensemble", data)
        members[name] = member
    return members


def tar_contents(path, names):
    """{member name: bytes} of those members of an existing tar that are wanted."""
    found = {}
    try:
        with tarfile.open(path, "r:xz") as tar:
            for info in tar:
                if info.isreg() and info.name in names:
                    found[info.name] = tar.extractfile(info).read()
    except (OSError, tarfile.TarError, EOFError):
        return {}
    return found


def write_tar(path, contents):
    """A reproducible tar.xz of {name: bytes}: sorted, mtime 0, owner 0, mode 644; built in
    memory (a group's tar is small) and written atomically."""
    buffer = io.BytesIO()
    with tarfile.open(fileobj=buffer, mode="w:xz", format=tarfile.GNU_FORMAT,
                      preset=XZ_PRESET) as tar:
        for name in sorted(contents):
            info = tarfile.TarInfo(name)
            info.size, info.mtime, info.mode = len(contents[name]), 0, 0o644
            info.uid = info.gid = 0
            info.uname = info.gname = ""
            tar.addfile(info, io.BytesIO(contents[name]))
    write_atomically(path, buffer.getvalue())


def has_particles(path):
    with h5py.File(path, "r") as f:
        return "particles" in f


def group_contents(group, directory, members, reuse, scratch):
    """{tar member name: bytes} of a group; `reuse` holds members of the group's previous tar
    for summaries whose hash is unchanged (not stripped again)."""
    contents = {}
    for member in members.values():
        for name in member.files:
            arcname = f"{group}/{name}"
            if arcname in reuse:
                contents[arcname] = reuse[arcname]
            elif name.endswith(".h5") and has_particles(os.path.join(directory, name)):
                stripped = os.path.join(scratch, "stripped.h5")
                strip_frames(os.path.join(directory, name), stripped)
                contents[arcname] = read_bytes(stripped)
                os.remove(stripped)
            else:
                contents[arcname] = read_bytes(os.path.join(directory, name))
    return contents


def campaign_groups(campaign_dir):
    """The groups the campaign directory's manifest names (its runs' and ensembles')."""
    if not os.path.isdir(campaign_dir):
        raise BadInput(f"'{campaign_dir}' is not a directory")
    manifest = os.path.join(campaign_dir, MANIFEST)
    try:
        with open(manifest, encoding="utf-8") as f:
            data = json.load(f)
        entries = list(data.get("runs", {}).values()) + list(data.get("ensembles", {}).values())
        return sorted({e["group"] for e in entries})
    except (OSError, ValueError, AttributeError, KeyError, TypeError) as error:
        raise BadInput(f"'{campaign_dir}' is not a campaign directory (no readable {MANIFEST} "
                       f"naming its groups: {error})") from None


def read_index(archive_dir):
    path = os.path.join(archive_dir, INDEX)
    if not os.path.isfile(path):
        return {}
    try:
        with open(path, encoding="utf-8") as f:
            index = json.load(f)
    except ValueError as error:
        raise BadInput(f"'{path}' is not JSON: {error}") from None
    if not isinstance(index, dict):
        raise BadInput(f"'{path}' is not a mapping of group to members")
    return index


def write_if_changed(path, data):
    """Writes `data` unless the file holds it already; whether it wrote."""
    if os.path.isfile(path) and read_bytes(path) == data:
        return False
    write_atomically(path, data)
    return True


def pack(campaign_dir, archive_dir, force=False):
    groups = campaign_groups(campaign_dir)
    if os.path.exists(archive_dir) and not os.path.isdir(archive_dir):
        raise BadInput(f"'{archive_dir}' is not a directory")
    os.makedirs(archive_dir, exist_ok=True)
    index = read_index(archive_dir)
    new_index = dict(index)
    total = tars = 0
    with tempfile.TemporaryDirectory(prefix="granjet_archive_") as scratch:
        for group in groups:
            directory = os.path.join(campaign_dir, group)
            if not os.path.isdir(directory):
                continue
            members = group_members(directory)
            runs = sum(m.kind == "run" for m in members.values())
            ensembles = len(members) - runs
            tar_path = os.path.join(archive_dir, group + TAR_SUFFIX)
            hashes = {name: m.sha for name, m in members.items()}
            if not members:
                kept = "; its tar is kept" if os.path.isfile(tar_path) else ""
                print(f"{group}: no complete run{kept}")
                continue
            if not force and index.get(group) == hashes and os.path.isfile(tar_path):
                state = "unchanged"
            else:
                previous = index.get(group, {}) if not force else {}
                kept = {f"{group}/{n}" for name, m in members.items()
                        if previous.get(name) == m.sha for n in m.files}
                reuse = tar_contents(tar_path, kept) if kept else {}
                write_tar(tar_path, group_contents(group, directory, members, reuse, scratch))
                new_index[group] = hashes
                state = "written"
            size = os.path.getsize(tar_path)
            total, tars = total + size, tars + 1
            print(f"{group}: {runs} runs, {ensembles} ensembles, {human(size)} ({state})")
    for group in sorted(set(new_index) - set(groups)):
        print(f"{group}: not in {campaign_dir}; its tar is kept")
    write_if_changed(os.path.join(archive_dir, INDEX),
                     (json.dumps(new_index, indent=2, sort_keys=True) + "\n").encode())
    write_if_changed(os.path.join(archive_dir, MANIFEST),
                     read_bytes(os.path.join(campaign_dir, MANIFEST)))
    print(f"archive {archive_dir}: {human(total)} in the {tars} group tars of this campaign")
    return 0


# ---- unpack ----------------------------------------------------------------------------------
def safe_member(info, group):
    """Why a tar member may not be extracted, or None: only regular files <group>/<name>."""
    parts = info.name.split("/")
    if not info.isreg():
        return "not a regular file"
    if info.name.startswith("/") or ".." in parts or "" in parts or "." in parts:
        return "a path outside the campaign directory"
    if len(parts) != 2 or parts[0] != group:
        return f"not a file of group '{group}' (<group>/<name>)"
    return None


def archive_tars(archive_dir):
    if not os.path.isdir(archive_dir):
        raise BadInput(f"'{archive_dir}' is not a directory")
    tars = sorted(n for n in os.listdir(archive_dir) if n.endswith(TAR_SUFFIX))
    if not tars:
        raise BadInput(f"'{archive_dir}' is not a campaign archive (no <group>{TAR_SUFFIX})")
    return tars


def read_group_tar(archive_dir, tar_name, index):
    """{member name: bytes} of a group's tar, every member checked: a regular file
    <group>/<name>, and each summary matching index.json when there is one."""
    group = tar_name[: -len(TAR_SUFFIX)]
    contents = {}
    try:
        with tarfile.open(os.path.join(archive_dir, tar_name), "r:xz") as tar:
            for info in tar:
                why = safe_member(info, group)
                if why:
                    raise BadInput(f"{tar_name}: refused member '{info.name}': {why}")
                contents[info.name] = tar.extractfile(info).read()
    except (tarfile.TarError, EOFError, OSError) as error:
        raise BadInput(f"{tar_name}: not a readable tar.xz ({error})") from None
    for name, data in contents.items():
        expected = index.get(group, {}).get(name.split("/")[1])
        if expected is not None and sha256(data) != expected:
            raise BadInput(f"{tar_name}: '{name}' does not match {INDEX} (an archive half "
                           "updated?)")
    return contents


def same_run_here(name, contents, campaign_dir):
    """Whether `name` (an .h5) belongs to a run or ensemble whose summary here is byte for byte
    the archive's: the same execution, so the file here (with its frames, if the campaign ran
    on this machine) is kept."""
    if not name.endswith(".h5"):
        return False
    summary = name[: -len(".h5")] + ".json"
    local = os.path.join(campaign_dir, *summary.split("/"))
    return summary in contents and os.path.isfile(local) and read_bytes(local) == contents[summary]


def unpack(archive_dir, campaign_dir, force=False):
    tars = archive_tars(archive_dir)
    index = read_index(archive_dir)
    if os.path.exists(campaign_dir) and not os.path.isdir(campaign_dir):
        raise BadInput(f"'{campaign_dir}' is not a directory")
    # Every member is checked and compared with what is there before anything is written:
    # nothing is written unless all are safe and none differs (or --force).
    plan, differing = {}, []
    for tar_name in tars:
        group = tar_name[: -len(TAR_SUFFIX)]
        contents = read_group_tar(archive_dir, tar_name, index)
        wanted, same, with_frames = set(), 0, 0
        for name, data in sorted(contents.items()):
            target = os.path.join(campaign_dir, *name.split("/"))
            if not os.path.isfile(target):
                wanted.add(name)
            elif read_bytes(target) == data:
                same += 1
            elif same_run_here(name, contents, campaign_dir):
                with_frames += 1
            else:
                differing.append(name)
                if force:
                    wanted.add(name)
        plan[tar_name] = wanted
        kept = f" ({with_frames} run files kept with their frames)" if with_frames else ""
        print(f"{group}: {len(wanted)} files to write, {same + with_frames} already there{kept}")
    if differing and not force:
        for name in differing:
            print(f"differs from the archive, left alone: {os.path.join(campaign_dir, name)}",
                  file=sys.stderr)
        print(f"{len(differing)} files in {campaign_dir} differ from the archive; nothing "
              "unpacked (--force replaces them)", file=sys.stderr)
        return 1
    for name in differing:
        print(f"replaced (--force): {os.path.join(campaign_dir, name)}")
    written = 0
    for tar_name, wanted in plan.items():
        if not wanted:
            continue
        for name, data in read_group_tar(archive_dir, tar_name, index).items():
            if name in wanted:
                target = os.path.join(campaign_dir, *name.split("/"))
                os.makedirs(os.path.dirname(target), exist_ok=True)
                write_atomically(target, data)
                written += 1
    manifest = os.path.join(archive_dir, MANIFEST)
    target = os.path.join(campaign_dir, MANIFEST)
    if os.path.isfile(manifest):
        os.makedirs(campaign_dir, exist_ok=True)
        if not os.path.exists(target):
            write_atomically(target, read_bytes(manifest))
        elif read_bytes(target) != read_bytes(manifest):
            print(f"kept {target} (it differs from the archive's)")
    print(f"unpacked {written} files into {campaign_dir}")
    return 0


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    commands = parser.add_subparsers(dest="command", required=True)
    p = commands.add_parser("pack", help="CAMPAIGN_DIR -> ARCHIVE_DIR/<group>.tar.xz")
    p.add_argument("campaign_dir")
    p.add_argument("archive_dir")
    p.add_argument("--force", action="store_true", help="rewrite every group's tar")
    u = commands.add_parser("unpack", help="ARCHIVE_DIR -> CAMPAIGN_DIR")
    u.add_argument("archive_dir")
    u.add_argument("campaign_dir")
    u.add_argument("--force", action="store_true",
                   help="replace files of CAMPAIGN_DIR that differ from the archive's")
    args = parser.parse_args(argv)
    try:
        if args.command == "pack":
            return pack(args.campaign_dir, args.archive_dir, args.force)
        return unpack(args.archive_dir, args.campaign_dir, args.force)
    except BadInput as error:
        print(f"campaign_archive.py {args.command}: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
