#include "run/scene_file.hpp"

#include <algorithm>
#include <boost/program_options.hpp>
#include <charconv>
#include <cmath>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <utility>

#include "core/errors.hpp"
#include "core/initial_state.hpp"
#include "run/scene_kinds.hpp"

namespace granjet {
namespace {

namespace po = boost::program_options;

struct Key {
  std::string name;
  std::string help;  // meaning and allowed values
  std::function<void(Scene&, const std::string&)> set;
  std::function<std::string(const Scene&)> get;
};

std::string format_number(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

double parse_double(const std::string& key, const std::string& text) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v))
    throw InputError(key, "'" + text + "' is not a finite number");
  return v;
}

// Allowed interval of a real key; open ends exclude the bound.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  bool lo_open = false;
  double hi = std::numeric_limits<double>::infinity();
  bool hi_open = false;

  bool contains(double v) const {
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
  std::string describe() const {
    const bool lo_inf = std::isinf(lo), hi_inf = std::isinf(hi);
    if (hi_inf) return std::string(lo_open ? "> " : ">= ") + format_number(lo);
    if (lo_inf) return std::string(hi_open ? "< " : "<= ") + format_number(hi);
    return std::string(lo_open ? "(" : "[") + format_number(lo) + ", " + format_number(hi) +
           (hi_open ? ")" : "]");
  }
};

constexpr double kInf = std::numeric_limits<double>::infinity();
// More threads than any machine we know of has cores: a typo, not a wish.
constexpr std::int64_t kMaxThreads = 256;
// Grain indices are 32-bit; memory (run/run_budget) refuses far fewer on most machines.
constexpr std::int64_t kMaxGrains = 1'000'000'000;
const Range kPositive{0.0, true, kInf, false};
const Range kNonNegative{0.0, false, kInf, false};

template <class Member>
Key real_key(std::string name, std::string meaning, Member member, Range range) {
  const std::string help = meaning + "; allowed " + range.describe();
  return {name, help,
          [name, member, range](Scene& s, const std::string& text) {
            const double v = parse_double(name, text);
            if (!range.contains(v))
              throw InputError(
                  name, format_number(v) + " is outside the allowed range " + range.describe());
            member(s) = v;
          },
          [member](const Scene& s) { return format_number(member(s)); }};
}

// An integer key, range-checked in 64 bits before it is narrowed to its member's type: at least
// `lo`, at most `hi` and what the member holds.
template <class Member>
Key integer_key(std::string name, std::string meaning, Member member, std::int64_t lo,
                std::int64_t hi = std::numeric_limits<std::int64_t>::max()) {
  using Stored = std::remove_cvref_t<decltype(member(std::declval<Scene&>()))>;
  constexpr auto stored_max = std::numeric_limits<Stored>::max();
  if (std::in_range<std::int64_t>(stored_max))
    hi = std::min(hi, static_cast<std::int64_t>(stored_max));
  const std::string allowed =
      "an integer " + (hi == std::numeric_limits<std::int64_t>::max()
                           ? ">= " + std::to_string(lo)
                           : "in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return {name, meaning + "; allowed " + allowed,
          [name, member, lo, hi, allowed](Scene& s, const std::string& text) {
            std::int64_t v = 0;
            const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
            if (ec != std::errc() || end != text.data() + text.size() || v < lo || v > hi)
              throw InputError(name, "'" + text + "' is not " + allowed);
            member(s) = static_cast<Stored>(v);
          },
          [member](const Scene& s) { return std::to_string(member(s)); }};
}

template <class Enum, class Member>
Key choice_key(std::string name, std::string meaning, Member member,
               std::vector<std::pair<std::string, Enum>> choices) {
  std::string allowed;
  for (const auto& [word, value] : choices) allowed += (allowed.empty() ? "" : " | ") + word;
  return {name, meaning + "; allowed " + allowed,
          [name, member, choices, allowed](Scene& s, const std::string& text) {
            for (const auto& [word, value] : choices)
              if (word == text) {
                member(s) = value;
                return;
              }
            throw InputError(name, "'" + text + "' is not one of: " + allowed);
          },
          [member, choices](const Scene& s) {
            for (const auto& [word, value] : choices)
              if (member(s) == value) return word;
            return std::string("?");
          }};
}

