// The progress rows of `granjet run`: sim time, % done, step (event-driven: events), grains,
// contacts (collisions), kinetic (with rotational) and dissipated energy, particle-steps/s
// (collisions/s), ETA.
#pragma once

#include <chrono>
#include <cstdint>
#include <ctime>
#include <iosfwd>

#include "core/simulator.hpp"

namespace granjet {

class ProgressTable {
 public:
  ProgressTable(std::ostream& out, double t_end, bool quiet, bool event_driven);
  // The column titles, once before the first row.
  void header();
  void row(double time, std::int64_t grains, const SimStats& stats, const EnergyBalance& energy);
  double elapsed_seconds() const;
  // The process' CPU time since the table was made, over all its threads.
  double cpu_seconds() const;

 private:
  using Clock = std::chrono::steady_clock;
  std::ostream& out_;
  double t_end_;
  bool quiet_;
  bool event_driven_;
  Clock::time_point start_ = Clock::now();
  std::clock_t cpu_start_ = std::clock();
  Clock::time_point last_ = start_;
  std::int64_t last_work_ = 0;
};

}  // namespace granjet
