#include "run/progress_table.hpp"

#include <cstdio>
#include <ostream>

namespace granjet {

ProgressTable::ProgressTable(std::ostream& out, double t_end, bool quiet, bool event_driven)
    : out_(out), t_end_(t_end), quiet_(quiet), event_driven_(event_driven) {}

void ProgressTable::header() {
  if (quiet_) return;
  char line[200];
  std::snprintf(line, sizeof line, "%10s %7s %11s %8s %11s %11s %11s %13s %9s\n", "time", "done",
                event_driven_ ? "events" : "step", "grains",
                event_driven_ ? "collisions" : "contacts", "E_kin", "E_diss",
                event_driven_ ? "collisions/s" : "psteps/s", "ETA [s]");
  out_ << line << std::flush;
}

double ProgressTable::elapsed_seconds() const {
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

double ProgressTable::cpu_seconds() const {
  return static_cast<double>(std::clock() - cpu_start_) / CLOCKS_PER_SEC;
}

void ProgressTable::row(double time, std::int64_t grains, const SimStats& stats,
                        const EnergyBalance& energy) {
  const Clock::time_point now = Clock::now();
  const double interval = std::chrono::duration<double>(now - last_).count();
  // The work counter of the backend: grain-steps (soft DEM) or collisions (event-driven).
  const std::int64_t work = event_driven_ ? stats.collisions : stats.particle_steps;
  const double rate = interval > 0.0 ? (work - last_work_) / interval : 0.0;
  last_ = now;
  last_work_ = work;
  if (quiet_) return;
  const double done = time / t_end_;
  const double eta = done > 0.0 ? elapsed_seconds() * (1.0 - done) / done : 0.0;
  const std::int64_t count = event_driven_ ? stats.collisions : stats.contacts;
  const std::int64_t step = event_driven_ ? stats.events : stats.steps;
  char line[200];
  std::snprintf(line, sizeof line,
                "%10.3f %6.1f%% %11lld %8lld %11lld %11.5g %11.5g %13.4g %9.1f\n", time,
                100.0 * done, static_cast<long long>(step), static_cast<long long>(grains),
                static_cast<long long>(count), energy.kinetic + energy.rotational,
                energy.dissipated, rate, eta);
  out_ << line << std::flush;
}

}  // namespace granjet