// output.fields: a list of the per-grain data to store; position, velocity, radius and id are
// required (the analysis reads them back), omega, force and contacts are optional.
Key output_fields_key() {
  static const std::vector<std::string> required = {"position", "velocity", "radius", "id"};
  const std::string allowed =
      "position, velocity, radius, id (all required) and any of omega, "
      "force, contacts";
  return {
      "output.fields", "per-grain data in each frame; allowed " + allowed,
      [allowed](Scene& s, const std::string& text) {
        std::set<std::string> seen;
        std::string word;
        for (std::istringstream in(text); std::getline(in, word, ',');) {
          word.erase(0, word.find_first_not_of(" \t"));
          word.erase(word.find_last_not_of(" \t") + 1);
          const bool known = word == "omega" || word == "force" || word == "contacts" ||
                             std::find(required.begin(), required.end(), word) != required.end();
          if (!known) throw InputError("output.fields", "'" + word + "' is not one of " + allowed);
          if (!seen.insert(word).second)
            throw InputError("output.fields", "'" + word + "' is listed twice");
        }
        for (const std::string& r : required)
          if (!seen.count(r))
            throw InputError("output.fields", "'" + text + "' lacks " + r + "; allowed " + allowed);
        s.output.omega = seen.count("omega") > 0;
        s.output.force = seen.count("force") > 0;
        s.output.contacts = seen.count("contacts") > 0;
      },
      [](const Scene& s) {
        std::string list = "position, velocity, radius, id";
        if (s.output.omega) list += ", omega";
        if (s.output.force) list += ", force";
        if (s.output.contacts) list += ", contacts";
        return list;
      }};
}

// Accessor of one scene member, usable on a const and a mutable Scene.
#define FIELD(path) [](auto& s) -> decltype(auto) { return (s.path); }

