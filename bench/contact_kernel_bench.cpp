// The linear contact law alone ([3.1], [3.2], [3.3]): 2D/3D x frictionless/frictional, on a
// fixed set of random overlapping contacts (a mix of sticking and sliding). Reports contacts/s.
// BM_ContactLaw: one contact at a time on Eigen vectors (how the plate and the analysis call
// it); BM_ContactLawColumns: the force pass's vectorised loop over a ContactTable, torques
// included.
#include <benchmark/benchmark.h>

#include <random>

#include "soft_dem/contact_table.hpp"
#include "soft_dem/linear_spring_dashpot.hpp"

namespace {

template <int D>
struct RandomContacts {
  static constexpr int kContacts = 4096;
  std::vector<granjet::dem::ContactGeometry<D>> geometry;
  std::vector<granjet::Vec<D>> v_rel;
  RandomContacts() {
    std::mt19937_64 rng(1);
    std::normal_distribution<double> g;
    for (int k = 0; k < kContacts; ++k) {
      granjet::Vec<D> r;
      for (int d = 0; d < D; ++d) r[d] = g(rng);
      r = r.normalized() * (1.0 - 0.01 * std::abs(g(rng)));
      geometry.push_back(granjet::dem::contact_geometry(r, r.norm(), 0.5, 0.5));
      granjet::Vec<D> v;
      for (int d = 0; d < D; ++d) v[d] = 0.3 * g(rng);
      v_rel.push_back(v);
    }
  }
};

template <int D, bool kFriction>
granjet::dem::LinearSpringDashpot<D, kFriction> study_law() {
  return {granjet::ContactSpec{}, 0.002};
}

void count_contacts(benchmark::State& state, int contacts) {
  state.counters["contacts/s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * contacts, benchmark::Counter::kIsRate);
}

template <int D, bool kFriction>
void BM_ContactLaw(benchmark::State& state) {
  const auto law = study_law<D, kFriction>();
  const RandomContacts<D> in;
  std::vector<granjet::Vec<D>> shear(in.kContacts, granjet::Vec<D>::Zero());
  for (auto _ : state) {
    granjet::Vec<D> sum = granjet::Vec<D>::Zero();
    for (int k = 0; k < in.kContacts; ++k) sum += law.force(in.geometry[k], in.v_rel[k], shear[k]);
    benchmark::DoNotOptimize(sum);
  }
  count_contacts(state, in.kContacts);
}

template <int D, bool kFriction>
void BM_ContactLawColumns(benchmark::State& state) {
  const auto law = study_law<D, kFriction>();
  const RandomContacts<D> in;
  granjet::dem::ContactTable<D, kFriction> table;
  granjet::dem::Columns<D> shear;
  table.resize(in.kContacts);
  shear.resize(in.kContacts);
  for (int k = 0; k < in.kContacts; ++k) {
    table.set(k, in.geometry[k], in.v_rel[k]);
    shear.set(k, granjet::Vec<D>::Zero());
  }
  for (auto _ : state) {
    table.apply(law, shear, 0, in.kContacts);
    benchmark::DoNotOptimize(table.forces().col[0][0]);
    benchmark::ClobberMemory();
  }
  count_contacts(state, in.kContacts);
}

}  // namespace

BENCHMARK(BM_ContactLaw<2, false>);
BENCHMARK(BM_ContactLaw<2, true>);
BENCHMARK(BM_ContactLaw<3, false>);
BENCHMARK(BM_ContactLaw<3, true>);
BENCHMARK(BM_ContactLawColumns<2, false>);
BENCHMARK(BM_ContactLawColumns<2, true>);
BENCHMARK(BM_ContactLawColumns<3, false>);
BENCHMARK(BM_ContactLawColumns<3, true>);
