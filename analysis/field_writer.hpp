// Stores an analysed ensemble in an HDF5 file (a granjet run file or any other; created when it
// does not exist), in two groups that replace earlier ones of the same name:
//
//   /fields   attributes dimension, seeds, coordinates ("cylindrical" | "cartesian")
//     mesh/lateral, mesh/height          bin borders (r or y; height above the wall)
//     layout/<name>                       [layers][lateral] bin centres, indices, volumes
//     <field path>/{mean,std,sem,count}   [layers][lateral]; "stress.rz" -> stress/rz/...
//   /analysis
//     global/<path>/{mean,std,sem,count}  scalars (flatness_bin/r, psi0, v2, ...)
//     vdf/c, vdf/density/<a>/{mean,std,sem}; azimuth/phi, azimuth/dN_dphi/{mean,std,sem} (3D)
//     fits/<law>/{value,error}            attributes parameters, ssr, points, converged
//
// plus an XDMF file that shows the fields' means in ParaView as cell data on the
// (lateral, height) mesh.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "analysis/run_analysis.hpp"

namespace granjet::analysis {

// Throws std::runtime_error naming the file and object when HDF5 fails.
void write_analysis_hdf5(const std::filesystem::path& file, const EnsembleResult& result);

// Writes `xmf` describing /fields of `h5_name` (relative to the directory of `xmf`). Throws
// std::runtime_error naming `xmf` when it cannot be written.
void write_fields_xdmf(const std::filesystem::path& xmf, const std::string& h5_name,
                       const EnsembleResult& result);

// Both of the above, the one way every command stores an analysis: /fields and /analysis into
// `file`, and a sidecar with the extension .fields.xmf beside the name the file will have,
// `published_as` (a run's file is written as .partial and renamed last; empty: `file` itself).
// Returns the sidecar's path.
std::filesystem::path store_ensemble(const std::filesystem::path& file,
                                     const EnsembleResult& result,
                                     const std::filesystem::path& published_as = {});

}  // namespace granjet::analysis
