// The scene as plain data: everything a run needs, in the units of the model (d, m, u0).
// Parsing lives in run/ (scene_file); building the initial grains in core/initial_state.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

namespace granjet {

// kGas and kHcs are periodic boxes of unit grains (elastic equilibrium gas, homogeneous cooling).
enum class SceneKind { kJet, kBinary, kGas, kHcs };
enum class IntegratorKind { kAdamsBashforth2, kVelocityVerlet };
// The target: tethered or fixed wall grains (model §4), or a flat immovable plate in their front
// face (event-driven backend).
enum class WallKind { kTethered, kFixed, kPlate };
// How the 3D target grains tile their disk: the study says only "one layer of DEM particles ...
// a bumpy wall" (model §4), so the lattice is an assumption (hexagonal, the densest, by default).
enum class WallLattice { kHexagonal, kSquare };
enum class Dispersity { kMono, kBi };
// The 3D jet's cross section: the study's cylinder, or the rectangle of its anisotropy runs.
enum class JetShape { kCylinder, kRectangle };
// Where the heights of the measuring layers start (model §6 "Height origin", which the study's
// text leaves open): the plane of the target grains' centres (z = 0 in 3D, x = 0 in 2D; the
// literal reading of "from the wall z = 0") or their top surface, d/2 above it. With a plate
// target (no grains; its face is where their top surface would be, core/plate_face.hpp) these
// are the plane d/2 behind the face and the face itself.
enum class HeightOrigin { kWallCentres, kWallSurface };
// How psi0 is measured (model §6 and [4.3]; the study does not say): the polar angle of the mean
// departure direction of the scattered grains, or the angle whose 1 - cos psi0 is the target's
// impulse over the incident momentum, sum m (v_out + u0 e_in) . e_jet / sum m u0.
enum class Psi0Reading { kDeparture, kMomentum };
// Whether the contact stress of the fields counts the transfers between flowing grains and
// target grains (the study sums "over the particles located at r" and leaves this open).
enum class WallContacts { kInclude, kExclude };
// Restitution laws of the event-driven backend [model §8].
enum class RestitutionLaw { kConstant, kVelocityDependent, kTcModel };
// The soft DEM's contact law: the study's linear spring-dashpot (model §2) or Hertz-Mindlin with
// Tsuji damping (soft_dem/hertz_mindlin.hpp, 3D), both from the same (e, t_c).
enum class ContactModel { kLinear, kHertz };

struct ContactSpec {
  ContactModel model = ContactModel::kLinear;
  double restitution = 0.75;   // e, binary restitution (model §2)
  double contact_time = 0.1;   // t_c in d/u0
  double friction = 0.2;       // mu_p
  double spring_ratio = 0.2;   // k_t / k_n
  double damping_ratio = 0.5;  // eta_t / eta_n
  // Whether the normal force may pull: the linear dashpot of [3.1] turns attractive at the end
  // of a contact (the overlap still positive, closing faster than k_n/eta_n allows). The study
  // does not say whether it clamped it at zero; [3.4] and [3.5] assume it did not.
  bool clamp_normal = false;
  // mu_r of the rolling resistance (soft_dem/rolling_resistance.hpp; not in the study): 0, none.
  double rolling_friction = 0.0;
  // F_a, the constant pull between touching grains (soft_dem/adhesion.hpp; not in the study):
  // 0, none.
  double adhesion = 0.0;
};

struct RunSpec {
  double t_end = 100.0;
  double dt = 0.0;  // 0: the study's dt = 0.02 t_c [model §3]
  IntegratorKind integrator = IntegratorKind::kAdamsBashforth2;
  std::uint64_t seed = 1;
  double skin = 0.3;         // Verlet skin in d
  double max_overlap = 0.5;  // blow-up when overlap exceeds this fraction of the smaller radius
  double progress_interval = 1.0;  // sim time between progress rows
  int threads = 1;  // soft DEM OpenMP threads; the results do not depend on it, bit for bit
  // Over MPI ranks, cut a jet's column lengthwise in the first levels while the pieces stay
  // wide (soft_dem/jet_cuts.hpp); false: every cut across the longest side.
  bool lengthwise_cuts = false;
  // Sim time between checkpoints in the run's .partial (0: none). A checkpoint is part of the
  // run: it rebuilds the soft DEM's neighbour list, and re-predicts the event-driven calendar.
  double checkpoint_interval = 10.0;
};

struct JetSpec {
  double diameter = 10.0;  // D_jet (3D) or strip width 2 R_jet (2D)
  double phi_tilde = 0.9;  // fraction of lattice sites kept [model §5]
  std::int64_t grains = 20000;
  double spacing = 1.0;  // lattice nearest-neighbour distance (fcc 1.0, 2D triangular 1.1)
  Dispersity dispersity = Dispersity::kMono;
  double small_diameter = 0.8;  // bidisperse: the small grains' diameter (large = 1)
  double speed = 1.0;           // u0
  double gap = 1.0;             // surface gap between the jet front and the target grains
  bool mass_by_volume = false;  // false: every grain has mass m (the study's convention)
  // Anisotropy runs (model §5, F4.3; 3D only): a rectangle of area A = `area` (d^2) and aspect
  // ratio l = `aspect_ratio` >= 1, long side sqrt(A l) along x, short side sqrt(A/l) along y,
  // eccentricity (l^2 - 1)/(l^2 + 1). `diameter` is then unused.
  JetShape shape = JetShape::kCylinder;
  double aspect_ratio = 1.0;
  double area = 16.0;

