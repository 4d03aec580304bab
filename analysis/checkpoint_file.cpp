#include "analysis/checkpoint_file.hpp"

#include <hdf5.h>

#include <string>
#include <system_error>
#include <vector>

#include "analysis/hdf5_handle.hpp"

namespace granjet::analysis {
namespace {

constexpr const char* kTime = "/app/time";

constexpr const char* kRanks = "checkpoint/ranks";
constexpr const char* kReaders = "checkpoint/readers";
constexpr const char* kShares = "shares/";

// Each entry of `archive` that `keep` accepts, as a dataset under `prefix`.
template <class Keep>
void write_entries(const H5Context& ctx, hid_t file, hid_t link_props, const StateArchive& archive,
                   const std::string& prefix, Keep&& keep) {
  const auto store = [&](const std::string& name, hid_t type, std::size_t n, const void* data) {
    const std::string path = prefix + name;
    const H5Handle set =
        ctx.own(H5Dcreate2(file, path.c_str(), type, ctx.dataspace({static_cast<hsize_t>(n)}).get(),
                           link_props, H5P_DEFAULT, H5P_DEFAULT),
                H5Dclose, "create", path);
    if (n > 0)
      ctx.check(H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "write", path);
  };
  for (const auto& [name, values] : archive.all_reals())
    if (keep(name)) store(name, H5T_NATIVE_DOUBLE, values.size(), values.data());
  for (const auto& [name, values] : archive.all_integers())
    if (keep(name)) store(name, H5T_NATIVE_INT64, values.size(), values.data());
}

std::string share_group(int rank) { return kShares + std::to_string(rank) + "/"; }

void write_file(const H5Context& ctx, const StateArchive& archive, const ShareOfRank& share_of) {
  H5Handle file = ctx.own(H5Fcreate(ctx.file().c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                          H5Fclose, "create", "the HDF5 file");
  const H5Handle link_props =
      ctx.own(H5Pcreate(H5P_LINK_CREATE), H5Pclose, "create", "link properties");
  ctx.check(H5Pset_create_intermediate_group(link_props.get(), 1), "set", "link properties");
  const auto everything = [](const std::string&) { return true; };
  if (archive.ranks() == 1) {
    write_entries(ctx, file.get(), link_props.get(), archive, "", everything);
  } else {
    write_entries(ctx, file.get(), link_props.get(), archive, "",
                  [&](const std::string& name) { return !archive.in_share(name); });
    StateArchive ranks;
    ranks.put(kRanks, std::int64_t{archive.ranks()});
    write_entries(ctx, file.get(), link_props.get(), ranks, "", everything);
    write_entries(ctx, file.get(), link_props.get(), archive, share_group(0),
                  [&](const std::string& name) { return archive.in_share(name); });
    for (int r = 1; r < archive.ranks(); ++r)
      write_entries(ctx, file.get(), link_props.get(), share_of(r), share_group(r), everything);
  }
  ctx.check(file.reset(), "close", "the HDF5 file");  // writes the last metadata
}

// Every dataset of the file, by its path below the root.
std::vector<std::string> dataset_names(const H5Context& ctx, hid_t file) {
  std::vector<std::string> names;
  ctx.check(H5Ovisit(
                file, H5_INDEX_NAME, H5_ITER_INC,
                [](hid_t, const char* name, const H5O_info_t* info, void* out) -> herr_t {
                  if (info->type == H5O_TYPE_DATASET)
                    static_cast<std::vector<std::string>*>(out)->push_back(name);
                  return 0;
                },
                &names),
            "list", "the checkpoint's entries");
  return names;
}

// The file opened read-only; InputError when it is not there or not HDF5.
H5Handle open_checkpoint(const H5Context& ctx) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(ctx.file(), ec) || H5Fis_hdf5(ctx.file().c_str()) <= 0)
    throw InputError(ctx.file().string(),
                     "is not a readable checkpoint (a run stopped before its first "
                     "run.checkpoint_interval has none)");
  return ctx.open_read_only();
}

std::filesystem::path being_written(const std::filesystem::path& checkpoint) {
  std::filesystem::path partial = checkpoint;
  partial += ".partial";
  return partial;
}

}  // namespace

