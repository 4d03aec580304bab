// The measurements a scene's kind calls for, each an observer of the run: a binary collision's
// restitution and contact time, a periodic gas's compressibility or cooling, a jet's fields and
// scattering (unless analysis.enabled = false).
#pragma once

#include <memory>
#include <vector>

#include "analysis/run_observer.hpp"
#include "core/scene.hpp"

namespace granjet::analysis {

// Built on the simulator at the run's start (some look at it at once).
template <int D>
std::vector<std::unique_ptr<RunObserver<D>>> scene_measurements(const Scene& scene,
                                                                Simulator<D>& sim);

extern template std::vector<std::unique_ptr<RunObserver<2>>> scene_measurements<2>(const Scene&,
                                                                                   Simulator<2>&);
extern template std::vector<std::unique_ptr<RunObserver<3>>> scene_measurements<3>(const Scene&,
                                                                                   Simulator<3>&);

}  // namespace granjet::analysis
