// The inline analysis asks for momentum transfers inside its window only: before it, the
// event-driven backend would otherwise record every impulse of the run (and a run over ranks
// gather every contact to rank 0) for samples that never use them. And it asks for the
// scattered grains only within the travel since its last sample, which measures the same.
#include "analysis/inline_analysis.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "run/backend_factory.hpp"
#include "run/scene_file.hpp"

namespace granjet {
namespace {

std::size_t transfers_between(Simulator<3>& sim, double from, double to) {
  std::vector<PairImpulse<3>> drained, found;
  sim.advance_to(from);
  sim.collect_transfers(drained);
  sim.advance_to(to);
  sim.collect_transfers(found);
  return found.size();
}

TEST(InlineAnalysis, RecordsTransfersInsideItsWindowOnly) {
  const Scene jet = load_scene(std::string(GRANJET_SCENES_DIR) + "/jet3d.ini",
                               {"jet.grains=800", "run.t_end=6", "analysis.window_start=4",
                                "analysis.window_end=6", "analysis.sample_interval=0.25"});
  // Without the analysis, a recording run sees impulses over the stretch before the window.
  const auto unobserved = make_simulator<3>("event_driven", jet);
  unobserved->record_transfers(true);
  ASSERT_GT(transfers_between(*unobserved, 3.0, 3.2), 0u);

  const auto sim = make_simulator<3>("event_driven", jet);
  analysis::InlineAnalysis<3> fields(jet, *sim);
  const auto drive = [&](double t_end) {
    while (sim->time() < t_end - 1e-9) {
      sim->advance_to(std::min(t_end, fields.next_time(*sim)));
      fields.observe(*sim);
    }
  };
  drive(3.0);  // samples before the window (which admits them from 4 - half an interval)
  EXPECT_EQ(transfers_between(*sim, 3.0, 3.2), 0u);
  drive(4.5);  // into the window
  EXPECT_TRUE(fields.window_sampled());
  EXPECT_GT(transfers_between(*sim, 4.5, 4.7), 0u);
}

// A run whose particles_in hands over only the grains the region holds, as a run over ranks
// gathers them to rank 0 (or, with `gather` false, every grain, as one process does); it keeps
// the regions asked for and how many grains each look got.
class GatheredRun final : public Simulator<3> {
 public:
  GatheredRun(std::unique_ptr<Simulator<3>> sim, bool gather)
      : sim_(std::move(sim)), gather_(gather) {}
  std::string_view backend() const override { return sim_->backend(); }
  void advance_to(double t) override { sim_->advance_to(t); }
  double time() const override { return sim_->time(); }
  const Particles<3>& particles() const override { return sim_->particles(); }
  const Particles<3>& particles_in(const SampleRegion& region) const override {
    regions_.push_back(region);
    const Particles<3>& all = sim_->particles();
    held_ = Particles<3>();
    for (std::size_t i = 0; i < all.size(); ++i)
      if (!gather_ || region.holds_grain<3>(all.position()[i], all.radius()[i], all.kind()[i])) {
        held_.add(all.id()[i], all.kind()[i], all.position()[i], all.velocity()[i], all.radius()[i],
                  all.mass()[i]);
        held_.spin().back() = all.spin()[i];
      }
    held_counts_.push_back(held_.size());
    return held_;
  }
  double travel() const override { return sim_->travel(); }
  void collect_transfers(std::vector<PairImpulse<3>>& out) override {
    sim_->collect_transfers(out);
  }
  SimStats stats() const override { return sim_->stats(); }
  bool has_contact_forces() const override { return sim_->has_contact_forces(); }
  EnergyBalance energy() const override { return sim_->energy(); }
  void checkpoint(StateArchive& out) override { sim_->checkpoint(out); }
  void restore(const StateArchive& in) override { sim_->restore(in); }

  const std::vector<SampleRegion>& regions() const { return regions_; }
  const std::vector<std::size_t>& held_counts() const { return held_counts_; }

 private:
  std::unique_ptr<Simulator<3>> sim_;
  bool gather_;
  mutable Particles<3> held_;
  mutable std::vector<SampleRegion> regions_;
  mutable std::vector<std::size_t> held_counts_;
};

// Runs the jet with the inline analysis to t_end; its result and the run.
std::pair<analysis::RunResult, std::unique_ptr<GatheredRun>> analysed(const Scene& scene,
                                                                      bool gather) {
  auto run = std::make_unique<GatheredRun>(make_simulator<3>("soft_dem", scene), gather);
  analysis::InlineAnalysis<3> fields(scene, *run);
  while (run->time() < scene.run.t_end - 1e-9) {
    run->advance_to(std::min(scene.run.t_end, fields.next_time(*run)));
    fields.observe(*run);
  }
  return {fields.finish(), std::move(run)};
}

// Equal tables, NaN equal to NaN.
void expect_same_table(const analysis::Table& a, const analysis::Table& b) {
  ASSERT_EQ(a.names(), b.names());
  for (const std::string& name : a.names())
    for (std::size_t row = 0; row < a.rows(); ++row) {
      const double x = a.at(row, name), y = b.at(row, name);
      EXPECT_TRUE(x == y || (std::isnan(x) && std::isnan(y))) << name << " row " << row;
    }
}

TEST(InlineAnalysis, AsksForTheScatteredGrainsWithinTheTravelSinceItsLastSample) {
  const Scene jet = load_scene(std::string(GRANJET_SCENES_DIR) + "/jet3d.ini",
                               {"jet.grains=2000", "run.t_end=30", "analysis.window_start=20",
                                "analysis.window_end=30", "analysis.sample_interval=0.5"});
  const auto [all, everything] = analysed(jet, false);
  const auto [shell, gathered] = analysed(jet, true);
  ASSERT_GT(all.global.at(0, "scattered"), 50.0);
  expect_same_table(all.global, shell.global);
  expect_same_table(all.fields, shell.fields);
  expect_same_table(all.vdf, shell.vdf);
  expect_same_table(all.azimuth, shell.azimuth);

  // The first look at the scattered grains asks for all of them, the later ones for a shell as
  // thick as the travel between two samples: at most about the jet speed times the interval.
  // (Inside the window a second look asks for the bins' grains, with no scattered ones.)
  std::vector<SampleRegion> asked;
  std::vector<std::size_t> got, got_everything;
  for (std::size_t k = 0; k < gathered->regions().size(); ++k) {
    if (!std::isfinite(gathered->regions()[k].beyond)) {
      EXPECT_GE(gathered->regions()[k].within, 0.0) << "a look at neither";
      continue;
    }
    asked.push_back(gathered->regions()[k]);
    got.push_back(gathered->held_counts()[k]);
    got_everything.push_back(everything->held_counts()[k]);
  }
  ASSERT_GT(asked.size(), 10u);
  EXPECT_TRUE(std::isinf(asked[0].until));
  for (std::size_t k = 1; k < asked.size(); ++k) {
    EXPECT_GT(asked[k].until, asked[k].beyond);
    EXPECT_LT(asked[k].until, asked[k].beyond + 1.5 * 0.5);
    EXPECT_LT(asked[k].within, 0.0) << "the scattered grains' look takes no bins";
  }
  // And once the sheet has spread past the shell, a look gets far fewer grains than one that
  // takes every scattered grain (the wall grains come with both).
  EXPECT_LT(got.back() + 50, got_everything.back());
}

}  // namespace
}  // namespace granjet
