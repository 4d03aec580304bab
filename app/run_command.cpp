#include "app/run_command.hpp"

#include <algorithm>
#include <fstream>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>

#include "analysis/binary_collision.hpp"
#include "analysis/h5md_writer.hpp"
#include "app/backend_factory.hpp"
#include "app/progress_table.hpp"
#include "app/scene_file.hpp"
#include "app/version.hpp"
#include "core/errors.hpp"

namespace granjet {
namespace {

template <int D>
analysis::Observables observables(const Simulator<D>& sim) {
  const EnergyBalance e = sim.energy();
  return {e.kinetic, e.rotational, e.elastic, e.dissipated,
          static_cast<std::int64_t>(sim.particles().size())};
}

// Writes the JSON next to its final name and renames it, so a reader never sees half a file.
void write_json_atomically(const std::filesystem::path& path, const nlohmann::json& j) {
  const std::filesystem::path tmp = path.string() + ".partial";
  {
    std::ofstream f(tmp);
    if (!f) throw std::runtime_error("cannot write the summary " + tmp.string());
    f << j.dump(2) << "\n";
  }
  std::filesystem::rename(tmp, path);
}

template <int D>
nlohmann::json summary_json(const Scene& scene, const std::string& backend,
                            const Simulator<D>& sim, std::int64_t grains_initial,
                            double wall_seconds, const std::string& status) {
  const SimStats s = sim.stats();
  const EnergyBalance e = sim.energy();
  nlohmann::json j;
  j["status"] = status;
  j["scene"] = scene.name;
  j["backend"] = backend;
  j["dimension"] = D;
  j["grains"] = sim.particles().size();
  j["grains_initial"] = grains_initial;
  j["removed"] = s.removed;
  j["time"] = sim.time();
  j["dt"] = scene.dt();
  j["steps"] = s.steps;
  j["contacts"] = s.contacts;
  j["neighbour_rebuilds"] = s.neighbour_rebuilds;
  j["wall_seconds"] = wall_seconds;
  j["particle_steps"] = s.particle_steps;
  j["particle_steps_per_second"] = wall_seconds > 0.0 ? s.particle_steps / wall_seconds : 0.0;
  j["energy"] = {{"kinetic", e.kinetic},   {"rotational", e.rotational},
                 {"elastic", e.elastic},   {"removed", e.removed},
                 {"dissipated", e.dissipated}};
  return j;
}

template <int D>
int run_scene(const Scene& scene, const RunOptions& options, const std::filesystem::path& out_file,
              std::ostream& out) {
  std::unique_ptr<Simulator<D>> sim = make_simulator<D>(options.backend, scene);
  const auto grains_initial = static_cast<std::int64_t>(sim->particles().size());
  analysis::RunMetadata meta;
  meta.creator_version = kVersion;
  meta.backend = options.backend;
  meta.scene_ini = scene_to_ini(scene);
  meta.dimension = D;
  analysis::H5mdWriter<D> writer(out_file, meta, sim->particles().size());
  writer.write_frame(0, sim->time(), sim->particles());
  writer.write_observables(0, sim->time(), observables(*sim));

  const double t_end = scene.run.t_end;
  const double dt = scene.dt();
  const double kInf = std::numeric_limits<double>::infinity();
  const bool binary = scene.kind == SceneKind::kBinary;
  analysis::BinaryCollisionTracker<D> tracker;
  if (binary) tracker.observe(sim->particles(), sim->time());
  double next_output = scene.output.interval > 0.0 ? scene.output.interval : kInf;
  double next_progress = scene.run.progress_interval;
  double last_output = 0.0;
  ProgressTable progress(out, t_end, options.quiet);
  std::string status = "complete";
  try {
    while (sim->time() < t_end - 0.5 * dt) {
      double target = std::min({t_end, next_output, next_progress});
      if (binary) target = std::min(target, sim->time() + dt);  // the tracker samples every step
      sim->advance_to(target);
      const double t = sim->time();
      if (binary) tracker.observe(sim->particles(), t);
      if (t >= next_output - 0.5 * dt || t >= t_end - 0.5 * dt) {
        writer.write_frame(sim->stats().steps, t, sim->particles());
        writer.write_observables(sim->stats().steps, t, observables(*sim));
        last_output = t;
        while (next_output <= t + 0.5 * dt) next_output += scene.output.interval;
      }
      if (t >= next_progress - 0.5 * dt) {
        progress.row(t, static_cast<std::int64_t>(sim->particles().size()), sim->stats());
        while (next_progress <= t + 0.5 * dt) next_progress += scene.run.progress_interval;
      }
    }
    if (last_output < sim->time()) {
      writer.write_frame(sim->stats().steps, sim->time(), sim->particles());
      writer.write_observables(sim->stats().steps, sim->time(), observables(*sim));
    }
  } catch (const BlowUpError& e) {
    const std::filesystem::path kept = writer.abandon(e.what());
    std::cerr << "granjet: " << e.what() << "\n"
              << "granjet: frames written so far are kept in " << kept.string() << "\n";
    status = e.what();
  }
  const double wall = progress.elapsed_seconds();
  nlohmann::json summary = summary_json(scene, options.backend, *sim, grains_initial, wall, status);
  if (binary && tracker.complete()) {
    summary["measured"] = {{"restitution", tracker.restitution()},
                           {"contact_time", tracker.contact_time()}};
    summary["requested"] = {{"restitution", scene.contact.restitution},
                            {"contact_time", scene.contact.contact_time}};
  }
  if (status == "complete") {
    writer.finish();
    summary["output"] = out_file.string();
  }
  if (!options.quiet || status != "complete") {
    out << "loop time " << wall << " s for " << sim->stats().steps << " steps, "
        << summary["particle_steps_per_second"].get<double>() << " particle-steps/s\n";
    if (summary.contains("measured"))
      out << "measured restitution " << tracker.restitution() << ", contact time "
          << tracker.contact_time() << "\n";
  }
  if (!options.summary.empty()) write_json_atomically(options.summary, summary);
  return status == "complete" ? 0 : 3;
}

}  // namespace

int run_command(const RunOptions& options, std::ostream& out) {
  const Scene scene = load_scene(options.scene_file, options.overrides);
  std::filesystem::path out_file = options.out;
  if (out_file.empty()) out_file = options.scene_file.stem().string() + ".h5";
  return scene.dimension == 2 ? run_scene<2>(scene, options, out_file, out)
                              : run_scene<3>(scene, options, out_file, out);
}

}  // namespace granjet