const std::vector<Key>& keys() {
  static const std::vector<Key> table = [] {
    std::vector<Key> k;
    k.push_back({"scene.name", "label stored in outputs",
                 [](Scene& s, const std::string& v) { s.name = v; },
                 [](const Scene& s) { return s.name; }});
    std::vector<std::pair<std::string, SceneKind>> kinds;
    for (const SceneKindTraits& kind : scene_kinds()) kinds.emplace_back(kind.word, kind.kind);
    k.push_back(choice_key<SceneKind>("scene.kind",
                                      "what to build (gas, hcs: periodic boxes, event_driven "
                                      "backend)",
                                      FIELD(kind), kinds));
    k.push_back(choice_key<int>("scene.dimension", "2 (disks) or 3 (spheres)", FIELD(dimension),
                                {{"2", 2}, {"3", 3}}));
    k.push_back(choice_key<ContactModel>(
        "contact.model",
        "soft DEM contact law: linear (the study's spring-dashpot) or hertz (Hertz-Mindlin with "
        "Tsuji damping, 3D), both from contact.restitution and contact.contact_time",
        FIELD(contact.model),
        {{"linear", ContactModel::kLinear}, {"hertz", ContactModel::kHertz}}));
    k.push_back(real_key("contact.restitution", "binary restitution coefficient e",
                         FIELD(contact.restitution), {0.0, true, 1.0, false}));
    k.push_back(real_key("contact.contact_time", "binary contact time t_c in d/u0",
                         FIELD(contact.contact_time), kPositive));
    k.push_back(real_key("contact.friction", "Coulomb friction mu_p (0: frictionless)",
                         FIELD(contact.friction), kNonNegative));
    k.push_back(
        real_key("contact.spring_ratio", "k_t / k_n", FIELD(contact.spring_ratio), kPositive));
    k.push_back(real_key("contact.damping_ratio", "eta_t / eta_n", FIELD(contact.damping_ratio),
                         kNonNegative));
    k.push_back(choice_key<bool>(
        "contact.clamp_normal",
        "true: the normal force never pulls (F_n >= 0), a choice the study leaves open; it "
        "raises e above [3.5]",
        FIELD(contact.clamp_normal), {{"false", false}, {"true", true}}));
    k.push_back(real_key("contact.rolling_friction",
                         "rolling resistance mu_r: a torque mu_r R* |F_n| against the grains' "
                         "rolling on each other (0: none; not in the study)",
                         FIELD(contact.rolling_friction), kNonNegative));
    k.push_back(real_key("contact.adhesion",
                         "adhesion F_a: a constant pull between touching grains, the DMT form "
                         "(0: none; not in the study)",
                         FIELD(contact.adhesion), kNonNegative));
    k.push_back(real_key("run.t_end", "simulated time in d/u0", FIELD(run.t_end), kPositive));
    k.push_back(
        real_key("run.dt", "time step (0: 0.02 t_c, the study's)", FIELD(run.dt), kNonNegative));
    k.push_back(choice_key<IntegratorKind>(
        "run.integrator", "time integrator", FIELD(run.integrator),
        {{"ab2", IntegratorKind::kAdamsBashforth2}, {"verlet", IntegratorKind::kVelocityVerlet}}));
    k.push_back(integer_key("run.seed", "random seed of the site removal", FIELD(run.seed), 0));
    // A skin of several d lists (1 + skin)^D times the contacts: memory and time for nothing.
    k.push_back(
        real_key("run.skin", "neighbour-list skin in d", FIELD(run.skin), {0.0, true, 5.0, false}));
    k.push_back(real_key("run.max_overlap",
                         "blow-up when an overlap exceeds this fraction of the smaller radius",
                         FIELD(run.max_overlap), {0.0, true, 1.0, false}));
    k.push_back(real_key("run.progress_interval", "sim time between progress rows",
                         FIELD(run.progress_interval), kPositive));
    k.push_back(real_key("run.checkpoint_interval",
                         "sim time between checkpoints in the run's .partial, from which "
                         "'granjet resume' goes on bit-identically (0: none)",
                         FIELD(run.checkpoint_interval), kNonNegative));
    k.push_back(integer_key("run.threads",
                            "OpenMP threads of the soft DEM (results are bit-identical for any)",
                            FIELD(run.threads), 1, kMaxThreads));
    k.push_back(choice_key<bool>(
        "run.lengthwise_cuts",
        "over MPI ranks: auto cuts a jet's column lengthwise while its pieces stay 10 reaches "
        "across; off (the default) cuts every part across its longest side",
        FIELD(run.lengthwise_cuts), {{"auto", true}, {"off", false}}));
    k.push_back(real_key("jet.diameter", "D_jet (3D) or strip width 2 R_jet (2D), in d",
                         FIELD(jet.diameter), kPositive));
    k.push_back(real_key("jet.phi_tilde", "fraction of lattice sites kept, phi~0",
                         FIELD(jet.phi_tilde), {0.0, true, 1.0, false}));
    k.push_back(
        integer_key("jet.grains", "number of jet grains", FIELD(jet.grains), 1, kMaxGrains));
    k.push_back(real_key("jet.spacing", "lattice nearest-neighbour distance in d",
                         FIELD(jet.spacing), {1.0, false, kInf, false}));
    k.push_back(choice_key<Dispersity>("jet.dispersity", "grain sizes", FIELD(jet.dispersity),
                                       {{"mono", Dispersity::kMono}, {"bi", Dispersity::kBi}}));
    k.push_back(real_key("jet.small_diameter", "bidisperse: diameter of the small grains",
                         FIELD(jet.small_diameter), {0.0, true, 1.0, false}));
    k.push_back(real_key("jet.speed", "incident speed u0", FIELD(jet.speed), kPositive));
    k.push_back(real_key("jet.gap", "surface gap between jet front and target", FIELD(jet.gap),
                         kNonNegative));
    k.push_back(choice_key<bool>("jet.mass_by_volume",
                                 "false: every grain has mass m (the study's convention)",
                                 FIELD(jet.mass_by_volume), {{"false", false}, {"true", true}}));
    k.push_back(choice_key<JetShape>(
        "jet.shape",
        "3D cross section: cylinder of jet.diameter, or rectangle of jet.area and "
        "jet.aspect_ratio (anisotropy runs; 3D only)",
        FIELD(jet.shape),
        {{"cylinder", JetShape::kCylinder}, {"rectangle", JetShape::kRectangle}}));
    k.push_back(real_key("jet.aspect_ratio",
                         "rectangle: aspect ratio l, long side sqrt(A l) along x, short side "
                         "sqrt(A/l) along y",
                         FIELD(jet.aspect_ratio), {1.0, false, kInf, false}));
    k.push_back(
        real_key("jet.area", "rectangle: cross-section area A in d^2", FIELD(jet.area), kPositive));
    k.push_back(choice_key<WallKind>(
        "wall.kind",
        "the target: tethered grains (springs k_w, dashpots eta_w), fixed grains (immovable), or "
        "plate (a flat immovable wall in the grains' front face, no target grains)",
        FIELD(wall.kind),
        {{"tethered", WallKind::kTethered},
         {"fixed", WallKind::kFixed},
         {"plate", WallKind::kPlate}}));
    k.push_back(real_key("wall.diameter", "D_tar (3D) or 2 R_tar (2D), in d", FIELD(wall.diameter),
                         {1.0, false, kInf, false}));
    k.push_back(choice_key<WallLattice>(
        "wall.lattice", "3D target grains' lattice (the 2D target is a row)", FIELD(wall.lattice),
        {{"hexagonal", WallLattice::kHexagonal}, {"square", WallLattice::kSquare}}));
    k.push_back(real_key("wall.spacing",
                         "centre distance of neighbouring target grains in d; below 1 they "
                         "overlap into a smoother layer (soft DEM)",
                         FIELD(wall.spacing), {0.5, false, kInf, false}));
    k.push_back(real_key("wall.jitter",
                         "random layer: largest in-plane shift of a target grain from its site, "
                         "in d, at most (wall.spacing - 1)/2 (0 below spacing 1)",
                         FIELD(wall.jitter), kNonNegative));
    k.push_back(real_key("wall.spring", "tether spring k_w in m u0^2/d^2", FIELD(wall.spring),
                         kNonNegative));
    k.push_back(real_key("wall.damping_ratio", "tether dashpot eta_w / eta_n",
                         FIELD(wall.damping_ratio), kNonNegative));
    k.push_back(real_key("binary.speed", "speed of grain 1 towards grain 2", FIELD(binary.speed),
                         kPositive));
    k.push_back(real_key("binary.impact_parameter", "lateral offset in d (0: head-on)",
                         FIELD(binary.impact_parameter), {0.0, false, 1.0, true}));
    k.push_back(
        real_key("binary.gap", "initial surface gap in d", FIELD(binary.gap), kNonNegative));
    k.push_back(real_key("binary.spin", "initial spin of grain 1 about z", FIELD(binary.spin),
                         {-kInf, true, kInf, true}));
    k.push_back(real_key("region.radius", "remove grains farther from the jet axis",
                         FIELD(region.radius), kPositive));
    k.push_back(real_key("region.below", "remove grains farther behind the target plane",
                         FIELD(region.below), kPositive));
    k.push_back(real_key("gas.phi", "packing fraction of the periodic gas", FIELD(gas.phi),
                         {0.0, true, 1.0, true}));
    k.push_back(integer_key("gas.grains", "number of gas grains (d = m = 1)", FIELD(gas.grains), 2,
                            kMaxGrains));
    k.push_back(real_key("gas.temperature", "initial granular temperature T = sum m v^2 / (D N)",
                         FIELD(gas.temperature), kPositive));
    k.push_back(real_key("gas.equilibration", "sim time before the measurements start",
                         FIELD(gas.equilibration), kNonNegative));
    k.push_back(real_key("gas.sample_interval", "sim time between temperature samples",
                         FIELD(gas.sample_interval), kPositive));
    k.push_back(choice_key<RestitutionLaw>(
        "ed.restitution_law", "event_driven restitution law (docs/model.md §8)",
        FIELD(ed.restitution_law),
        {{"constant", RestitutionLaw::kConstant},
         {"velocity_dependent", RestitutionLaw::kVelocityDependent},
         {"tc_model", RestitutionLaw::kTcModel}}));
    k.push_back(real_key("ed.v0",
                         "velocity_dependent: e = 1 - (1 - e0)(v_n/v0)^(3/4) below v0, in u0",
                         FIELD(ed.v0), kPositive));
    k.push_back(real_key("ed.tc", "tc_model: elastic if either grain collided less than tc ago",
                         FIELD(ed.tc), kNonNegative));
    k.push_back(real_key("output.interval", "sim time between stored frames (0: first and last)",
                         FIELD(output.interval), kNonNegative));
    k.push_back(real_key("output.max_bytes",
                         "refuse a run whose frames would need more bytes than this (raise it "
                         "for long, dense outputs)",
                         FIELD(output.max_bytes), kPositive));
    k.push_back(output_fields_key());
    k.push_back(choice_key<UnitLabels>(
        "output.unit_labels",
        "unit attributes of the H5MD datasets, whose numbers are in d, d/u0, u0 and m: "
        "mdanalysis names them Angstrom, ps, Angstrom ps-1, kJ mol-1 Angstrom-1 at factor 1 "
        "(MDAnalysis loads the file without flags), reduced names them d, d u0-1, u0, m u0+2 d-1",
        FIELD(output.unit_labels),
        {{"mdanalysis", UnitLabels::kMdAnalysis}, {"reduced", UnitLabels::kReduced}}));
    k.push_back(choice_key<bool>("analysis.enabled",
                                 "measure the fields of docs/model.md §6 during jet runs",
                                 FIELD(analysis.enabled), {{"true", true}, {"false", false}}));
    k.push_back(real_key("analysis.window_start", "start of the time average",
                         FIELD(analysis.window_start), kNonNegative));
    k.push_back(real_key("analysis.window_end", "end of the time average",
                         FIELD(analysis.window_end), kPositive));
    k.push_back(real_key("analysis.sample_interval", "sim time between samples",
                         FIELD(analysis.sample_interval), kPositive));
    k.push_back(integer_key("analysis.lateral_bins", "bins across the target (3D rings, 2D bins)",
                            FIELD(analysis.lateral_bins), 1));
    k.push_back(
        integer_key("analysis.layers", "layers stacked above the wall", FIELD(analysis.layers), 1));
    k.push_back(real_key("analysis.layer_height", "height of a layer in d",
                         FIELD(analysis.layer_height), kPositive));
    k.push_back(choice_key<HeightOrigin>(
        "analysis.height_origin",
        "where layer heights start: the target grains' centre plane (z = 0 in 3D, x = 0 in 2D) "
        "or their top surface d/2 above it (with a plate: its face)",
        FIELD(analysis.height_origin),
        {{"wall_centres", HeightOrigin::kWallCentres},
         {"wall_surface", HeightOrigin::kWallSurface}}));
    k.push_back(real_key("analysis.scatter_radius",
                         "grains farther than this from the jet axis count as scattered (psi0, "
                         "v2); 0: max(1.5 R_tar, jet outer radius + 1), within 0.9 region.radius",
                         FIELD(analysis.scatter_radius), kNonNegative));
    k.push_back(choice_key<Psi0Reading>(
        "analysis.psi0",
        "what psi0 reports: departure, the polar angle of the scattered grains' mean direction; "
        "momentum, 1 - cos psi0 = the target's impulse over the incident momentum [4.3] (both "
        "are stored as psi0_departure and psi0_momentum)",
        FIELD(analysis.psi0),
        {{"departure", Psi0Reading::kDeparture}, {"momentum", Psi0Reading::kMomentum}}));
    k.push_back(choice_key<WallContacts>(
        "analysis.stress_wall_contacts",
        "whether the fields' contact stress (and P, mu*, I, eta, sigma_Y) counts the transfers "
        "with target grains or the plate (stress_contact_wall is stored either way)",
        FIELD(analysis.stress_wall_contacts),
        {{"include", WallContacts::kInclude}, {"exclude", WallContacts::kExclude}}));
    return k;
  }();
  return table;
}

