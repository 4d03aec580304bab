#include "analysis/scene_measurements.hpp"

#include "analysis/binary_collision_observer.hpp"
#include "analysis/gas_observer.hpp"
#include "analysis/inline_analysis.hpp"

namespace granjet::analysis {

template <int D>
std::vector<std::unique_ptr<RunObserver<D>>> scene_measurements(const Scene& scene,
                                                                Simulator<D>& sim) {
  std::vector<std::unique_ptr<RunObserver<D>>> measurements;
  if (scene.kind == SceneKind::kBinary)
    measurements.push_back(std::make_unique<BinaryCollisionObserver<D>>(scene, sim));
  if (scene.periodic()) measurements.push_back(std::make_unique<GasObserver<D>>(scene, sim));
  if (scene.kind == SceneKind::kJet && scene.analysis.enabled)
    measurements.push_back(std::make_unique<InlineAnalysis<D>>(scene, sim));
  return measurements;
}

template std::vector<std::unique_ptr<RunObserver<2>>> scene_measurements<2>(const Scene&,
                                                                            Simulator<2>&);
template std::vector<std::unique_ptr<RunObserver<3>>> scene_measurements<3>(const Scene&,
                                                                            Simulator<3>&);

}  // namespace granjet::analysis
