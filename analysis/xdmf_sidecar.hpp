// XDMF 2 description of the frames in a granjet H5MD file, so that ParaView ("Xdmf Reader")
// can show the grains without knowing H5MD.
#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>

namespace granjet::analysis {

struct XdmfFrame {
  double time = 0.0;
  std::size_t grains = 0;  // valid rows 0..grains-1 of this frame
};

// The sidecar's name: the .h5 file's name with the extension .xmf.
std::filesystem::path xdmf_path_for(const std::filesystem::path& h5_file);

// Writes `xmf`, reading every array by hyperslab from `h5_name`, a file name relative to the
// directory of `xmf` so the pair can be moved together. Throws std::runtime_error naming `xmf`.
void write_xdmf_sidecar(const std::filesystem::path& xmf, const std::string& h5_name, int dimension,
                        std::size_t max_grains, std::span<const XdmfFrame> frames);

}  // namespace granjet::analysis
