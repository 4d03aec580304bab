// The contact law alone [3.1]-[3.3]: 2D/3D x frictionless/frictional, on a fixed set of
// random overlapping contacts (a mix of sticking and sliding). Reports contacts/s.
#include <benchmark/benchmark.h>

#include <random>

#include "soft_dem/contact_law.hpp"

namespace {

template <int D, bool kFriction>
void BM_ContactLaw(benchmark::State& state) {
  granjet::ContactSpec spec;
  granjet::dem::LinearSpringDashpot<D, kFriction> law(granjet::dem::contact_coefficients(spec),
                                                       0.002);
  constexpr int kContacts = 4096;
  std::mt19937_64 rng(1);
  std::normal_distribution<double> g;
  std::vector<granjet::dem::ContactGeometry<D>> geometry;
  std::vector<granjet::Vec<D>> v_rel, shear(kContacts, granjet::Vec<D>::Zero());
  for (int k = 0; k < kContacts; ++k) {
    granjet::Vec<D> r;
    for (int d = 0; d < D; ++d) r[d] = g(rng);
    r = r.normalized() * (1.0 - 0.01 * std::abs(g(rng)));
    geometry.push_back(granjet::dem::contact_geometry(r, r.norm(), 0.5, 0.5));
    granjet::Vec<D> v;
    for (int d = 0; d < D; ++d) v[d] = 0.3 * g(rng);
    v_rel.push_back(v);
  }
  for (auto _ : state) {
    granjet::Vec<D> sum = granjet::Vec<D>::Zero();
    for (int k = 0; k < kContacts; ++k) sum += law.force(geometry[k], v_rel[k], shear[k]);
    benchmark::DoNotOptimize(sum);
  }
  state.counters["contacts/s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * kContacts, benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(BM_ContactLaw<2, false>);
BENCHMARK(BM_ContactLaw<2, true>);
BENCHMARK(BM_ContactLaw<3, false>);
BENCHMARK(BM_ContactLaw<3, true>);
