// `import granjet`: scenes, simulators and kinetic theory from Python, on the library the
// command uses (run/, analysis/), with NumPy arrays. Build: the CMake tree (pybind11 from
// Debian's pybind11-dev); the module lands in build/python (docs/python.md).
#include <Python.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <iostream>
#include <map>
#include <memory>
#include <span>
#include <sstream>
#include <string>
#include <tuple>
#include <type_traits>
#include <variant>
#include <vector>

#include "analysis/field_reader.hpp"
#include "analysis/fits.hpp"
#include "analysis/h5md_reader.hpp"
#include "analysis/kinetic_theory.hpp"
#include "core/dim.hpp"
#include "core/errors.hpp"
#include "core/scene.hpp"
#include "run/backend_factory.hpp"
#include "run/frame_replay.hpp"
#include "run/output_paths.hpp"
#include "run/run_budget.hpp"
#include "run/run_command.hpp"
#include "run/scene_file.hpp"
#include "run/version.hpp"
#include "soft_dem/contact_coefficients.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace granjet::python {
namespace {

// A Python value as a scene file writes it: true/false, numbers at full precision (repr), lists
// comma-separated (output.fields).
std::string scene_text(const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    std::string joined;
    for (const py::handle& item : value) joined += (joined.empty() ? "" : ", ") + scene_text(item);
    return joined;
  }
  return py::repr(value).cast<std::string>();
}

Scene parse(const std::string& ini, const std::string& source,
            const std::vector<std::string>& overrides) {
  std::istringstream in(ini);
  return parse_scene(in, source, overrides);
}

// {"scene.kind": "jet", "jet.grains": 1000} or {"scene": {"kind": "jet"}, "jet": {...}}: the
// same keys, checks and messages as a scene file.
Scene scene_from_dict(const py::dict& entries) {
  std::map<std::string, std::vector<std::string>> sections;
  const auto add = [&](const std::string& key, const py::handle& value) {
    const auto dot = key.find('.');
    if (dot == std::string::npos)
      throw InputError(key, "expected section.key (such as run.t_end), or a section's dict");
    sections[key.substr(0, dot)].push_back(key.substr(dot + 1) + " = " + scene_text(value));
  };
  for (const auto& [key, value] : entries) {
    const std::string name = key.cast<std::string>();
    if (py::isinstance<py::dict>(value)) {
      for (const auto& [inner, v] : value.cast<py::dict>())
        add(name + "." + inner.cast<std::string>(), v);
    } else {
      add(name, value);
    }
  }
  std::string ini;
  for (const auto& [section, lines] : sections) {
    ini += "[" + section + "]\n";
    for (const std::string& line : lines) ini += line + "\n";
  }
  return parse(ini, "dict", {});
}

