#include "run/backend_factory.hpp"

#include "core/errors.hpp"
#include "event_driven/ed_simulator.hpp"
#include "event_driven/scene_support.hpp"
#include "soft_dem/dem_simulator.hpp"
#include "soft_dem/scene_support.hpp"

namespace granjet {
namespace {

const std::vector<Backend>& backends() {
  static const std::vector<Backend> all = {
      {"soft_dem", /*counts_events=*/false, /*rate_2d=*/9.5e7, /*rate_3d=*/6.5e7,
       /*bytes_per_grain=*/2048.0, dem::peak_overlap, dem::scene_support,
       [](const Scene& s) { return dem::make_dem_simulator<2>(s); },
       [](const Scene& s) { return dem::make_dem_simulator<3>(s); }},
      {"event_driven", /*counts_events=*/true, /*rate_2d=*/5.0e5, /*rate_3d=*/5.0e5,
       /*bytes_per_grain=*/2048.0, /*peak_overlap=*/nullptr, ed::scene_support,
       ed::make_ed_simulator<2>, ed::make_ed_simulator<3>}};
  return all;
}

}  // namespace

std::vector<std::string> backend_names() {
  std::vector<std::string> names;
  for (const Backend& b : backends()) names.push_back(b.name);
  return names;
}

const Backend& backend_named(const std::string& name) {
  for (const Backend& b : backends())
    if (b.name == name) return b;
  std::string allowed;
  for (const std::string& known : backend_names()) allowed += (allowed.empty() ? "" : ", ") + known;
  throw InputError("--backend", "'" + name + "' is not available; allowed: " + allowed);
}

SceneSupport check_backend(const std::string& backend, const Scene& scene) {
  SceneSupport support = backend_named(backend).support(scene);
  if (support.unsupported.empty()) return support;
  std::string reasons;
  for (const SceneSupport::Refusal& r : support.unsupported)
    reasons += (reasons.empty() ? "" : "; " + r.key + ": ") + r.reason;
  throw InputError(support.unsupported.front().key, reasons);
}

std::string describe(const std::string& backend, const SceneSupport::Adaptation& adaptation) {
  return backend + ": " + adaptation.key + " = " + adaptation.requested + " becomes " +
         adaptation.resolved + " (" + adaptation.reason + ")";
}

template <int D>
std::unique_ptr<Simulator<D>> make_simulator(const std::string& backend, const Scene& scene) {
  const Scene resolved = check_backend(backend, scene).resolved;
  if constexpr (D == 2)
    return backend_named(backend).make_2d(resolved);
  else
    return backend_named(backend).make_3d(resolved);
}

template std::unique_ptr<Simulator<2>> make_simulator<2>(const std::string&, const Scene&);
template std::unique_ptr<Simulator<3>> make_simulator<3>(const std::string&, const Scene&);

}  // namespace granjet
