// XDMF description of the fields that write_analysis_hdf5 stores (/fields), so that ParaView's
// "XDMF Reader" and "Xdmf3 Reader S/T" draw each bin as solid cells where its grains were, in
// the run's coordinates: a 3D ring as kRingSectors annular sectors about the jet axis (z), a 2D
// bin as a box one grain diameter thick in z. Each cell carries its bin's ensemble means.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "analysis/run_analysis.hpp"

namespace granjet::analysis {

// Enough that a ring looks round (the sectors' chords stray 0.009 R from the circle), few enough
// for the XDMF Reader, whose function parser fails on the join of 29 or more copies.
inline constexpr std::size_t kRingSectors = 24;

// The drawn cells: sectors x layers x lateral bins (2D: one "sector", the thickness in z), and
// their corners [sectors + 1][layers + 1][lateral + 1] (x, y, z), row-major. 3D corners are
// (r cos a, r sin a, origin + h) with a = 2 pi s / sectors, the last plane closing the ring on
// the first; 2D corners are (origin + h, y, -1/2 or +1/2).
struct FieldCells {
  std::size_t sectors = 1;
  std::size_t layers = 0;
  std::size_t lateral = 0;
  std::vector<double> corners;
};

FieldCells field_cells(const EnsembleResult& result);

// Writes `xmf` describing /fields of `h5_name` (relative to the directory of `xmf`), whose
// /fields/mesh/points holds field_cells(result).corners. Throws std::runtime_error naming `xmf`
// when it cannot be written.
void write_fields_xdmf(const std::filesystem::path& xmf, const std::string& h5_name,
                       const EnsembleResult& result);

}  // namespace granjet::analysis
