#include "app/progress_table.hpp"

#include <cstdio>
#include <ostream>

namespace granjet {

ProgressTable::ProgressTable(std::ostream& out, double t_end, bool quiet)
    : out_(out), t_end_(t_end), quiet_(quiet) {
  if (quiet_) return;
  char line[160];
  std::snprintf(line, sizeof line, "%10s %7s %8s %9s %13s %9s\n", "time", "done", "grains",
                "contacts", "psteps/s", "ETA [s]");
  out_ << line << std::flush;
}

double ProgressTable::elapsed_seconds() const {
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

void ProgressTable::row(double time, std::int64_t grains, const SimStats& stats) {
  const Clock::time_point now = Clock::now();
  const double interval = std::chrono::duration<double>(now - last_).count();
  const double rate = interval > 0.0 ? (stats.particle_steps - last_particle_steps_) / interval : 0.0;
  last_ = now;
  last_particle_steps_ = stats.particle_steps;
  if (quiet_) return;
  const double done = time / t_end_;
  const double eta = done > 0.0 ? elapsed_seconds() * (1.0 - done) / done : 0.0;
  char line[160];
  std::snprintf(line, sizeof line, "%10.3f %6.1f%% %8lld %9lld %13.4g %9.1f\n", time, 100.0 * done,
                static_cast<long long>(grains), static_cast<long long>(stats.contacts), rate, eta);
  out_ << line << std::flush;
}

}  // namespace granjet
