#include "analysis/layer_temperature.hpp"

#include <cmath>
#include <vector>

#include "core/jet_geometry.hpp"

namespace granjet::analysis {

double layer_a_temperature(const Particles<2>& p, const Scene& scene, int* count) {
  const double origin = height_origin_position(scene.analysis.height_origin);
  const double height = scene.analysis.layer_height;
  const double dy = scene.wall.diameter / 10.0;  // R_tar / 5
  Vec<2> sum = Vec<2>::Zero();
  std::vector<std::size_t> in;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind()[i] != GrainKind::kFree) continue;
    const Vec<2>& x = p.position()[i];
    const double h = x.x() - origin;
    if (h > 0.0 && h <= height && x.y() > -dy && x.y() < 0.0) {
      in.push_back(i);
      sum += p.velocity()[i];
    }
  }
  if (count != nullptr) *count = static_cast<int>(in.size());
  if (in.size() < 2) return std::nan("");
  const Vec<2> mean = sum / static_cast<double>(in.size());
  double t = 0.0;
  for (std::size_t i : in) t += p.mass()[i] * (p.velocity()[i] - mean).squaredNorm();
  return t / (2.0 * static_cast<double>(in.size()));
}

}  // namespace granjet::analysis
