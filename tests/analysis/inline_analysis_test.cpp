// The inline analysis asks for momentum transfers inside its window only: before it, the
// event-driven backend would otherwise record every impulse of the run (and a run over ranks
// gather every contact to rank 0) for samples that never use them.
#include "analysis/inline_analysis.hpp"

#include <gtest/gtest.h>

#include <algorithm>
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

}  // namespace
}  // namespace granjet
