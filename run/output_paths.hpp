// The files a command is about to write, checked before it writes any: none may be its input,
// no two may be one file, and none may exist as something other than a regular file (as root,
// --out /dev/null would replace the device node by an HDF5 file).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace granjet {

struct OutputPath {
  std::string option;  // what sets it, for the message: "--out", "--summary"
  std::filesystem::path path;
  std::string role;  // "the run file", "its XDMF sidecar", ...
};

// The files `granjet run` writes for one run: OUT, OUT.partial, OUT's sidecars and log (option
// --out), SUMMARY and SUMMARY.partial (--summary; none when empty). `whose` starts their roles:
// "the run's", "seed 7's".
std::vector<OutputPath> run_outputs(const std::filesystem::path& out,
                                    const std::filesystem::path& summary,
                                    const std::string& whose = "the run's");

// Throws InputError naming the option and the clash.
void check_outputs(const std::filesystem::path& input, const std::vector<OutputPath>& outputs);

}  // namespace granjet