  double long_side() const { return std::sqrt(area * aspect_ratio); }   // along x
  double short_side() const { return std::sqrt(area / aspect_ratio); }  // along y
  // The largest distance of the cross section from the jet axis: the cylinder's radius (2D: the
  // strip's half-width) or the rectangle's half-diagonal.
  double outer_radius() const {
    return shape == JetShape::kRectangle ? 0.5 * std::hypot(long_side(), short_side())
                                         : 0.5 * diameter;
  }
};

struct WallSpec {
  WallKind kind = WallKind::kTethered;
  double diameter = 22.0;                         // D_tar (3D disk) or 2 R_tar (2D segment)
  WallLattice lattice = WallLattice::kHexagonal;  // 3D; the 2D target is a row
  double spacing = 1.0;  // centre distance of lattice neighbours (1: touching)
  // A random layer: each site moved in the target plane by a uniform random vector of length at
  // most `jitter` (drawn from run.seed), never so far that target grains overlap.
  double jitter = 0.0;
  double spring = 10.0;        // k_w in m u0^2/d^2
  double damping_ratio = 5.0;  // eta_w / eta_n
};

struct BinarySpec {
  double speed = 1.0;             // approach speed of grain 1 towards grain 2 (at rest)
  double impact_parameter = 0.0;  // lateral offset in d (0 = head-on)
  double gap = 0.0537;            // initial surface gap
  double spin = 0.0;              // initial spin of grain 1 about z (the collision plane is x-y)
};

// Grains of the jet that leave this region are removed and counted: farther than `radius` from
// the jet axis, or more than `below` behind the target plane.
struct RegionSpec {
  double radius = 44.0;
  double below = 10.0;
};

// Periodic gas scenes [model §5]: gas.grains unit grains (d = m = 1) at packing fraction gas.phi,
// started on a lattice with Maxwellian velocities of temperature gas.temperature.
struct GasSpec {
  double phi = 0.3;
  std::int64_t grains = 10976;   // 4 * 14^3: a full fcc lattice
  double temperature = 1.0;      // T = sum m v^2 / (D N), zero total momentum
  double equilibration = 2.0;    // sim time before the measurements start
  double sample_interval = 0.1;  // sim time between temperature samples (cooling)
};

// The event-driven backend [model §8]. velocity_dependent: e(v_n) = 1 - (1 - e0)(v_n/v0)^(3/4)
// below v0 and e0 = contact.restitution above; tc_model: elastic when either grain collided less
// than tc ago.
struct EdSpec {
  RestitutionLaw restitution_law = RestitutionLaw::kVelocityDependent;
  // A tenth of the jet speed: collisions at flow speeds keep e0, only the slow rattling of dense
  // regions is made nearly elastic, which is what prevents inelastic collapse.
  double v0 = 0.1;
  double tc = 0.1;  // the soft contact time t_c of the study, the natural choice
};

// The measurements of model §6, taken inline during a jet run. Defaults: the 3D study (5 rings
// of width R_tar/5 in one 5 d layer, window 50..100); scenes/jet2d.ini sets the 2D study's.
struct AnalysisSpec {
  bool enabled = true;
  double window_start = 50.0;
  double window_end = 100.0;
  double sample_interval = 0.5;
  int lateral_bins = 5;  // 3D rings across 0..R_tar, 2D bins across -R_tar..R_tar
  int layers = 1;        // stacked layers of layer_height above the wall
  double layer_height = 5.0;
  HeightOrigin height_origin = HeightOrigin::kWallCentres;  // h = 0 of the layers
  double scatter_radius =
      0.0;  // where grains count as scattered; 0: from the target (run_analysis)
  Psi0Reading psi0 = Psi0Reading::kDeparture;                  // what global psi0 reports
  WallContacts stress_wall_contacts = WallContacts::kInclude;  // in the fields' contact stress
};

// The unit attributes of the H5MD output: MDAnalysis reads only molecular unit names, so
// kMdAnalysis labels d, d/u0, u0 and m u0^2/d with its base units at factor 1 (Angstrom, ps,
// ...); kReduced names them as they are.
enum class UnitLabels { kMdAnalysis, kReduced };

struct OutputSpec {
  double interval = 1.0;  // sim time between stored frames; 0 = initial and final only
  // A run whose frames would take more is refused before it starts (run/run_budget).
  double max_bytes = 8e9;
  // Per-grain data beyond position, velocity, radius and id (which analysis reads back).
  bool omega = false;
  bool force = false;     // total force on each grain
  bool contacts = false;  // the touching pairs with their forces and overlaps
  UnitLabels unit_labels = UnitLabels::kMdAnalysis;
};

struct Scene {
  std::string name = "scene";
  SceneKind kind = SceneKind::kJet;
  int dimension = 3;
  ContactSpec contact;
  RunSpec run;
  JetSpec jet;
  WallSpec wall;
  BinarySpec binary;
  RegionSpec region;
  GasSpec gas;
  EdSpec ed;
  AnalysisSpec analysis;
  OutputSpec output;

  double dt() const { return run.dt > 0.0 ? run.dt : 0.02 * contact.contact_time; }
  bool frictional() const { return contact.friction > 0.0; }
  // Without friction no tangential force acts, so neither spins nor contact history matter.
  bool needs_rotation() const { return frictional(); }
  bool needs_history() const { return frictional(); }
  bool has_wall() const { return kind == SceneKind::kJet; }
  // The target, by its kind (jet scenes only).
  bool has_plate() const { return has_wall() && wall.kind == WallKind::kPlate; }
  bool has_tethered_wall() const { return has_wall() && wall.kind == WallKind::kTethered; }
  bool periodic() const { return kind == SceneKind::kGas || kind == SceneKind::kHcs; }
  bool monodisperse() const {
    return kind != SceneKind::kJet || jet.dispersity == Dispersity::kMono;
  }
};

}  // namespace granjet
