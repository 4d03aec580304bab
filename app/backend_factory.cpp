#include "app/backend_factory.hpp"

#include "core/errors.hpp"
#include "soft_dem/dem_simulator.hpp"

namespace granjet {

std::vector<std::string> backend_names() { return {"soft_dem"}; }

template <int D>
std::unique_ptr<Simulator<D>> make_simulator(const std::string& backend, const Scene& scene) {
  if (backend == "soft_dem") return dem::make_dem_simulator<D>(scene);
  std::string allowed;
  for (const std::string& name : backend_names()) allowed += (allowed.empty() ? "" : ", ") + name;
  throw InputError("--backend", "'" + backend + "' is not available; allowed: " + allowed);
}

template std::unique_ptr<Simulator<2>> make_simulator<2>(const std::string&, const Scene&);
template std::unique_ptr<Simulator<3>> make_simulator<3>(const std::string&, const Scene&);

}  // namespace granjet
