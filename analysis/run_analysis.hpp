// The study's measurements of one run (model §6), fed sample by sample from the run loop or from
// stored frames, and their combination over an ensemble of seeds with the scene's fits.
//
//   RunAnalysis<D> analysis(AnalysisConfig::for_scene(scene));  // + the [analysis] keys
//   std::vector<PairImpulse<D>> transfers;
//   while (running) {
//     sim.advance_to(std::min(analysis.next_sample_time(), ...other stops...));
//     if (analysis.due(sim.time())) {
//       transfers.clear();  // those since the previous sample, used inside the window only
//       if (analysis.in_window(sim.time())) sim.collect_transfers(transfers);
//       analysis.sample(sim.time(), sim.particles(), transfers);
//     }
//   }
//   runs.push_back(analysis.finish());                 // one RunResult per seed
//   EnsembleResult all = combine_runs(runs, D);         // mean and spread over seeds + fits
//   write_analysis_hdf5(file, all); to_json(all);       // field_writer.hpp, analysis_json.hpp
#pragma once

#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "analysis/bin_grid.hpp"
#include "analysis/field_accumulator.hpp"
#include "analysis/fits.hpp"
#include "analysis/scattering.hpp"
#include "analysis/table.hpp"
#include "core/particles.hpp"
#include "core/sample_region.hpp"
#include "core/scene.hpp"
#include "core/simulator.hpp"

namespace granjet::analysis {

// The scene's [analysis] section.
struct AnalysisConfig {
  double window_start = 50.0;  // time average over window_start <= t <= window_end (model §5)
  double window_end = 100.0;
  double sample_interval = 0.5;
  BinSpec bins;
  FieldOptions options;
  double scatter_radius = 16.5;  // grains beyond this distance from the jet axis are scattered
  Psi0Reading psi0_reading = Psi0Reading::kDeparture;  // what global psi0 and psi0_window are
  double incident_speed = 1.0;                         // u0, for the momentum reading of psi0
  // phi = 0 of the azimuthal distribution (3D): towards the middle of a rectangular jet's short
  // side, e_x (for_scene).
  double reference_azimuth = 0.0;
  // The exit angle of an ideal fluid jet on the same plate (model §7b), for 2D plate targets;
  // NaN otherwise.
  double free_streamline_psi0 = std::numeric_limits<double>::quiet_NaN();
  int azimuth_bins = 36;

  // The mesh and window of the scene's [analysis] section (the study's, model §5-§6, in the
  // shipped scenes: 3D 5 rings of width R_tar/5 in a 5 d layer, window 50..100; 2D layers
  // 0..5 d and 5..10 d cut into 10 bins across -R_tar..R_tar, window 180..300).
  // R_tar = wall.diameter/2; heights from analysis.height_origin (the target grains' centre
  // plane or their top surface); e-bar [2.55] for frictional grains; scattered grains are counted
  // beyond analysis.scatter_radius, or when that is 0 beyond max(1.5 R_tar, the jet's outer
  // radius + 1 d), capped at 0.9 region.radius (inside the region cut, so they are seen before
  // their removal).
  static AnalysisConfig for_scene(const Scene& scene);
};

// One run's measurements.
struct RunResult {
  MeshEdges edges;
  Table layout;   // per bin: FieldAccumulator::layout()
  Table fields;   // per bin: FieldAccumulator::fields()
  Table global;   // one row: flatness_bin.a and flatness_region.a (T5.1: scaled by each bin's
                  // T_a, or by one T_a for the region), psi0, psi0_window (of the grains
                  // scattered within the time window; both by analysis.psi0's reading),
                  // psi0_departure and psi0_momentum (whole run) and their _window forms,
                  // v2 (3D), scattered, samples,
                  // transfer_time, window_start, window_end; psi0_free_streamline (2D plate)
  Table vdf;      // per histogram interval: "c" (its centre), "density.a" (each bin's scaling)
  Table azimuth;  // per interval of [0, 2 pi): "phi" (its centre), "dN_dphi" over its mean (3D)
};

template <int D>
class RunAnalysis {
 public:
  explicit RunAnalysis(const AnalysisConfig& config);

  // Samples are due every sample_interval from t = 0 (scattering is watched for the whole run,
  // the fields only inside the window).
  double next_sample_time() const { return next_; }
  bool due(double time) const { return time >= next_ - 1e-9 * config_.sample_interval; }
  bool in_window(double time) const;
  // `transfers`: everything collect_transfers returned since the previous sample (they may be
  // left empty outside the window, where they are not used).
  void sample(double time, const Particles<D>& particles,
              std::span<const PairImpulse<D>> transfers);
  // A sample without momentum transfers (stored frames): the contact stress stays unmeasured.
  void sample(double time, const Particles<D>& particles);

  // A sample in parts, for a run whose grains are spread over MPI ranks (InlineAnalysis): the
  // scattered grains, gathered (scatter_region: those beyond the scatter radius, and every
  // target grain); then, inside the window, the bins' grains and transfers, which each rank
  // sums apart (Simulator::sample_own into bins(), over bins_region()) for the time that
  // book_window returns; then schedule_after.
  SampleRegion scatter_region() const;
  void observe_scattering(double time, const Particles<D>& particles);
  // Inside the window: the time the sample's transfers cover (0 for the window's first, or
  // without transfers: none are counted); outside it: none.
  std::optional<double> book_window(double time, bool transfers_known);
  SampleRegion bins_region() const { return fields_.reach(); }
  FieldAccumulator<D>& bins() { return fields_; }
  void schedule_after(double time);

  RunResult finish() const;

  const FieldAccumulator<D>& field_accumulator() const { return fields_; }
  const ScatteringMeasurement<D>& scattering() const { return scattering_; }

  // Checkpoints: what the samples so far have summed and when the next is due; the bins' state
  // in the group kFieldsState.
  static constexpr const char* kFieldsState = "fields";
  template <class Visitor>
  void visit_state(Visitor& v) {
    auto fields = v.nested(kFieldsState);
    fields_.visit_state(fields);
    auto scattering = v.nested("scattering");
    scattering_.visit_state(scattering);
    v("next", next_);
    v("open", open_);
    v("last_window_time", last_window_time_);
  }

 private:
  void take(double time, const Particles<D>& particles, std::span<const PairImpulse<D>> transfers,
            bool transfers_known);

  AnalysisConfig config_;
  FieldAccumulator<D> fields_;
  ScatteringMeasurement<D> scattering_;
  double next_ = 0.0;
  bool open_ = false;  // the window has had its first sample
  double last_window_time_ = 0.0;
};

extern template class RunAnalysis<2>;
extern template class RunAnalysis<3>;

// Mean and spread over seeds of every quantity, and the scene's fits to the ensemble-mean bins:
// 3D mu* = a I; 2D [6.2] phi(I_T), [6.3] phi(I_s), [6.9] and [6.10] mu*(I_s).
struct EnsembleResult {
  int dimension = 3;
  int seeds = 0;
  MeshEdges edges;
  Table layout;
  EnsembleTable fields, global, vdf, azimuth;
  std::vector<FitResult> fits;
};

// Throws std::invalid_argument when `runs` is empty or the runs differ in their bins.
EnsembleResult combine_runs(std::span<const RunResult> runs, int dimension);

}  // namespace granjet::analysis