#undef FIELD

// Levenshtein distance: the edits (insert, delete, replace) from a to b.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// "; did you mean run.t_end?" for the nearest key within a few edits, else nothing.
std::string suggestion(const std::string& name) {
  const Key* best = nullptr;
  std::size_t best_distance = 3;  // more edits than this are another word
  for (const Key& k : keys())
    if (const std::size_t d = edit_distance(name, k.name); d <= best_distance) {
      best = &k;
      best_distance = d;
    }
  return best ? "; did you mean " + best->name + "?" : "";
}

const Key& find_key(const std::string& name) {
  for (const Key& k : keys())
    if (k.name == name) return k;
  throw InputError(name,
                   "unknown key" + suggestion(name) + " (see 'granjet --help' for the scene keys)");
}

void apply_override(Scene& scene, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos)
    throw InputError("--set " + assignment, "expected section.key=value");
  find_key(assignment.substr(0, eq)).set(scene, assignment.substr(eq + 1));
}

// The starting lattice must not overlap, and the box must hold three cells of one diameter
// (the event-driven cell list's stencil).
template <int D>
void validate_gas_lattice(const Scene& s) {
  const GasLattice<D> lattice = gas_lattice<D>(s.gas);
  if (lattice.box.minCoeff() < 3.0)
    throw InputError("gas.grains", std::to_string(s.gas.grains) +
                                       " grains at gas.phi = " + format_number(s.gas.phi) +
                                       " make a box narrower than 3 diameters; add grains");
  // The packing fraction scales as the lattice spacing to the power -D.
  if (lattice.nearest < 1.0)
    throw InputError("gas.phi", format_number(s.gas.phi) + " is too dense for the starting " +
                                    (D == 3 ? "fcc" : "triangular") + " lattice of " +
                                    std::to_string(s.gas.grains) + " grains; at most about " +
                                    format_number(s.gas.phi * std::pow(lattice.nearest, D)));
}