std::filesystem::path checkpoint_path(const std::filesystem::path& run_file) {
  std::filesystem::path path = run_file;
  if (path.extension() == ".partial") path.replace_extension();
  path += ".checkpoint";
  return path;
}

void write_checkpoint_file(const std::filesystem::path& checkpoint, const StateArchive& archive,
                           const ShareOfRank& share_of) {
  if (archive.ranks() > 1 && !share_of)
    throw std::logic_error("a checkpoint split over ranks needs their shares");
  const std::filesystem::path partial = being_written(checkpoint);
  try {
    const H5Context ctx(partial);
    write_file(ctx, archive, share_of);
    std::filesystem::rename(partial, checkpoint);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(partial, ignored);
    throw;
  }
}

void remove_checkpoint_file(const std::filesystem::path& checkpoint) {
  std::filesystem::remove(checkpoint);
  std::filesystem::remove(being_written(checkpoint));
}

StateArchive read_checkpoint_file(const std::filesystem::path& checkpoint, ShareReader who) {
  const H5Context ctx(checkpoint, H5Context::Role::kInput);
  const H5Handle file = open_checkpoint(ctx);
  // The dataset at `path` as entry `name` of `into`: its values, or none (only its kind).
  const auto read = [&](const std::string& path, StateArchive& into, const std::string& name,
                        bool with_values = true) {
    const H5Handle set =
        ctx.own(H5Dopen2(file.get(), path.c_str(), H5P_DEFAULT), H5Dclose, "open", path);
    const H5Handle type = ctx.own(H5Dget_type(set.get()), H5Tclose, "query", path);
    const H5Handle space = ctx.own(H5Dget_space(set.get()), H5Sclose, "query", path);
    const hssize_t n = with_values ? H5Sget_simple_extent_npoints(space.get()) : 0;
    if (n < 0) ctx.fail("count", path);
    const auto values = [&](hid_t memory_type, void* out) {
      if (n > 0)
        ctx.check(H5Dread(set.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out), "read",
                  path);
    };
    if (H5Tget_class(type.get()) == H5T_FLOAT) {
      std::vector<double> v(n);
      values(H5T_NATIVE_DOUBLE, v.data());
      into.put_reals(name, std::move(v));
    } else {
      std::vector<std::int64_t> v(n);
      values(H5T_NATIVE_INT64, v.data());
      into.put_integers(name, std::move(v));
    }
  };
  StateArchive archive;
  const std::vector<std::string> names = dataset_names(ctx, file.get());
  for (const std::string& name : names)
    if (!name.starts_with(kShares)) read(name, archive, name);
  if (!archive.contains(kRanks)) return archive;  // whole
  const std::int64_t ranks = archive.integer(kRanks);
  // Reader `reader` takes the shares s with s * readers / ranks == reader, in rank order; every
  // share holds the same entries, so one with none takes share 0's, empty. The archive knows
  // them as shares (StateReader::in_share).
  const std::string first = share_group(0);
  for (const std::string& name : names) {
    if (!name.starts_with(first)) continue;
    read(name, archive, name.substr(first.size()), false);
    archive.share_also(name.substr(first.size()));
  }
  for (std::int64_t s = 0; s < ranks; ++s) {
    if (who.readers == 0 || s * who.readers / ranks != who.reader) continue;
    const std::string group = share_group(static_cast<int>(s));
    for (const std::string& name : names) {
      if (!name.starts_with(group)) continue;
      StateArchive entry;  // one dataset at a time: a share is never held twice
      read(name, entry, name.substr(group.size()));
      archive.append_share(entry);
    }
  }
  if (who.readers > 1) archive.put(kReaders, std::int64_t{who.readers});
  return archive;
}

std::optional<double> checkpoint_time(const std::filesystem::path& checkpoint) {
  try {
    const H5Context ctx(checkpoint, H5Context::Role::kInput);
    const H5Handle file = open_checkpoint(ctx);
    const H5Handle set = ctx.own(H5Dopen2(file.get(), kTime, H5P_DEFAULT), H5Dclose, "open", kTime);
    const H5Handle space = ctx.own(H5Dget_space(set.get()), H5Sclose, "query", kTime);
    if (H5Sget_simple_extent_npoints(space.get()) != 1) return std::nullopt;
    double time = 0.0;
    ctx.check(H5Dread(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &time), "read",
              kTime);
    return time;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

}  // namespace granjet::analysis
