// earliest_contacts (event_driven/contact_scan.hpp) gives, bit for bit, the times the scalar
// pair_quadratic and contact_delay give, and keeps the earliest two as a scan in list order
// with strict comparisons does, ties, echoes and partial last steps included, in 2D and 3D.
#include "event_driven/contact_scan.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/random.hpp"

namespace granjet::ed {
namespace {

template <int D>
Vec<D> random_vec(Random& rng, double scale) {
  Vec<D> x;
  for (int a = 0; a < D; ++a) x[a] = scale * (2.0 * rng.uniform() - 1.0);
  return x;
}

enum class Image { kNearest, kShifted, kSame };

template <int D>
void expect_scalar_scan(Random& rng, Image image_kind) {
  const std::size_t grains = 1 + rng.below(40);
  std::vector<Flight<D>> flight(grains + 1);
  for (Flight<D>& f : flight) {
    f.x = random_vec<D>(rng, 3.0);
    f.t = -rng.uniform();
    // Some partners at rest or in the same state as others: ties in time.
    f.v = rng.below(4) == 0 ? Vec<D>::Zero() : random_vec<D>(rng, 2.0);
    f.radius = 0.4 + 0.2 * static_cast<double>(rng.below(2));
  }
  for (std::size_t k = 1; k < grains; ++k)
    if (rng.below(5) == 0) flight[k] = flight[k - 1];
  const std::uint32_t i = static_cast<std::uint32_t>(grains);
  std::vector<std::uint32_t> list(1 + rng.below(30));
  for (std::uint32_t& k : list) k = static_cast<std::uint32_t>(rng.below(grains));
  const std::int32_t echo = rng.below(2) == 0 ? -1 : static_cast<std::int32_t>(list[0]);
  const double now = rng.uniform();
  const Vec<D> x_i = flight[i].position_at(now);
  const Vec<D> box = Vec<D>::Constant(4.0), inv_box = box.cwiseInverse();
  std::array<Vec<D>, 27> shift;
  for (Vec<D>& s : shift) s = random_vec<D>(rng, 1.0).array().round() * box.array();
  std::vector<std::uint8_t> image(list.size());
  for (std::uint8_t& c : image) c = static_cast<std::uint8_t>(rng.below(27));
  const double tolerance = 0.5;  // large, so that echoes are taken often

  Earliest want;
  for (std::size_t m = 0; m < list.size(); ++m) {
    const Flight<D>& f = flight[list[m]];
    Vec<D> dr = f.position_at(now) - x_i;
    if (image_kind == Image::kNearest)
      for (int a = 0; a < D; ++a) dr[a] -= box[a] * std::nearbyint(dr[a] * inv_box[a]);
    else if (image_kind == Image::kShifted)
      dr = Vec<D>(f.position_at(now) + shift[image[m]] - x_i);
    const double sigma = flight[i].radius + f.radius;
    PairQuadratic q = pair_quadratic(dr, Vec<D>(f.v - flight[i].v), sigma);
    if (static_cast<std::int32_t>(list[m]) == echo && q.c < tolerance * sigma * sigma) q.b = 0.0;
    const double t = now + contact_delay(q.b, q.c, q.a);
    if (t < want.first) {
      want.second = want.first;
      want.second_at = want.first_at;
      want.first = t;
      want.first_at = m;
    } else if (t < want.second) {
      want.second = t;
      want.second_at = m;
    }
  }
  const Scanner<D> self{now, flight[i].v, flight[i].radius, echo, tolerance};
  Earliest got;
  if (image_kind == Image::kNearest)
    got = earliest_contacts(self, flight.data(), list.data(), list.size(),
                            NearestImage<D>{x_i, box, inv_box});
  else if (image_kind == Image::kShifted)
    got = earliest_contacts(self, flight.data(), list.data(), list.size(),
                            ShiftedImage<D>{x_i, shift.data(), image.data()});
  else
    got = earliest_contacts(self, flight.data(), list.data(), list.size(), SameImage<D>{x_i});
  ASSERT_EQ(got.first, want.first);
  ASSERT_EQ(got.second, want.second);
  if (want.first < kNever) {
    ASSERT_EQ(got.first_at, want.first_at);
  }
  if (want.second < kNever) {
    ASSERT_EQ(got.second_at, want.second_at);
  }
}

TEST(ContactScan, GivesTheScalarTimesAndTheirEarliestTwo) {
  Random rng(17);
  for (int round = 0; round < 6000; ++round) {
    SCOPED_TRACE(round);
    expect_scalar_scan<3>(rng, static_cast<Image>(round % 3));
    expect_scalar_scan<2>(rng, static_cast<Image>((round + 1) % 3));
  }
}

}  // namespace
}  // namespace granjet::ed
