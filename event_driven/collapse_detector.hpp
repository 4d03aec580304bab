// Inelastic collapse [model §8]: with a constant e < 1 a group of grains can collide infinitely
// often in a finite time, so the event clock stalls while the collision count explodes. A grain
// that collides kCollisions times within kSpan free-flight times (smallest diameter / rms speed)
// is taken as collapsing: no flow of hard grains comes near that rate, and a collapsing group
// reaches it after finitely many events, also when the clock no longer moves at all.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "event_driven/flight.hpp"

namespace granjet::ed {

class CollapseDetector {
 public:
  static constexpr std::int64_t kCollisions = 1000;
  static constexpr double kSpan = 1e-6;

  explicit CollapseDetector(std::size_t grains) : start_(grains, -kNever), count_(grains, 0) {}

  // The free-flight time that scales the span; refreshed as the gas heats or cools.
  void set_flight_time(double flight_time) { span_ = kSpan * flight_time; }

  // Books a collision of `grain` at `now`; true when its streak reaches kCollisions.
  bool collided(std::uint32_t grain, double now) {
    if (now - start_[grain] > span_) {
      start_[grain] = now;
      count_[grain] = 0;
    }
    return ++count_[grain] >= kCollisions;
  }

  // The grains in a streak at `now` of at least a tenth of the limit, most collisions first.
  std::vector<std::uint32_t> streaking(double now) const {
    std::vector<std::uint32_t> out;
    for (std::uint32_t g = 0; g < count_.size(); ++g)
      if (now - start_[g] <= span_ && count_[g] >= kCollisions / 10) out.push_back(g);
    std::stable_sort(out.begin(), out.end(),
                     [this](std::uint32_t a, std::uint32_t b) { return count_[a] > count_[b]; });
    return out;
  }

  // The time origin moved forward by dt.
  void shift(double dt) {
    for (double& s : start_) s -= dt;
  }

 private:
  double span_ = kNever;
  std::vector<double> start_;
  std::vector<std::int64_t> count_;
};

}  // namespace granjet::ed
