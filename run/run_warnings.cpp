#include "run/run_warnings.hpp"

#include "core/number_text.hpp"

namespace granjet {

std::vector<std::string> run_warnings(const Scene& s, const Backend& backend) {
  std::vector<std::string> warnings;
  if (!backend.counts_events && s.run.t_end < s.dt())
    warnings.push_back("run.t_end = " + number_text(s.run.t_end) +
                       " is shorter than one time step (" + number_text(s.dt()) +
                       "): the run stores its start and one step");
  if (s.kind == SceneKind::kJet && s.analysis.enabled && s.run.t_end <= s.analysis.window_start)
    warnings.push_back("run.t_end = " + number_text(s.run.t_end) +
                       " ends before the analysis window " + number_text(s.analysis.window_start) +
                       ".." + number_text(s.analysis.window_end) +
                       " starts: no fields will be measured");
  if (s.kind == SceneKind::kJet && s.wall.kind != WallKind::kPlate &&
      s.wall.diameter < 2.0 * s.wall.spacing)
    warnings.push_back("wall.diameter = " + number_text(s.wall.diameter) +
                       " at wall.spacing = " + number_text(s.wall.spacing) +
                       " makes a target of one grain: the jet mostly misses it");
  return warnings;
}

}  // namespace granjet
