#include "app/backend_factory.hpp"

#include <iomanip>
#include <sstream>

#include "core/errors.hpp"
#include "event_driven/ed_simulator.hpp"
#include "event_driven/scene_support.hpp"
#include "soft_dem/dem_simulator.hpp"

namespace granjet {

std::vector<std::string> backend_names() { return {"soft_dem", "event_driven"}; }

void check_backend(const std::string& backend, const Scene& scene) {
  // The event-driven backend runs every scene (event_driven/scene_support.hpp says what the
  // hard-core version changes); the soft one, every scene its contact law supports.
  if (backend == "soft_dem") {
    dem::check_scene(scene);
    return;
  }
  if (backend == "event_driven") return;
  std::string allowed;
  for (const std::string& name : backend_names()) allowed += (allowed.empty() ? "" : ", ") + name;
  throw InputError("--backend", "'" + backend + "' is not available; allowed: " + allowed);
}

std::vector<std::string> backend_notes(const std::string& backend, const Scene& scene) {
  if (backend == "event_driven") return {ed::scene_note(scene)};
  // Coarse steps change the dissipation without any blow-up to report (an HCS at dt = 0.2 t_c
  // with AB2 cools 62% too slowly, docs/run_time_vs_error.md).
  if (const double steps = scene.dt() / scene.contact.contact_time; steps > 0.05 + 1e-9) {
    std::ostringstream note;
    note << "run.dt = " << std::setprecision(3) << steps << " t_c: coarser than 0.05 t_c, where "
         << "one collision's e and t_c stay within 1% (docs/run_time_vs_error.md); dissipation "
         << "and cooling rates are biased, and dense jets blow up from 0.15-0.2 t_c";
    return {note.str()};
  }
  return {};
}

template <int D>
std::unique_ptr<Simulator<D>> make_simulator(const std::string& backend, const Scene& scene) {
  check_backend(backend, scene);
  if (backend == "event_driven") return ed::make_ed_simulator<D>(scene);
  return dem::make_dem_simulator<D>(scene);
}

template std::unique_ptr<Simulator<2>> make_simulator<2>(const std::string&, const Scene&);
template std::unique_ptr<Simulator<3>> make_simulator<3>(const std::string&, const Scene&);

}  // namespace granjet