// Read-only NumPy view of `count` rows of `width` doubles (or ids) at `data`, owned by `owner`:
// no copy; valid until the owner's next advance.
template <class T>
py::array view(const T* data, std::size_t count, std::size_t width, const py::object& owner) {
  std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(count)};
  std::vector<py::ssize_t> strides{static_cast<py::ssize_t>(width * sizeof(T))};
  if (width > 1) {
    shape.push_back(static_cast<py::ssize_t>(width));
    strides.push_back(sizeof(T));
  }
  py::array a(py::dtype::of<T>(), shape, strides, data, owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// The dimension of a simulator held in the variant below.
template <class T>
struct DimensionOf;
template <int D>
struct DimensionOf<std::unique_ptr<Simulator<D>>> {
  static constexpr int value = D;
};

class PySimulator {
 public:
  PySimulator(const Scene& requested, const std::string& backend, int threads)
      : requested_(requested), backend_(backend) {
    if (threads > 0) requested_.run.threads = threads;
    check_run_budget(requested_, backend, physical_memory_bytes());
    support_ = check_backend(backend, requested_);
    if (scene().dimension == 2)
      sim_ = make_simulator<2>(backend, scene());
    else
      sim_ = make_simulator<3>(backend, scene());
  }

  // `granjet run` of this simulator into `out` (run/run_command.hpp): the same file, sidecars,
  // log and summary as the command's for the same scene. From t = 0 only, as the command runs.
  py::object run(const std::string& out, const std::string& summary, bool log, bool quiet) {
    if (time() != 0.0)
      throw py::value_error(
          "run() writes a run from t = 0, as granjet run does; this simulator "
          "is at t = " +
          std::to_string(time()) + ": make a new one");
    RunOptions options;
    options.scene_file = "(Python granjet.Simulator)";
    options.backend = backend_;
    options.out = out;
    options.summary = summary;
    options.log = log;
    options.quiet = quiet;
    check_outputs({}, run_outputs(options.out, options.summary));
    std::ostream silent(nullptr);
    RunOutcome outcome;
    {
      py::gil_scoped_release unlocked;
      outcome = std::visit(
          [&](auto& sim) {
            return run_simulation(*sim, requested_, support_, options, options.out,
                                  quiet ? silent : std::cout);
          },
          sim_);
    }
    const std::string status = outcome.summary.value("status", std::string());
    if (outcome.exit_code >= 128) {  // Ctrl-C: the run is kept, with a checkpoint
      PyErr_SetString(
          PyExc_KeyboardInterrupt,
          ("the run is kept in " + out + ".partial; granjet resume continues it").c_str());
      throw py::error_already_set();
    }
    if (outcome.exit_code != 0) {  // the blow-up's message is the run's status
      const py::object blow_up = py::module_::import("granjet").attr("BlowUpError");
      PyErr_SetString(blow_up.ptr(), (status + "; frames kept in " + out + ".partial").c_str());
      throw py::error_already_set();
    }
    return py::module_::import("json").attr("loads")(outcome.summary.dump());
  }

  // Advances in stretches of 50 steps, the GIL released, and lets Python handle its signals in
  // between: Ctrl-C raises KeyboardInterrupt at a step's end and the simulator stays usable.
  // Stopping between stretches changes nothing: the run loop stops where its observers ask.
  void advance_to(double t) {
    const double stretch = 50.0 * scene().dt(), half_step = 0.5 * scene().dt();
    while (time() < t - half_step) {
      // The last stretch ends at t itself: a sum of stretches would round beside it.
      const double next = time() + stretch < t - half_step ? time() + stretch : t;
      {
        py::gil_scoped_release unlocked;
        std::visit([&](auto& sim) { sim->advance_to(next); }, sim_);
      }
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    }
  }

  double time() const {
    return std::visit([](const auto& sim) { return sim->time(); }, sim_);
  }
  int dimension() const { return scene().dimension; }
  const Scene& scene() const { return support_.resolved; }
  const std::string& backend() const { return backend_; }

  py::dict energies() const {
    const EnergyBalance e = std::visit([](const auto& sim) { return sim->energy(); }, sim_);
    return py::dict("kinetic"_a = e.kinetic, "rotational"_a = e.rotational, "elastic"_a = e.elastic,
                    "dissipated"_a = e.dissipated, "removed"_a = e.removed, "total"_a = e.total());
  }

  py::dict stats() const {
    const SimStats s = std::visit([](const auto& sim) { return sim->stats(); }, sim_);
    return py::dict("steps"_a = s.steps, "particle_steps"_a = s.particle_steps,
                    "contacts"_a = s.contacts, "neighbour_rebuilds"_a = s.neighbour_rebuilds,
                    "removed"_a = s.removed, "events"_a = s.events, "collisions"_a = s.collisions,
                    "cell_crossings"_a = s.cell_crossings);
  }

  // The grains' arrays, views into the simulator (self keeps it alive).
  static py::array grains(const py::object& self, const std::string& what) {
    const PySimulator& me = self.cast<const PySimulator&>();
    return std::visit(
        [&](const auto& sim) -> py::array {
          const auto& p = sim->particles();
          constexpr int D = DimensionOf<std::remove_cvref_t<decltype(sim)>>::value;
          if (what == "positions") return view(p.position().data()->data(), p.size(), D, self);
          if (what == "velocities") return view(p.velocity().data()->data(), p.size(), D, self);
          if (what == "radii") return view(p.radius().data(), p.size(), 1, self);
          if (what == "ids") return view(p.id().data(), p.size(), 1, self);
          const double* spin = reinterpret_cast<const double*>(p.spin().data());
          return view(spin, p.size(), D == 3 ? 3 : 1, self);
        },
        me.sim_);
  }

  // Contact forces (soft DEM): a copy, since they are sampled, not stored.
  py::dict forces() const {
    return std::visit(
        [](const auto& sim) {
          constexpr int D = DimensionOf<std::remove_cvref_t<decltype(sim)>>::value;
          ForceSample<D> sample;
          sim->sample_forces(sample);
          const auto c = static_cast<py::ssize_t>(sample.contacts.size());
          py::array_t<std::int64_t> pairs({c, py::ssize_t{2}});
          py::array_t<double> normal({c, py::ssize_t{D}}), tangential({c, py::ssize_t{D}});
          py::array_t<double> overlap(c);
          auto pr = pairs.mutable_unchecked<2>();
          auto nr = normal.mutable_unchecked<2>(), tr = tangential.mutable_unchecked<2>();
          auto orr = overlap.mutable_unchecked<1>();
          for (py::ssize_t k = 0; k < c; ++k) {
            const auto& contact = sample.contacts[k];
            pr(k, 0) = contact.i;
            pr(k, 1) = contact.j;
            for (int d = 0; d < D; ++d) {
              nr(k, d) = contact.normal_force[d];
              tr(k, d) = contact.tangential_force[d];
            }
            orr(k) = contact.overlap;
          }
          py::array_t<double> total(
              {static_cast<py::ssize_t>(sample.total.size()), py::ssize_t{D}});
          auto t = total.mutable_unchecked<2>();
          for (std::size_t i = 0; i < sample.total.size(); ++i)
            for (int d = 0; d < D; ++d) t(static_cast<py::ssize_t>(i), d) = sample.total[i][d];
          return py::dict("pairs"_a = pairs, "normal"_a = normal, "tangential"_a = tangential,
                          "overlap"_a = overlap, "total"_a = total);
        },
        sim_);
  }

 private:
  Scene requested_;
  std::string backend_;
  SceneSupport support_;
  std::variant<std::unique_ptr<Simulator<2>>, std::unique_ptr<Simulator<3>>> sim_;
};

// A run's or an ensemble's file as granjet wrote it: its summary, stored scene, frames and any
// dataset of doubles, as NumPy arrays (copies: the file is closed between reads).
class PyFile {
 public:
  explicit PyFile(std::string path)
      : path_(std::move(path)), summary_(analysis::read_summary(path_)) {}

  py::dict summary() const {
    const analysis::FileSummary& f = summary_;
    return py::dict("creator"_a = f.creator + " " + f.creator_version, "backend"_a = f.backend,
                    "status"_a = f.status, "dimension"_a = f.dimension, "frames"_a = f.frames,
                    "max_grains"_a = f.max_grains, "first_time"_a = f.first_time,
                    "last_time"_a = f.last_time, "members"_a = f.members,
                    "checkpoint"_a = f.checkpoint);
  }
  Scene scene() const { return parse(summary_.scene_ini, path_ + " (stored scene)", {}); }

  // Frame k's present grains, sorted by id.
  py::dict frame(std::size_t k) const {
    py::dict d;
    const auto fill = [&](const auto& f, int dimension) {
      const auto n = static_cast<py::ssize_t>(f.id.size());
      d["step"] = f.step;
      d["time"] = f.time;
      d["ids"] = py::array_t<std::int64_t>(n, f.id.data());
      d["radii"] = py::array_t<double>(n, f.radius.data());
      const std::vector<py::ssize_t> shape{n, dimension};
      d["positions"] = py::array_t<double>(shape, f.position.data()->data());
      d["velocities"] = py::array_t<double>(shape, f.velocity.data()->data());
    };
    if (summary_.dimension == 2)
      fill(analysis::read_frame<2>(path_, k), 2);
    else
      fill(analysis::read_frame<3>(path_, k), 3);
    return d;
  }

  // FE.1's T_g(t) in layer (a) over the frames in the analysis window (2D jets): (times, T_g).
  py::tuple layer_a_temperature() const {
    const TimeSeries s = layer_a_temperature_series(path_);
    const auto n = static_cast<py::ssize_t>(s.time.size());
    return py::make_tuple(py::array_t<double>(n, s.time.data()),
                          py::array_t<double>(n, s.value.data()));
  }

  // Any dataset of doubles, flattened: "/observables/kinetic_energy/value",
  // "/fields/T_g/mean", "/analysis/...".
  py::array_t<double> dataset(const std::string& name) const {
    const analysis::ShapedValues v = analysis::read_shaped_values(path_, name);
    return py::array_t<double>(std::vector<py::ssize_t>(v.shape.begin(), v.shape.end()),
                               v.values.data());
  }

  // The measured fields by their names in the JSON summary ("T_g", "stress.rz"), each a dict
  // of its statistics over seeds (mean, std, sem, count) as [layers][lateral] arrays.
  py::dict fields() const { return grouped("/fields", {"mesh/", "layout/"}); }
  // The observables' time series by name: {name: {"step", "time", "value"}}.
  py::dict observables() const { return grouped("/observables", {}); }

 private:
  // The datasets below `group` as {name: {leaf: array}}: "stress/rz/mean" -> ["stress.rz"]
  // ["mean"]; paths starting with one of `skipped` are left out.
  py::dict grouped(const std::string& group, const std::vector<std::string>& skipped) const {
    py::dict out;
    for (const std::string& path : analysis::list_datasets(path_, group)) {
      if (std::any_of(skipped.begin(), skipped.end(),
                      [&](const std::string& s) { return path.rfind(s, 0) == 0; }))
        continue;
      const std::size_t slash = path.rfind('/');
      if (slash == std::string::npos) continue;  // a dataset directly in the group
      std::string name = path.substr(0, slash);
      std::replace(name.begin(), name.end(), '/', '.');
      const py::str key(name);
      if (!out.contains(key)) out[key] = py::dict();
      out[key][py::str(path.substr(slash + 1))] = dataset(group + "/" + path);
    }
    return out;
  }

  std::string path_;
  analysis::FileSummary summary_;
};

}  // namespace
}  // namespace granjet::python

