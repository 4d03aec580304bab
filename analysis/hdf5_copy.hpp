// Copies an HDF5 file object by object into a new one, leaving some top-level groups out.
#pragma once

#include <filesystem>
#include <set>
#include <string>

namespace granjet::analysis {

// Creates `target` (replacing it) with every top-level object of `source` but those named in
// `left_out` (names without the leading '/'). Objects reached by several hard links, in one
// group or across groups (H5MD's shared step and time), stay one object with several links;
// soft links stay soft. The left-out groups are never opened. Throws InputError naming
// `source` when it cannot be read, std::runtime_error naming `target` when that cannot be
// written.
void copy_hdf5_except(const std::filesystem::path& source, const std::filesystem::path& target,
                      const std::set<std::string>& left_out);

}  // namespace granjet::analysis
