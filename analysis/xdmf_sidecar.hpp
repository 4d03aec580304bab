// XDMF description of the frames in a granjet H5MD file, so that ParaView (its "XDMF Reader"
// and "Xdmf3 Reader S/T") shows the grains, and the contacts as lines, without knowing H5MD.
#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>

namespace granjet::analysis {

// What the H5MD file stores besides the always-present position, velocity, radius and id
// (h5md_writer.hpp describes the layout).
struct XdmfLayout {
  int dimension = 3;
  std::size_t rows = 0;  // grain rows per frame: row r holds grain id r, or fill values
  bool omega = false;    // /particles/all/omega (3D: [rows][3], 2D: [rows])
  bool force = false;    // /particles/all/force ([rows][dimension])
  // Rows per frame of /connectivity/contacts and /contacts/*; 0: the file holds no contacts.
  std::size_t contact_rows = 0;
};

struct XdmfFrame {
  double time = 0.0;
  std::size_t grains = 0;    // valid entries 0..grains-1 of this frame's /particles/all/present
  std::size_t contacts = 0;  // valid rows 0..contacts-1 of /connectivity/contacts and /contacts/*
};

// The sidecar's name: the .h5 file's name with the extension .xmf.
std::filesystem::path xdmf_path_for(const std::filesystem::path& h5_file);

// Writes `xmf`, reading every array by hyperslab from `h5_name`, a file name relative to the
// directory of `xmf` so the pair can be moved together. Throws std::runtime_error naming `xmf`.
void write_xdmf_sidecar(const std::filesystem::path& xmf, const std::string& h5_name,
                        const XdmfLayout& layout, std::span<const XdmfFrame> frames);

}  // namespace granjet::analysis
