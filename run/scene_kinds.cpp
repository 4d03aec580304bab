#include "run/scene_kinds.hpp"

#include <cmath>

#include "analysis/binary_collision_observer.hpp"
#include "analysis/gas_observer.hpp"
#include "analysis/inline_analysis.hpp"
#include "core/errors.hpp"
#include "core/initial_state.hpp"

namespace granjet {
namespace {

template <int D>
using Measurements = std::vector<std::unique_ptr<analysis::RunObserver<D>>>;

SceneQuantity none(const Scene&) { return {0.0, "", ""}; }

// The jet: the column, its target, and the fields and scattering of model §6.
template <int D>
Measurements<D> jet_measurements(const Scene& s, Simulator<D>& sim) {
  Measurements<D> m;
  if (s.analysis.enabled) m.push_back(std::make_unique<analysis::InlineAnalysis<D>>(s, sim));
  return m;
}

SceneKindTraits jet() {
  return {
      SceneKind::kJet,
      "jet",
      false,
      [](const Scene& s) {
        return static_cast<double>(s.jet.grains) +
               (s.wall.kind == WallKind::kPlate ? 0.0 : target_grains_estimate(s));
      },
      [](const Scene& s) -> SceneQuantity {
        return {static_cast<double>(s.jet.grains) / s.jet.phi_tilde, "jet.phi_tilde",
                "the lattice sites drawn for the jet (jet.grains / jet.phi_tilde)"};
      },
      [](const Scene& s) -> std::vector<SceneQuantity> {
        return {{jet_column_length(s), "jet.spacing",
                 "the jet's length (jet.grains / jet.phi_tilde sites of jet.spacing across "
                 "jet.diameter)"},
                {s.jet.gap, "jet.gap", "the gap"},
                {s.wall.diameter, "wall.diameter", "the target's diameter"}};
      },
      [](const Scene& s) -> SceneQuantity {
        return {s.jet.speed, "jet.speed", ""};
      },
      [](const Scene& s) -> SceneQuantity {
        if (!s.analysis.enabled) return none(s);
        return {(std::min(s.run.t_end, s.analysis.window_end) - s.analysis.window_start) /
                    s.analysis.sample_interval,
                "analysis.sample_interval",
                "the analysis samples (window / analysis.sample_interval)"};
      },
      [](const Scene& s) -> std::vector<std::pair<std::string, double>> {
        return {{"analysis.window_start", s.analysis.window_start},
                {"analysis.window_end", s.analysis.window_end}};
      },
      jet_measurements<2>,
      jet_measurements<3>,
  };
}

// A kind watched by one observer.
template <template <int> class Observer, int D>
Measurements<D> measured_by(const Scene& s, Simulator<D>& sim) {
  Measurements<D> m;
  m.push_back(std::make_unique<Observer<D>>(s, sim));
  return m;
}

// Two grains head-on (or oblique): their restitution and contact time.

SceneKindTraits binary() {
  return {
      SceneKind::kBinary,
      "binary",
      true,
      [](const Scene&) { return 2.0; },
      none,
      [](const Scene& s) -> std::vector<SceneQuantity> {
        return {{s.binary.gap, "binary.gap", "the gap"}};
      },
      [](const Scene& s) -> SceneQuantity {
        return {s.binary.speed, "binary.speed", ""};
      },
      none,
      [](const Scene&) { return std::vector<std::pair<std::string, double>>{}; },
      measured_by<analysis::BinaryCollisionObserver, 2>,
      measured_by<analysis::BinaryCollisionObserver, 3>,
  };
}

// A periodic gas, at equilibrium (gas) or cooling (hcs): its compressibility or Haff cooling.

SceneKindTraits gas(SceneKind kind, std::string word) {
  return {
      kind,
      std::move(word),
      false,
      [](const Scene& s) { return static_cast<double>(s.gas.grains); },
      none,
      [](const Scene& s) -> std::vector<SceneQuantity> {
        return {{gas_box_edge(s), "gas.phi", "the box edge (gas.grains at gas.phi)"}};
      },
      // The rms relative speed sqrt(2 D T), with T = sum m v^2 / (D N).
      [](const Scene& s) -> SceneQuantity {
        return {std::sqrt(2.0 * s.dimension * s.gas.temperature), "gas.temperature", ""};
      },
      [](const Scene& s) -> SceneQuantity {
        return {(s.run.t_end - s.gas.equilibration) / s.gas.sample_interval, "gas.sample_interval",
                "the temperature samples (run.t_end / gas.sample_interval)"};
      },
      [](const Scene& s) -> std::vector<std::pair<std::string, double>> {
        return {{"gas.equilibration", s.gas.equilibration}};
      },
      measured_by<analysis::GasObserver, 2>,
      measured_by<analysis::GasObserver, 3>,
  };
}

}  // namespace

const std::vector<SceneKindTraits>& scene_kinds() {
  static const std::vector<SceneKindTraits> kinds{jet(), binary(), gas(SceneKind::kGas, "gas"),
                                                  gas(SceneKind::kHcs, "hcs")};
  return kinds;
}

const SceneKindTraits& scene_kind(SceneKind kind) {
  for (const SceneKindTraits& k : scene_kinds())
    if (k.kind == kind) return k;
  throw std::logic_error("scene kind without an entry in run/scene_kinds.cpp");
}

}  // namespace granjet
