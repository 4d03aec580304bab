#include "run/run_budget.hpp"

#include <unistd.h>

#include <algorithm>
#include <sstream>

#include "analysis/kinetic_theory.hpp"
#include "core/errors.hpp"
#include "core/initial_state.hpp"
#include "core/number_text.hpp"
#include "run/backend_factory.hpp"
#include "run/scene_kinds.hpp"

namespace granjet {
namespace {

// The limits, each far beyond what the study needs (a jet3d run: 5e4 steps, 101 frames, 100
// samples, 2e4 grains in 60 d) and each what a day of one core could at best get through.
constexpr double kMaxSteps = 1e9;
constexpr double kMaxCollisions = 1e12;
constexpr double kMaxFrames = 1e5;
constexpr double kMaxProgressRows = 1e6;
constexpr double kMaxSamples = 1e7;
constexpr double kMaxJetSites = 1e9;  // lattice sites drawn to build the jet
// Farther out, double positions lose the 1e-9 d that contacts of 1e-3 d overlap need.
constexpr double kMaxExtent = 1e7;
constexpr double kBaseBytes = 64e6;  // the program itself

// "KEY: WHAT would be VALUE UNIT; at most LIMIT UNIT".
void refuse_above(double value, double limit, const std::string& key, const std::string& what,
                  const std::string& unit = "") {
  // !(<=) also refuses NaN and infinity.
  if (!(value <= limit))
    throw InputError(key, what + " would be " + number_text(value) + unit + "; at most " +
                              number_text(limit) + unit);
}

void check_extent(const Scene& s) {
  const SceneKindTraits& kind = scene_kind(s.kind);
  const SceneQuantity sites = kind.sites(s);
  if (!sites.key.empty()) refuse_above(sites.value, kMaxJetSites, sites.key, sites.what);
  // Farther out, positions lose the precision contacts need.
  for (const SceneQuantity& length : kind.lengths(s))
    refuse_above(length.value, kMaxExtent, length.key, length.what, " d");
}

void check_memory(const Scene& s, const Backend& backend, double memory_bytes) {
  const double grains = scene_kind(s.kind).grains(s);
  const double bytes = kBaseBytes + backend.bytes_per_grain * grains;
  if (bytes <= memory_bytes) return;
  const std::string key = s.periodic() ? "gas.grains"
                          : target_grains_estimate(s) > static_cast<double>(s.jet.grains)
                              ? "wall.diameter"
                              : "jet.grains";
  throw InputError(key, number_text(grains) + " grains would need about " +
                            number_text(bytes / 1e9) + " GB; this machine has " +
                            number_text(memory_bytes / 1e9) + " GB");
}

// A head-on contact at the scene's hardest speed (scene_kinds) overlaps by at most what the
// backend's contact law says (for [3.1] with [3.4], v t_c / pi).
void check_soft_overlap(const Scene& s, double (*peak_overlap)(const Scene&, double)) {
  const SceneQuantity contact = scene_kind(s.kind).contact_speed(s);
  const double speed = contact.value;
  const std::string& key = contact.key;
  const double smaller_radius =
      0.5 * (s.monodisperse() ? 1.0 : std::min(1.0, s.jet.small_diameter));
  const double overlap = peak_overlap(s, speed);
  if (overlap > s.run.max_overlap * smaller_radius)
    throw InputError(
        key, "at speed " + number_text(speed) + " a contact of contact.contact_time = " +
                 number_text(s.contact.contact_time) + " overlaps by " + number_text(overlap) +
                 " d, beyond run.max_overlap = " + number_text(s.run.max_overlap) +
                 " of the smaller radius " + number_text(smaller_radius) +
                 ": the soft DEM would blow up; slow the grains or shorten t_c");
}

void check_duration(const Scene& s, const Backend& backend) {
  const double t_end = s.run.t_end;
  // A time-stepped backend steps by dt; an event-driven binary run is sampled every dt too.
  if (!backend.counts_events || scene_kind(s.kind).sampled_every_step)
    refuse_above(t_end / s.dt(), kMaxSteps, s.run.dt > 0.0 ? "run.dt" : "run.t_end",
                 "the time steps (run.t_end / run.dt)");
  if (backend.counts_events && s.periodic()) {
    const double per_grain =
        analysis::kinetic::enskog_collision_frequency(s.gas.phi, s.gas.temperature, s.dimension);
    refuse_above(0.5 * static_cast<double>(s.gas.grains) * per_grain * t_end, kMaxCollisions,
                 "gas.temperature",
                 "the collisions of gas.grains over run.t_end at gas.temperature (Enskog)");
  }
  const double frames = s.output.interval > 0.0 ? t_end / s.output.interval + 2.0 : 2.0;
  refuse_above(frames, kMaxFrames, "output.interval", "the frames (run.t_end / output.interval)");
  refuse_above(t_end / s.run.progress_interval, kMaxProgressRows, "run.progress_interval",
               "the progress rows (run.t_end / run.progress_interval)");
  const SceneQuantity samples = scene_kind(s.kind).samples(s);
  if (!samples.key.empty()) refuse_above(samples.value, kMaxSamples, samples.key, samples.what);
  // Every frame stores id, present, radius, position and velocity of every grain, and what
  // output.fields adds: omega, force, and the contacts, at most one per grain pair of a dense
  // packing (3 per grain in 3D, 2 in 2D), each two ids, two force vectors and an overlap.
  const double d = s.dimension;
  double per_grain = 2.0 * d + 3.0;
  if (s.output.omega) per_grain += d == 3 ? 3.0 : 1.0;
  if (s.output.force) per_grain += d;
  if (s.output.contacts) per_grain += (d == 3 ? 3.0 : 2.0) * (3.0 + 2.0 * d);
  const double grains = scene_kind(s.kind).grains(s);
  const double frame_bytes = grains * per_grain * 8.0;
  if (frames * frame_bytes > s.output.max_bytes)
    throw InputError(
        "output.max_bytes",
        number_text(frames) + " frames of " + number_text(grains) + " grains need about " +
            number_text(frames * frame_bytes / 1e9) +
            " GB, more than output.max_bytes = " + number_text(s.output.max_bytes / 1e9) +
            " GB; store fewer frames (output.interval) or raise it");
}

}  // namespace

double physical_memory_bytes() {
  return static_cast<double>(::sysconf(_SC_PHYS_PAGES)) *
         static_cast<double>(::sysconf(_SC_PAGE_SIZE));
}

void check_run_budget(const Scene& scene, const std::string& backend_name, double memory_bytes) {
  const Backend& backend = backend_named(backend_name);
  check_memory(scene, backend,
               memory_bytes);  // first: it names the grain count, the likeliest cause
  check_extent(scene);
  if (backend.peak_overlap) check_soft_overlap(scene, backend.peak_overlap);
  check_duration(scene, backend);
}

}  // namespace granjet
