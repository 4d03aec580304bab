// Every text file granjet writes (summaries, XDMF sidecars, manifests) is written to PATH.partial,
// flushed and checked, then renamed: a reader, a crash or a full disk never leaves half a file
// under its final name.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>

namespace granjet::analysis {

// Throws std::runtime_error naming the file when it cannot be written; nothing is left behind.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write);

}  // namespace granjet::analysis
