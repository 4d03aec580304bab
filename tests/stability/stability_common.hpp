// Shared pieces of the stability stress tests: scenes from the shipped scene
// files with overrides, the state checks every case makes, and the one summary line per
// measurement that docs/stability.md quotes (`[stability] ...` on stdout and as a gtest
// property, so `ctest -L stability --output-on-failure -V` reproduces the report's numbers).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdlib>
#include <iostream>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/particles.hpp"
#include "core/scene.hpp"
#include "run/scene_file.hpp"

namespace granjet::stability {

// A shipped scene (scenes/NAME.ini) with `section.key=value` overrides, through the same loader
// and validation as `granjet run`.
inline Scene shipped_scene(const std::string& name, const std::vector<std::string>& overrides) {
  return load_scene(std::string(GRANJET_SCENES_DIR) + "/" + name + ".ini", overrides);
}

// Every position, velocity and spin of the state is finite.
template <int D>
bool all_finite(const Particles<D>& p) {
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.position()[i].allFinite() || !p.velocity()[i].allFinite()) return false;
    if constexpr (D == 3) {
      if (!p.spin()[i].allFinite()) return false;
    } else {
      if (!std::isfinite(p.spin()[i])) return false;
    }
  }
  return true;
}

// Largest overlap (see max_overlap_fraction) for sparse states: sort along x, sweep.
template <int D>
double max_overlap_fraction_sorted(const Particles<D>& p) {
  std::vector<std::uint32_t> order(p.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return p.position()[a][0] < p.position()[b][0];
  });
  double largest_radius = 0.0;
  for (double r : p.radius()) largest_radius = std::max(largest_radius, r);
  double worst = 0.0;
  for (std::size_t a = 0; a < order.size(); ++a)
    for (std::size_t b = a + 1; b < order.size(); ++b) {
      const std::uint32_t i = order[a], j = order[b];
      if (p.position()[j][0] - p.position()[i][0] > 2.0 * largest_radius) break;
      const double reach = p.radius()[i] + p.radius()[j];
      const double dist = (p.position()[i] - p.position()[j]).norm();
      if (dist < reach)
        worst = std::max(worst, (reach - dist) / std::min(p.radius()[i], p.radius()[j]));
    }
  return worst;
}

// The largest overlap between any two grains, as a fraction of the smaller radius (cell grid
// of one largest diameter, so linear in the grains).
template <int D>
double max_overlap_fraction(const Particles<D>& p) {
  const std::size_t n = p.size();
  if (n < 2) return 0.0;
  double largest_radius = 0.0;
  Vec<D> lo = p.position()[0], hi = p.position()[0];
  for (std::size_t i = 0; i < n; ++i) {
    largest_radius = std::max(largest_radius, p.radius()[i]);
    lo = lo.cwiseMin(p.position()[i]);
    hi = hi.cwiseMax(p.position()[i]);
  }
  const double cell = 2.0 * largest_radius;
  std::array<long, D> cells{};
  long total = 1;
  for (int d = 0; d < D; ++d) {
    cells[d] = std::max(1L, static_cast<long>((hi[d] - lo[d]) / cell) + 1);
    total *= cells[d];
  }
  // Very sparse states (grains scattered far apart) get a coarser grid; the count stays linear.
  if (total > static_cast<long>(16 * n)) return max_overlap_fraction_sorted(p);
  auto cell_of = [&](const Vec<D>& x, std::array<long, D>& c) {
    for (int d = 0; d < D; ++d)
      c[d] = std::min(cells[d] - 1, static_cast<long>((x[d] - lo[d]) / cell));
  };
  auto flat = [&](const std::array<long, D>& c) {
    long k = 0;
    for (int d = D - 1; d >= 0; --d) k = k * cells[d] + c[d];
    return k;
  };
  std::vector<std::vector<std::uint32_t>> grid(static_cast<std::size_t>(total));
  for (std::uint32_t i = 0; i < n; ++i) {
    std::array<long, D> c;
    cell_of(p.position()[i], c);
    grid[flat(c)].push_back(i);
  }
  double worst = 0.0;
  for (std::uint32_t i = 0; i < n; ++i) {
    std::array<long, D> c;
    cell_of(p.position()[i], c);
    const int neighbours = D == 2 ? 9 : 27;
    for (int k = 0; k < neighbours; ++k) {
      std::array<long, D> o = c;
      int rest = k;
      bool inside = true;
      for (int d = 0; d < D; ++d) {
        o[d] += rest % 3 - 1;
        rest /= 3;
        inside = inside && o[d] >= 0 && o[d] < cells[d];
      }
      if (!inside) continue;
      for (std::uint32_t j : grid[flat(o)]) {
        if (j <= i) continue;
        const double reach = p.radius()[i] + p.radius()[j];
        const double dist = (p.position()[i] - p.position()[j]).norm();
        if (dist < reach)
          worst = std::max(worst, (reach - dist) / std::min(p.radius()[i], p.radius()[j]));
      }
    }
  }
  return worst;
}

// One line of the report: printed and recorded as a property of the running test.
inline void report(const std::string& key, const std::string& line) {
  std::cout << "[stability] " << key << ": " << line << std::endl;
  ::testing::Test::RecordProperty(key, line);
}

// Seconds of wall time since construction.
class Stopwatch {
 public:
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// A hang must fail clearly, not stall the label until ctest's timeout: past `seconds` of wall
// time the watchdog prints what hung and ends the test executable (exit code 1).
class Watchdog {
 public:
  Watchdog(double seconds, std::string what)
      : what_(std::move(what)), thread_([this, seconds] {
          std::unique_lock lock(mutex_);
          if (!done_.wait_for(lock, std::chrono::duration<double>(seconds),
                              [this] { return finished_; })) {
            std::cout << "[stability] HANG: " << what_ << " still running after " << seconds
                      << " s of wall time" << std::endl;
            std::_Exit(1);
          }
        }) {}
  ~Watchdog() {
    {
      std::lock_guard lock(mutex_);
      finished_ = true;
    }
    done_.notify_one();
    thread_.join();
  }

 private:
  std::string what_;
  std::mutex mutex_;
  std::condition_variable done_;
  bool finished_ = false;
  std::thread thread_;
};

template <class... T>
std::string cat(const T&... parts) {
  std::ostringstream s;
  s.precision(4);
  (s << ... << parts);
  return s.str();
}

}  // namespace granjet::stability
