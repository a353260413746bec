// The Python front end of the core: `import fldsim` builds the same Simulation as `fldsim run`
// from an experiment file (with --set style overrides), steps it, and hands the state and the
// observers' results to numpy. pybind11 from Debian (pybind11-dev).
//
//   sim = fldsim.Simulation("examples/quickstart.yaml", overrides=["run.duration=1"])
//   sim.run(); sim.finish()
//   sim.positions          # (N, 3) body centres in the box [0, L)^3, unit a
//   sim.results()          # {"results/orientation/S_xx": (value, stderr, unit), ...}
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <sstream>

#include "fldsim/error.hpp"
#include "io/Checkpoint.hpp"
#include "io/Hdf5ResultSink.hpp"
#include "io/MemoryResultSink.hpp"
#include "run/Experiment.hpp"
#include "run/Provenance.hpp"
#include "run/Simulation.hpp"

namespace py = pybind11;

namespace fldsim::python {
namespace {

// Results go to memory (for numpy) and, when an output file is named, to it as well.
class TeeSink : public ResultSink {
 public:
  TeeSink(MemoryResultSink& memory, ResultSink* file) : memory_(memory), file_(file) {}
  void write_scalar(const std::string& p, double v, double e, const std::string& u,
                    const std::string& d) override {
    memory_.write_scalar(p, v, e, u, d);
    if (file_) file_->write_scalar(p, v, e, u, d);
  }
  void write_array(const std::string& p, const std::vector<std::size_t>& s, const double* x,
                   const std::string& u, const std::string& d) override {
    memory_.write_array(p, s, x, u, d);
    if (file_) file_->write_array(p, s, x, u, d);
  }
  void append_sample(const std::string& p, std::int64_t step, double t, const std::vector<std::size_t>& s,
                     const double* x, const std::string& u) override {
    memory_.append_sample(p, step, t, s, x, u);
    if (file_) file_->append_sample(p, step, t, s, x, u);
  }
  void write_attribute(const std::string& p, const std::string& k, const std::string& v) override {
    memory_.write_attribute(p, k, v);
    if (file_) file_->write_attribute(p, k, v);
  }
  void write_int_attribute(const std::string& p, const std::string& k,
                           const std::vector<std::int64_t>& v) override {
    memory_.write_int_attribute(p, k, v);
    if (file_) file_->write_int_attribute(p, k, v);
  }
  void write_string_list_attribute(const std::string& p, const std::string& k,
                                   const std::vector<std::string>& v) override {
    memory_.write_string_list_attribute(p, k, v);
    if (file_) file_->write_string_list_attribute(p, k, v);
  }

 private:
  MemoryResultSink& memory_;
  ResultSink* file_;
};

py::array_t<double> array(const std::vector<std::size_t>& shape, const double* data) {
  std::vector<py::ssize_t> dims(shape.begin(), shape.end());
  py::array_t<double> a(dims);
  std::copy(data, data + a.size(), a.mutable_data());
  return a;
}

class PySimulation {
 public:
  PySimulation(const std::string& file, const std::vector<std::string>& overrides, const std::string& output,
               bool overwrite) {
    ex_ = read_experiment(file, overrides, registry_);
    if (!output.empty()) {
      ex_.output = output;
      file_sink_ = std::make_unique<Hdf5ResultSink>(output, overwrite);
    }
    tee_ = std::make_unique<TeeSink>(memory_, file_sink_.get());
    sim_ = Simulation::from_experiment(ex_, *registry_, *tee_, log_);
    if (file_sink_) write_provenance(*file_sink_, ex_, *registry_, *sim_);
  }

  // n steps, not past the end of the run (observers size their work by its length).
  void step(std::int64_t n) {
    if (n < 0) throw py::value_error("step: n must be >= 0");
    const std::int64_t left = sim_->settings().total_steps - sim_->system().step();
    if (n > left)
      throw py::value_error("step: " + std::to_string(n) + " steps asked, " + std::to_string(left) +
                            " left in run.duration");
    for (std::int64_t k = 0; k < n; ++k) step_checking_signals();
  }
  void run() {
    while (!sim_->finished()) step_checking_signals();
  }
  void finish() {
    if (finished_) return;
    sim_->finish();
    if (file_sink_) {
      write_checkpoint(ex_.output + ".checkpoint", sim_->capture());
      file_sink_->commit();
    }
    finished_ = true;
  }

  py::array_t<double> positions() const {
    const auto& x = sim_->system().positions();
    return array({x.size(), 3}, x.empty() ? nullptr : x.front().data());
  }
  py::array_t<double> orientations() const {
    const auto& q = sim_->system().orientations();
    std::vector<double> flat(4 * q.size());
    for (std::size_t i = 0; i < q.size(); ++i) {
      flat[4 * i] = q[i].w();
      flat[4 * i + 1] = q[i].x();
      flat[4 * i + 2] = q[i].y();
      flat[4 * i + 3] = q[i].z();
    }
    return array({q.size(), 4}, flat.data());
  }
  py::array_t<double> directors() const {
    const System& s = sim_->system();
    std::vector<double> flat(3 * s.size());
    for (std::size_t i = 0; i < s.size(); ++i) {
      const Vec3 n = s.director(i);
      for (int d = 0; d < 3; ++d) flat[3 * i + d] = n[d];
    }
    return array({s.size(), 3}, flat.data());
  }
  py::array_t<double> displacements() const {
    const auto& d = sim_->system().displacement();
    return array({d.size(), 3}, d.empty() ? nullptr : d.front().data());
  }
  double time() const { return sim_->system().time() / sim_->settings().time_scale; }

