// Commands that read an HDF5 file a user hands in (info, analyze) run in a child process. HDF5
// does not guard against damaged files: a flipped bit in an object header or a B-tree can crash
// the library itself. In a child, such a crash becomes an error naming the file (exit 2) and
// the parent removes what the child was writing, instead of a segmentation fault.
#pragma once

#include <filesystem>
#include <functional>

namespace granjet {

// Runs `command` in a forked child and returns its exit code; an exception in it is reported
// there (report_current_exception). When the child dies of a signal, removes `scratch` (a file
// only this command writes; empty: none) and throws InputError naming `file` and the signal.
int run_guarded(const std::function<int()>& command, const std::filesystem::path& file,
                const std::filesystem::path& scratch = {});

}  // namespace granjet