void validate_gas(const Scene& s) {
  if (s.dimension == 2)
    validate_gas_lattice<2>(s);
  else
    validate_gas_lattice<3>(s);
  if (s.gas.equilibration >= s.run.t_end)
    throw InputError("gas.equilibration", format_number(s.gas.equilibration) +
                                              " leaves nothing to measure: must be smaller than "
                                              "run.t_end = " +
                                              format_number(s.run.t_end));
}

// The jitter must not make target grains overlap (or, below spacing 1, overlap more than their
// lattice does), and the tethers join lattice neighbours only: grains within spacing + 2 jitter
// of each other, while next-nearest sites, shifted towards each other, stay beyond that.
void validate_wall(const Scene& s) {
  const WallSpec& w = s.wall;
  const double room = std::max(0.0, 0.5 * (w.spacing - 1.0));
  if (w.jitter > room + 1e-12)
    throw InputError("wall.jitter", format_number(w.jitter) +
                                        " would let target grains overlap: "
                                        "at most (wall.spacing - 1)/2 = " +
                                        format_number(room) + " (0 below spacing 1)");
  const bool square = w.lattice == WallLattice::kSquare;
  if (square && s.dimension == 2)
    throw InputError("wall.lattice",
                     "square is a 3D lattice; the 2D target is a row: use hexagonal");
  const double next_nearest = s.dimension == 2 ? 2.0 : square ? std::sqrt(2.0) : std::sqrt(3.0);
  if (w.spacing + 4.0 * w.jitter >= next_nearest * w.spacing)
    throw InputError("wall.jitter", format_number(w.jitter) + " is too large for wall.spacing = " +
                                        format_number(w.spacing) +
                                        ": shifted sites could reach their next-nearest "
                                        "neighbours' tether range");
}

}  // namespace

