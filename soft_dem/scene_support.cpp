#include "soft_dem/scene_support.hpp"

#include <iomanip>
#include <sstream>
#include <string>

#include "core/errors.hpp"
#include "soft_dem/dem_simulator.hpp"

namespace granjet::dem {

SceneSupport scene_support(const Scene& scene) {
  SceneSupport support;
  support.resolved = scene;
  if (const std::string why = contact_law_refusal(scene); !why.empty())
    support.unsupported.push_back({"contact.model", why});
  if (scene.contact.rolling_friction > 0.0 && scene.periodic())
    support.unsupported.push_back(
        {"contact.rolling_friction",
         "rolling resistance is built for the jet and binary scenes, not the periodic gases; "
         "set it to 0"});
  if (scene.output.omega && !scene.needs_rotation())
    support.unsupported.push_back(
        {"output.fields",
         "omega: the grains of this run do not turn (contact.friction = 0); drop it"});
  // Coarse steps change the dissipation without any blow-up to report
  // (docs/run_time_vs_error.md).
  if (const double steps = scene.dt() / scene.contact.contact_time; steps > 0.05 + 1e-9) {
    std::ostringstream note;
    note << "run.dt = " << std::setprecision(3) << steps << " t_c: coarser than 0.05 t_c, where "
         << "one collision's e and t_c stay within 1% (docs/run_time_vs_error.md); dissipation "
         << "and cooling rates are biased, and dense jets blow up from 0.15-0.2 t_c";
    support.notes.push_back(note.str());
  }
  return support;
}

void check_over_ranks(const Scene& scene, int ranks) {
  if (ranks > 1 && scene.periodic())
    throw InputError("mpirun -n " + std::to_string(ranks),
                     "a periodic box runs on one rank: the domain decomposition cuts open "
                     "space (run it without mpirun; run.threads = N shares one machine)");
}

}  // namespace granjet::dem
