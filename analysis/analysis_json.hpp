// The JSON summary of an analysed ensemble: one entry per bin with its centre and every
// field as {mean, std, sem, count} (dotted field names nest: "stress.rz" -> "stress": {"rz"}),
// the global measurements, the distributions and the fits. Values that could not be measured
// (an empty bin, a single seed's spread) are null.
//
//   { "dimension", "seeds", "coordinates": "cylindrical" | "cartesian",
//     "mesh": {"lateral": [...], "height": [...]},
//     "bins": [{"layer", "layer_name" ("a", "b", ...), "lateral_index", "r" | "y",
//               "r_over_R_tar" | "y_over_R_tar", "h", "volume", "n": {...}, "stress": {...},
//               ...}, ...],
//     "global": {"flatness_bin": {"r": {...}, ...}, "flatness_region": {"r": {...}, ...},
//                "psi0": {...}, "v2": {...}, ...},
//     "vdf": {"c": [...], "density": {"r": {"mean": [...], "std": [...], "sem": [...]}, ...}},
//     "azimuth": {"phi": [...], "dN_dphi": {...}},
//     "fits": {"6.9": {"parameters": {"mu_s": {"value", "error"}, ...}, "ssr", "points",
//                      "converged"}, ...} }
#pragma once

#include <nlohmann/json.hpp>

#include "analysis/run_analysis.hpp"

namespace granjet::analysis {

nlohmann::json to_json(const EnsembleResult& result);
nlohmann::json to_json(const FitResult& fit);

}  // namespace granjet::analysis