namespace {

// The 1-based lines of INI `text` that assign `key` (section.key), for messages.
std::vector<int> assignment_lines(const std::string& text, const std::string& key) {
  const auto trim = [](std::string v) {
    const auto first = v.find_first_not_of(" \t\r"), last = v.find_last_not_of(" \t\r");
    return first == std::string::npos ? std::string() : v.substr(first, last - first + 1);
  };
  std::vector<int> lines;
  std::istringstream in(text);
  std::string section, line;
  for (int number = 1; std::getline(in, line); ++number) {
    line = trim(line);
    if (line.starts_with('[') && line.ends_with(']')) {
      section = trim(line.substr(1, line.size() - 2));
    } else if (const auto eq = line.find('='); !line.starts_with('#') && eq != std::string::npos) {
      const std::string name = trim(line.substr(0, eq));
      if ((section.empty() ? name : section + "." + name) == key) lines.push_back(number);
    }
  }
  return lines;
}

// `require_kind`: a scene file must say what it builds; an empty or all-comment file (or a
// stray INI) would otherwise silently run the default jet.
Scene parse_scene_text(const std::string& text, const std::string& source,
                       const std::vector<std::string>& overrides, bool require_kind) {
  po::options_description desc;
  for (const Key& k : keys()) desc.add_options()(k.name.c_str(), po::value<std::string>());
  po::parsed_options parsed(&desc);
  try {
    std::istringstream in(text);
    parsed = po::parse_config_file(in, desc, /*allow_unregistered=*/true);
  } catch (const po::error& e) {
    throw InputError(source, e.what());
  }
  Scene scene;
  std::set<std::string> given;
  for (const po::option& o : parsed.options) {
    if (o.unregistered)
      throw InputError(o.string_key, "unknown key in " + source + suggestion(o.string_key) +
                                         " (see 'granjet --help' for the scene keys)");
    if (!given.insert(o.string_key).second) {
      std::string where;
      for (const int line : assignment_lines(text, o.string_key))
        where += (where.empty() ? "lines " : " and ") + std::to_string(line);
      throw InputError(o.string_key,
                       "given twice in " + source + " (" + where + "); keep the one you mean");
    }
    find_key(o.string_key).set(scene, o.value.front());
  }
  if (require_kind && !given.contains("scene.kind"))
    throw InputError(source,
                     "names no scene.kind: a scene file says what it builds "
                     "([scene] kind = jet | binary | gas | hcs)");
  for (const std::string& assignment : overrides) apply_override(scene, assignment);
  validate_scene(scene);
  return scene;
}

}  // namespace

