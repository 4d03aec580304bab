// Stores an analysed ensemble in an HDF5 file (a granjet run file or any other; created when it
// does not exist), in two groups that replace earlier ones of the same name:
//
//   /fields   attributes dimension, seeds, coordinates ("cylindrical" | "cartesian"),
//             height_origin (where height 0 lies on the jet axis, z in 3D, x in 2D)
//     mesh/lateral, mesh/height          bin borders (r or y; height above the wall)
//     mesh/points                         corners of the cells the sidecar draws (FieldCells)
//     layout/<name>                       [layers][lateral] bin centres, indices, volumes
//     <field path>/{mean,std,sem,count}   [layers][lateral]; "stress.rz" -> stress/rz/...
//   /analysis
//     global/<path>/{mean,std,sem,count}  scalars (flatness_bin/r, psi0, v2, ...)
//     vdf/c, vdf/density/<a>/{mean,std,sem}; azimuth/phi, azimuth/dN_dphi/{mean,std,sem} (3D)
//     fits/<law>/{value,error}            attributes parameters, ssr, points, converged
//
// plus an XDMF file that shows the fields' means in ParaView as cells where the grains were
// (fields_xdmf.hpp).
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "analysis/fields_xdmf.hpp"
#include "analysis/run_analysis.hpp"

namespace granjet::analysis {

// Throws std::runtime_error naming the file and object when HDF5 fails.
void write_analysis_hdf5(const std::filesystem::path& file, const EnsembleResult& result);

// Where a field's datasets lie below /fields: dotted names become nested groups,
// "stress.rz" -> "stress/rz".
std::string field_path(std::string name);

// The .fields.xmf sidecar that shows the fields of `file` in ParaView, beside it.
std::filesystem::path fields_sidecar(const std::filesystem::path& file);

// A new file `target` holding every top-level object of `source` except /fields and /analysis:
// where a re-analysis writes them afresh. The old groups are never opened, so a damaged one
// cannot stop the library (deleting a damaged group can crash it), and a file analysed again
// does not keep the space of its earlier analysis. Throws InputError naming `source` when it
// cannot be read, std::runtime_error naming `target` when that cannot be written.
void copy_without_analysis(const std::filesystem::path& source,
                           const std::filesystem::path& target);

// The one way every command stores an analysis: `runs` combined (mean and spread over seeds,
// fits; combine_runs), written as /fields and /analysis into `file` (write_analysis_hdf5), and
// the fields' sidecar (write_fields_xdmf) beside the name the file will have, `published_as` (a
// run's file is written as .partial and renamed last; empty: `file` itself). Returns the
// combined result, for the JSON summaries.
EnsembleResult write_ensemble(const std::filesystem::path& file, std::span<const RunResult> runs,
                              int dimension, const std::filesystem::path& published_as = {});

}  // namespace granjet::analysis
