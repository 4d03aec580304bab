#include "app/run_warnings.hpp"

#include <sstream>

namespace granjet {
namespace {

std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

std::vector<std::string> run_warnings(const Scene& s, const Backend& backend) {
  std::vector<std::string> warnings;
  if (!backend.counts_events && s.run.t_end < s.dt())
    warnings.push_back("run.t_end = " + number(s.run.t_end) + " is shorter than one time step (" +
                       number(s.dt()) + "): the run stores its start and one step");
  if (s.kind == SceneKind::kJet && s.analysis.enabled && s.run.t_end <= s.analysis.window_start)
    warnings.push_back("run.t_end = " + number(s.run.t_end) + " ends before the analysis window " +
                       number(s.analysis.window_start) + ".." + number(s.analysis.window_end) +
                       " starts: no fields will be measured");
  if (s.kind == SceneKind::kJet && s.wall.kind != WallKind::kPlate &&
      s.wall.diameter < 2.0 * s.wall.spacing)
    warnings.push_back("wall.diameter = " + number(s.wall.diameter) +
                       " at wall.spacing = " + number(s.wall.spacing) +
                       " makes a target of one grain: the jet mostly misses it");
  return warnings;
}

}  // namespace granjet
