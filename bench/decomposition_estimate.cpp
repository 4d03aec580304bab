// How one frame of a soft-DEM run would split over K MPI ranks by recursive coordinate bisection
// (core/recursive_bisection.hpp): per K the load imbalance, each rank's ghosts (the grains of
// other ranks within the neighbour cut, 2 r_max + skin, of its region) and the bytes one step's
// halo exchange would send (each ghost's position, velocity and spin as doubles). Each grain
// weighs 1 + its listed pairs (its share of the distance tests), as measured work would; and
// how many of each rank's ghosts touch another grain (the rest fly free at that instant). The
// geometry of a decomposition, for docs/performance.md; no rank runs anything.
// The cut's skin is the run's run.skin (from the scene the file keeps), and a jet's column is
// cut lengthwise as a run cuts it (soft_dem/jet_cuts.hpp); the frame, the last.
//   build/bench/granjet_decomposition RUN.h5 [--frame F] [--parts 2,4,8,16,64]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "analysis/h5md_reader.hpp"
#include "core/neighbour_list.hpp"
#include "core/recursive_bisection.hpp"
#include "run/scene_file.hpp"
#include "soft_dem/jet_cuts.hpp"

namespace {

template <int D>
int estimate(const std::string& file, std::size_t frame, const granjet::Scene& scene,
             const std::vector<int>& parts) {
  const double skin = scene.run.skin;
  const granjet::analysis::Frame<D> f = granjet::analysis::read_frame<D>(file, frame);
  const std::size_t n = f.position.size();
  const double r_max = *std::max_element(f.radius.begin(), f.radius.end());
  const double cut = 2.0 * r_max + skin;
  // Listed pairs per grain, from the same half list a run builds.
  granjet::CellGrid<D> grid;
  grid.build(f.position, cut, 1, f.id);
  std::vector<granjet::Vec<D>> x;
  std::vector<double> radius;
  for (std::uint32_t k : grid.order()) {
    x.push_back(f.position[k]);
    radius.push_back(f.radius[k]);
  }
  granjet::PairList pairs;
  granjet::build_half_pairs<D>(
      grid, x, radius, skin, [](auto, auto) { return false; }, pairs);
  std::vector<double> weight(n, 1.0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t k = pairs.first[i]; k < pairs.first[i + 1]; ++k) {
      weight[i] += 1.0;
      weight[pairs.partner[k]] += 1.0;
    }
  // Grains that touch another (the listed pairs that overlap): those a step pushes. A ghost
  // that touches nothing flies free, so its state after a step could be known without its owner.
  std::vector<std::uint8_t> touching(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t k = pairs.first[i]; k < pairs.first[i + 1]; ++k) {
      const std::uint32_t j = pairs.partner[k];
      if ((x[i] - x[j]).norm() < radius[i] + radius[j]) touching[i] = touching[j] = 1;
    }
  constexpr int kGhostDoubles = D == 3 ? 9 : 5;  // x, v, w
  std::printf("%s, frame %zu (t = %g): %zu grains, %zu listed pairs, cut %g\n", file.c_str(), frame,
              f.time, n, pairs.size(), cut);
  std::printf("%6s %10s %12s %12s %12s %10s %16s %16s\n", "ranks", "imbalance", "grains/rank",
              "ghosts mean", "ghosts max", "ghost/own", "halo bytes/step", "touching mean");
  for (int k : parts) {
    const granjet::RecursiveBisection<D> rcb(x, weight, k, granjet::dem::jet_cuts<D>(scene, cut));
    std::vector<std::size_t> owned(k, 0), ghosts(k, 0);
    std::size_t touching_ghosts = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const int own = rcb.part()[i];
      ++owned[own];
      rcb.for_each_part_near(x[i], cut, [&](int part) {
        ghosts[part] += part != own;
        touching_ghosts += part != own && touching[i];
      });
    }
    std::size_t total = 0, most = 0;
    for (std::size_t g : ghosts) total += g, most = std::max(most, g);
    std::printf("%6d %10.3f %12.0f %12.0f %12zu %10.3f %16zu %16.0f\n", k,
                granjet::imbalance(rcb.part(), weight, k), static_cast<double>(n) / k,
                static_cast<double>(total) / k, most, static_cast<double>(total) / n,
                total * kGhostDoubles * sizeof(double), static_cast<double>(touching_ghosts) / k);
  }
  return 0;
}

std::vector<int> parse_parts(const std::string& text) {
  std::vector<int> parts;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    const int k = std::atoi(item.c_str());
    if (k < 1) throw std::invalid_argument("--parts: '" + item + "' is not a count of ranks >= 1");
    parts.push_back(k);
  }
  return parts;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc < 2) {
      std::fprintf(stderr,
                   "usage: granjet_decomposition RUN.h5 [--frame F] [--parts 2,4,8,16,64]\n");
      return 2;
    }
    const std::string file = argv[1];
    std::size_t frame = 0;
    bool last = true;
    std::vector<int> parts = {2, 4, 8, 16, 64};
    for (int a = 2; a + 1 < argc; a += 2) {
      const std::string key = argv[a], value = argv[a + 1];
      if (key == "--frame") {
        frame = std::stoul(value);
        last = false;
      } else if (key == "--parts") {
        parts = parse_parts(value);
      } else {
        throw std::invalid_argument("unknown option '" + key + "' (--frame, --parts)");
      }
    }
    const granjet::analysis::FileSummary summary = granjet::analysis::read_summary(file);
    if (last) frame = summary.frames > 0 ? summary.frames - 1 : 0;
    std::istringstream scene(summary.scene_ini);
    const granjet::Scene run_scene = granjet::parse_scene(scene, file, {});
    return summary.dimension == 2 ? estimate<2>(file, frame, run_scene, parts)
                                  : estimate<3>(file, frame, run_scene, parts);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "granjet_decomposition: %s\n", e.what());
    return 2;
  }
}