PYBIND11_MODULE(granjet, m) {
  using namespace granjet;
  using granjet::python::PySimulator;
  m.doc() = "granjet: granular jets on a soft-sphere DEM and an event-driven hard-sphere backend";
  // As `granjet --version` gives it, and as the files this build writes record it.
  m.attr("__version__") = std::string(kVersion) + "+" + kCommit;

  static py::exception<InputError> scene_error(m, "SceneError");
  static py::exception<BlowUpError> blow_up_error(m, "BlowUpError");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      scene_error(e.what());
    } catch (const BlowUpError& e) {
      blow_up_error(e.what());
    }
  });

  py::class_<Scene>(m, "Scene", "A scene: every key of a scene file, checked as the CLI checks it.")
      .def_static(
          "from_file",
          [](const std::string& path, const std::vector<std::string>& overrides) {
            return load_scene(path, overrides);
          },
          py::arg("path"), py::arg("overrides") = std::vector<std::string>{},
          "A scene file, with overrides 'section.key=value' as --set gives them.")
      .def_static("from_dict", &python::scene_from_dict, py::arg("entries"),
                  "From {'section.key': value} or {'section': {'key': value}}; scene.kind is "
                  "required, every other key has its default.")
      .def(
          "set",
          [](Scene& s, const std::string& key, const py::object& value) {
            s = python::parse(scene_to_ini(s), "scene", {key + "=" + python::scene_text(value)});
          },
          py::arg("key"), py::arg("value"), "Sets one key, checked with the whole scene.")
      .def("to_ini", &scene_to_ini, "The scene as a file that reproduces it.")
      .def_property_readonly("dimension", [](const Scene& s) { return s.dimension; })
      .def("__repr__", [](const Scene& s) {
        return "<granjet.Scene " + (s.name.empty() ? std::string("(unnamed)") : s.name) + ", " +
               std::to_string(s.dimension) + "D>";
      });

  py::class_<PySimulator>(m, "Simulator",
                          "A scene on a backend: advance it, read its grains as NumPy arrays.")
      .def(py::init<const Scene&, const std::string&, int>(), py::arg("scene"),
           py::arg("backend") = "soft_dem", py::arg("threads") = 0,
           "threads: run.threads (0: the scene's); the results do not depend on it.")
      .def("advance_to", &PySimulator::advance_to, py::arg("t"),
           "Advances to time t (to within half a step); Ctrl-C stops it at a step's end.")
      .def("run", &PySimulator::run, py::arg("out"), py::arg("summary") = "",
           py::arg("log") = false, py::arg("quiet") = true,
           "Runs the scene from t = 0 to run.t_end into `out` as `granjet run` does (the same "
           "H5MD file, sidecars, analysis; the log and the JSON summary if asked for) and "
           "returns the summary. Ctrl-C keeps the run as OUT.partial (KeyboardInterrupt); a "
           "blow-up raises BlowUpError.")
      .def_property_readonly("time", &PySimulator::time)
      .def_property_readonly("dimension", &PySimulator::dimension)
      .def_property_readonly("backend", &PySimulator::backend)
      .def_property_readonly("scene", &PySimulator::scene, "The scene as the backend resolved it.")
      .def("energies", &PySimulator::energies)
      .def("stats", &PySimulator::stats)
      .def_property_readonly(
          "positions", [](const py::object& s) { return PySimulator::grains(s, "positions"); })
      .def_property_readonly(
          "velocities", [](const py::object& s) { return PySimulator::grains(s, "velocities"); })
      .def_property_readonly("radii",
                             [](const py::object& s) { return PySimulator::grains(s, "radii"); })
      .def_property_readonly("ids",
                             [](const py::object& s) { return PySimulator::grains(s, "ids"); })
      .def_property_readonly("spins",
                             [](const py::object& s) { return PySimulator::grains(s, "spins"); })
      .def("forces", &PySimulator::forces,
           "Contact pairs (ids; -1 the plate) with their normal and tangential forces and "
           "overlaps, and each grain's total force (soft DEM).");

  // Scalars or NumPy arrays (element by element), as the analysis computes them.
  using granjet::python::PyFile;
  py::class_<PyFile>(m, "File", "A granjet H5MD file, read back.")
      .def_property_readonly("summary", &PyFile::summary)
      .def_property_readonly("scene", &PyFile::scene, "The scene as the backend ran it.")
      .def("frame", &PyFile::frame, py::arg("k"),
           "Frame k's grains sorted by id: step, time, ids, positions, velocities, radii.")
      .def("layer_a_temperature", &PyFile::layer_a_temperature,
           "FE.1's T_g(t) in layer (a), -dy < y < 0, over the frames in the analysis window of "
           "a 2D jet: (times, values).")
      .def("dataset", &PyFile::dataset, py::arg("name"),
           "A dataset of doubles in its shape (e.g. '/observables/kinetic_energy/value', "
           "'/fields/T_g/mean').")
      .def_property_readonly("fields", &PyFile::fields,
                             "The measured fields by name ('T_g', 'stress.rz'): {'mean', 'std', "
                             "'sem', 'count'} as [layers][lateral] arrays.")
      .def_property_readonly("observables", &PyFile::observables,
                             "The observables by name: {'step', 'time', 'value'} arrays.");
  m.def(
      "open", [](const std::string& path) { return PyFile(path); }, py::arg("path"),
      "A run's or an ensemble's file as granjet wrote it.");

  py::module_ theory = m.def_submodule("theory", "Kinetic theory of inelastic hard spheres.");
  namespace kt = granjet::analysis::kinetic;
  theory.attr("PHI_FREEZING") = kt::kPhiFreezing;
  theory.attr("PHI_CLOSE_PACKING") = kt::kPhiClosePacking;
  theory.def("chi", py::vectorize(&kt::chi), py::arg("phi"),
             "[5.3] pair correlation at contact (infinite from phi_c on).");
  theory.def("pressure_ratio", py::vectorize(&kt::pressure_ratio), py::arg("phi"), py::arg("e"),
             "[5.2] P/(n T_g) = 1 + 2 phi (1+e) chi.");
  theory.def("effective_restitution", py::vectorize(&kt::effective_restitution), py::arg("e"),
             py::arg("mu_p"), "[2.55] e - (pi/2) mu_p + (9/2) mu_p^2.");
  theory.def("sonine_a2", py::vectorize(py::overload_cast<double, int>(&kt::sonine_a2)),
             py::arg("e"), py::arg("dimension") = 3, "[2.37] the HCS Sonine coefficient.");
  theory.def("cooling_per_collision", py::vectorize(&kt::cooling_per_collision), py::arg("e"),
             py::arg("dimension"));
  theory.def("carnahan_starling", py::vectorize(&kt::carnahan_starling), py::arg("phi"));
  theory.def("henderson", py::vectorize(&kt::henderson), py::arg("phi"));
  theory.def("enskog_collision_frequency", py::vectorize(&kt::enskog_collision_frequency),
             py::arg("phi"), py::arg("temperature"), py::arg("dimension"));
  theory.def("viscosity_star", py::vectorize(&kt::viscosity_star), py::arg("phi"), py::arg("e"),
             "[5.4]-[5.11] Garzo-Dufty eta*.");
  theory.def("kinetic_viscosity", py::vectorize(&kt::kinetic_viscosity), py::arg("phi"),
             py::arg("e"), py::arg("temperature"), py::arg("mass") = 1.0, py::arg("diameter") = 1.0,
             "[5.4] eta_kin.");

  py::module_ contact = m.def_submodule("contact", "The soft contact laws' coefficients.");
  contact.def(
      "coefficients",
      [](double e, double t_c, double spring_ratio, double damping_ratio) {
        ContactSpec spec;
        spec.restitution = e;
        spec.contact_time = t_c;
        spec.spring_ratio = spring_ratio;
        spec.damping_ratio = damping_ratio;
        const dem::ContactCoefficients c = dem::contact_coefficients(spec);
        return py::dict("k_n"_a = c.kn, "eta_n"_a = c.eta_n, "k_t"_a = c.kt, "eta_t"_a = c.eta_t);
      },
      py::arg("e"), py::arg("t_c"), py::arg("spring_ratio") = 0.2, py::arg("damping_ratio") = 0.5,
      "[3.4], [3.5]: the linear law's k_n, eta_n (and k_t, eta_t) of two unit grains whose "
      "head-on collision has restitution e and lasts t_c.");
  contact.def(
      "collision",
      [](double k_n, double eta_n) {
        const dem::BinaryCollision c = dem::binary_collision(k_n, eta_n);
        return py::dict("e"_a = c.restitution, "t_c"_a = c.contact_time);
      },
      py::arg("k_n"), py::arg("eta_n"),
      "[3.4], [3.5] the other way: the restitution e and duration t_c of the head-on collision "
      "of two unit grains under the linear law (k_n, eta_n); NaN when overdamped.");

  py::module_ fits = m.def_submodule("fits", "The study's laws and their least-squares fits.");
  namespace an = granjet::analysis;
  fits.def("packing_law", py::vectorize(&an::packing_law), py::arg("i"), py::arg("phi_0"),
           py::arg("a"), py::arg("alpha"), "[6.2]/[6.3] phi = phi_0 - a I^(2/alpha).");
  fits.def("friction_saturating", py::vectorize(&an::friction_saturating), py::arg("i_s"),
           py::arg("mu_s"), py::arg("mu_max"), py::arg("i_0"),
           "[6.9] mu* = mu_s + (mu_max - mu_s)/(1 + I_0/I_s).");
  fits.def("friction_power", py::vectorize(&an::friction_power), py::arg("i_s"), py::arg("mu_s"),
           py::arg("b"), py::arg("beta"), "[6.10] mu* = mu_s + b I_s^beta.");
  fits.def("friction_linear", py::vectorize(&an::friction_linear), py::arg("i"), py::arg("a"),
           "3D mu* = a I.");
  fits.def("scattering_angle_law", py::vectorize(&an::scattering_angle_law), py::arg("x"),
           py::arg("c0"), py::arg("c1"), py::arg("c2"), "psi0(X), model §6.");
  // A fit as {"law", "parameters": {name: (value, error)}, "ssr", "points", "converged"}.
  const auto fitted = [](const an::FitResult& f) {
    py::dict parameters;
    for (std::size_t k = 0; k < f.parameters.size(); ++k)
      parameters[py::str(f.parameters[k])] = py::make_tuple(f.value[k], f.error[k]);
    return py::dict("law"_a = f.law, "parameters"_a = parameters, "ssr"_a = f.ssr,
                    "points"_a = f.points, "converged"_a = f.converged);
  };
  using Fit = an::FitResult (*)(std::span<const double>, std::span<const double>);
  for (const auto& [name, fit, doc] : std::vector<std::tuple<const char*, Fit, const char*>>{
           {"phi_of_i_t", &an::fit_phi_of_i_t, "[6.2]: phi_T, a_T, alpha_T"},
           {"phi_of_i_s", &an::fit_phi_of_i_s, "[6.3]: phi_s, a_s, alpha_s"},
           {"mu_saturating", &an::fit_mu_saturating, "[6.9]: mu_s, mu_max, I_0"},
           {"mu_power", &an::fit_mu_power, "[6.10] with mu_s = 0: b, beta"},
           {"mu_linear", &an::fit_mu_linear, "3D mu* = a I: a"},
           {"mu_affine", &an::fit_mu_affine, "3D mu* = mu_0 + a I: mu_0, a"},
           {"scattering_angle", &an::fit_scattering_angle, "psi0(X): C0, C1, C2"}})
    fits.def(
        name,
        [fit, fitted](const std::vector<double>& x, const std::vector<double>& y) {
          if (x.size() != y.size()) throw py::value_error("x and y differ in length");
          return fitted(fit(x, y));
        },
        py::arg("x"), py::arg("y"), doc);
}