  py::dict results() const {
    py::dict d;
    for (const auto& [path, s] : memory_.scalars())
      d[py::str(path)] = py::make_tuple(s.value, s.stderr_value, s.unit);
    return d;
  }
  py::dict arrays() const {
    py::dict d;
    for (const auto& [path, a] : memory_.arrays()) d[py::str(path)] = array(a.shape, a.data.data());
    return d;
  }
  std::vector<std::string> series_names() const {
    std::vector<std::string> names;
    for (const auto& kv : memory_.series()) names.push_back(kv.first);
    return names;
  }
  py::dict series(const std::string& path) const {
    const auto it = memory_.series().find(path);
    if (it == memory_.series().end()) throw py::key_error("no time series '" + path + "'");
    const auto& s = it->second;
    std::vector<std::size_t> shape{s.steps.size()};
    shape.insert(shape.end(), s.shape.begin(), s.shape.end());
    std::vector<double> times(s.times.size());
    for (std::size_t k = 0; k < times.size(); ++k) times[k] = s.times[k] / sim_->settings().time_scale;
    py::dict d;
    d["step"] = py::array_t<std::int64_t>(py::ssize_t(s.steps.size()), s.steps.data());
    d["time"] = py::array_t<double>(py::ssize_t(times.size()), times.data());
    d["value"] = array(shape, s.data.data());
    d["unit"] = s.unit;
    return d;
  }

  void save_checkpoint(const std::string& path) const { write_checkpoint(path, sim_->capture()); }
  void load_checkpoint(const std::string& path) { sim_->apply(read_checkpoint(path), path); }

  Simulation& sim() { return *sim_; }
  const Simulation& sim() const { return *sim_; }
  std::string log() const { return log_.str(); }

 private:
  void step_checking_signals() {
    {
      py::gil_scoped_release release;
      sim_->step();
    }
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }

  std::unique_ptr<PluginRegistry> registry_;
  Experiment ex_;
  MemoryResultSink memory_;
  std::unique_ptr<Hdf5ResultSink> file_sink_;
  std::unique_ptr<TeeSink> tee_;
  std::ostringstream log_;
  std::unique_ptr<Simulation> sim_;
  bool finished_ = false;
};

}  // namespace
}  // namespace fldsim::python

PYBIND11_MODULE(_fldsim, m) {
  using fldsim::python::PySimulation;
  m.doc() = "fldsim: Brownian suspensions of rigid colloids under shear (Fast Lubrication Dynamics)";
  m.attr("__version__") = FLDSIM_VERSION;
  // pybind11 tries the translators last registered first: the derived ConfigError after Error.
  py::register_exception<fldsim::Error>(m, "Error", PyExc_RuntimeError);
  py::register_exception<fldsim::ConfigError>(m, "ConfigError", PyExc_ValueError);

  py::class_<PySimulation>(m, "Simulation",
                           "One run of an experiment, assembled as `fldsim run` assembles it.")
      .def(py::init<const std::string&, const std::vector<std::string>&, const std::string&, bool>(),
           py::arg("experiment"), py::arg("overrides") = std::vector<std::string>{}, py::arg("output") = "",
           py::arg("overwrite") = false,
           "experiment: YAML file; overrides: ['flow.peclet=10', ...] as `fldsim run --set`; output: "
           "also write an HDF5 result file (and its checkpoint) there, completed by finish()")
      .def("step", &PySimulation::step, py::arg("n") = 1, "take n time steps (not past run.duration)")
      .def("run", &PySimulation::run, "step to the end of run.duration")
      .def("finish", &PySimulation::finish,
           "let every observer write its steady-state results (and complete the output file)")
      .def_property_readonly("positions", &PySimulation::positions,
                             "body centres (N, 3) in the box [0, L)^3, unit a")
      .def_property_readonly("orientations", &PySimulation::orientations,
                             "unit quaternions (N, 4), scalar first (w, x, y, z), body to lab frame")
      .def_property_readonly("directors", &PySimulation::directors, "body axes n (N, 3), lab frame")
      .def_property_readonly("displacements", &PySimulation::displacements,
                             "unwrapped displacement of each body since the start (N, 3), unit a")
      .def_property_readonly("time", &PySimulation::time, "time in the run's unit (time_unit)")
      .def_property_readonly("time_unit", [](const PySimulation& s) { return s.sim().settings().time_unit; })
      .def_property_readonly("step_index", [](const PySimulation& s) { return s.sim().system().step(); })
      .def_property_readonly("total_steps",
                             [](const PySimulation& s) { return s.sim().settings().total_steps; })
      .def_property_readonly("finished", [](const PySimulation& s) { return s.sim().finished(); })
      .def_property_readonly(
          "strain", [](const PySimulation& s) { return s.sim().system().box().strain(); },
          "accumulated shear strain gammadot t")
      .def_property_readonly("box_edge", [](const PySimulation& s) { return s.sim().system().box().edge(); })
      .def_property_readonly("count", [](const PySimulation& s) { return s.sim().system().size(); })
      .def("results", &PySimulation::results,
           "steady-state scalars written by finish(): {path: (value, standard error, unit)}")
      .def("arrays", &PySimulation::arrays, "arrays written by the observers: {path: numpy array}")
      .def("series_names", &PySimulation::series_names, "paths of the observers' time series")
      .def("series", &PySimulation::series, py::arg("path"),
           "one time series: {'step', 'time' (run's unit), 'value', 'unit'}")
      .def("save_checkpoint", &PySimulation::save_checkpoint, py::arg("path"))
      .def("load_checkpoint", &PySimulation::load_checkpoint, py::arg("path"),
           "continue from a checkpoint (bit for bit as the run that wrote it)")
      .def_property_readonly("log", &PySimulation::log, "what `fldsim run` would have printed");
}