Scene parse_scene(std::istream& in, const std::string& source,
                  const std::vector<std::string>& overrides) {
  const std::string text{std::istreambuf_iterator<char>(in), {}};
  return parse_scene_text(text, source, overrides, /*require_kind=*/false);
}

Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw InputError(file.string(), "no such scene file");
  if (!std::filesystem::is_regular_file(file, ec))
    throw InputError(file.string(), "is not a regular file; a scene is an INI file");
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "cannot open the scene file");
  const std::string text{std::istreambuf_iterator<char>(in), {}};
  if (in.bad()) throw InputError(file.string(), "cannot read the scene file");
  return parse_scene_text(text, file.string(), overrides, /*require_kind=*/true);
}

void validate_scene(const Scene& s) {
  if (s.analysis.window_end <= s.analysis.window_start)
    throw InputError("analysis.window_end", format_number(s.analysis.window_end) +
                                                " must be after analysis.window_start = " +
                                                format_number(s.analysis.window_start));
  if (s.dt() >= s.contact.contact_time)
    throw InputError("run.dt", format_number(s.dt()) +
                                   " must be smaller than contact.contact_time = " +
                                   format_number(s.contact.contact_time));
  if (s.contact.rolling_friction > 0.0 && s.contact.friction == 0.0)
    throw InputError("contact.rolling_friction",
                     format_number(s.contact.rolling_friction) +
                         " needs contact.friction > 0: without sliding friction the grains never "
                         "turn, so there is no rolling to resist");
  if (s.contact.adhesion > 0.0 && s.contact.clamp_normal)
    throw InputError("contact.adhesion", format_number(s.contact.adhesion) +
                                             " pulls, which contact.clamp_normal = true forbids; "
                                             "set one of them");
  if (s.periodic()) validate_gas(s);
  if (s.kind == SceneKind::kJet) validate_wall(s);
  if (s.kind == SceneKind::kJet && s.region.radius <= s.jet.outer_radius())
    throw InputError("region.radius",
                     format_number(s.region.radius) + " cuts the jet (outer radius " +
                         format_number(s.jet.outer_radius()) +
                         "): its grains would be removed before they reach the target; it must "
                         "be larger");
  if (s.analysis.scatter_radius >= s.region.radius)
    throw InputError("analysis.scatter_radius",
                     format_number(s.analysis.scatter_radius) +
                         " must be smaller than region.radius = " + format_number(s.region.radius) +
                         " (grains are removed there before they could be seen scattered)");
  if (s.kind == SceneKind::kJet && s.dimension == 2 && s.jet.shape == JetShape::kRectangle)
    throw InputError("jet.shape",
                     "rectangle is a 3D cross section (scene.dimension = 3); the 2D "
                     "jet is a strip of width jet.diameter: use cylinder");
}

std::string scene_to_ini(const Scene& scene) {
  std::map<std::string, std::vector<std::string>> sections;
  std::vector<std::string> order;
  for (const Key& k : keys()) {
    const auto dot = k.name.find('.');
    const std::string section = k.name.substr(0, dot);
    if (!sections.count(section)) order.push_back(section);
    std::string value = k.get(scene);
    if (k.name == "run.dt") value = format_number(scene.dt());
    sections[section].push_back(k.name.substr(dot + 1) + " = " + value);
  }
  std::ostringstream out;
  for (const std::string& section : order) {
    out << "[" << section << "]\n";
    for (const std::string& line : sections[section]) out << line << "\n";
    out << "\n";
  }
  return out.str();
}

std::string scene_keys_help() {
  std::ostringstream out;
  for (const Key& k : keys()) {
    out << "  " << k.name;
    out << std::string(k.name.size() < 26 ? 26 - k.name.size() : 1, ' ') << k.help << "\n";
  }
  return out.str();
}

}  // namespace granjet
