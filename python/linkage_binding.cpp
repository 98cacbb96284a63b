// xshell._core.Linkage: the statics problem of a configuration (its linkage,
// supports and loads, linkage/statics_problem.hpp) as research code sees it:
// the reduced unknowns in the documented order (docs/model.md, "The reduced
// unknowns"), the total energy (elastic energy minus the work of the dead
// loads), its gradient and its Hessian over all of them (the fixed ones
// included), and which are free. Built by the same loading as a run
// (app/relax_run.hpp: load_run), so that it is the problem `relax` solves.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <limits>
#include <optional>
#include <string>

#include "app/relax_run.hpp"
#include "bindings.hpp"
#include "io/input_error.hpp"
#include "io/state_file.hpp"

namespace py = pybind11;

namespace xshell::python {

namespace {

class Linkage {
 public:
  explicit Linkage(const RelaxRequest& request) {
    try {
      load_run(request, run_);
    } catch (const InputError& e) {
      throw py::value_error(e.what());
    }
  }

  LinkageProblem& problem() { return *run_.problem; }

  Eigen::VectorXd dofs() { return problem().dofs(); }

  void set_dofs(const Eigen::VectorXd& q) {
    if (q.size() != problem().linkage().num_dofs())
      throw py::value_error("set_dofs: expected " + std::to_string(problem().linkage().num_dofs()) +
                            " values, got " + std::to_string(q.size()));
    problem().set_dofs(q);
  }

  py::dict energy_terms() {
    const EnergyReport e = problem().energy();
    py::dict d;
    d["total"] = e.total();
    d["stretching"] = e.stretching;
    d["bending"] = e.bending;
    d["twisting"] = e.twisting;
    d["external"] = e.external;
    return d;
  }

  // The full Hessian of the total energy: the elastic Hessian with the dead
  // loads' part on the full variables (the loads at joints are linear in
  // the unknowns).
  Eigen::SparseMatrix<double> hessian() {
    return problem().linkage().hessian(&problem().segment_loads());
  }

  std::vector<bool> free() {
    std::vector<bool> f(problem().linkage().num_dofs());
    for (size_t i = 0; i < f.size(); ++i) f[i] = !problem().is_fixed(static_cast<int>(i));
    return f;
  }

  Eigen::MatrixXd vertices() {
    const std::vector<Eigen::Vector3d> x = problem().vertex_positions();
    Eigen::MatrixXd out(x.size(), 3);
    for (size_t i = 0; i < x.size(); ++i) out.row(i) = (x[i] + run_.setup.origin).transpose();
    return out;
  }

  Eigen::VectorXd opening_angles() {
    const std::vector<std::optional<double>> a = problem().opening_angles();
    Eigen::VectorXd out(a.size());
    for (size_t i = 0; i < a.size(); ++i)
      out[i] = a[i] ? *a[i] : std::numeric_limits<double>::quiet_NaN();
    return out;
  }

  std::string state() { return state_text(problem().linkage(), run_.setup.origin); }

 private:
  LoadedRun run_;
};

}  // namespace

void bind_linkage(py::module_& m) {
  py::class_<Linkage>(m, "Linkage")
      .def(py::init([](const std::string& config, const std::optional<std::string>& config_text,
                       const std::string& base_dir, const std::optional<std::string>& init,
                       const std::optional<std::string>& init_text) {
             RelaxRequest request;
             request.config = config;
             request.config_text = config_text;
             request.base_dir = base_dir;
             request.write_files = false;
             request.init = init;
             request.init_text = init_text;
             return new Linkage(request);
           }),
           py::arg("config"), py::arg("config_text"), py::arg("base_dir"), py::arg("init"),
           py::arg("init_text"))
      .def_property_readonly("dofs", &Linkage::dofs)
      .def("set_dofs", &Linkage::set_dofs, py::arg("q"))
      // The evaluations release the GIL (other threads run meanwhile).
      .def(
          "energy", [](Linkage& l) { return l.problem().energy().total(); },
          py::call_guard<py::gil_scoped_release>())
      .def("energy_terms", &Linkage::energy_terms)
      .def(
          "gradient", [](Linkage& l) { return l.problem().full_gradient(); },
          py::call_guard<py::gil_scoped_release>())
      .def("hessian", &Linkage::hessian, py::call_guard<py::gil_scoped_release>())
      .def_property_readonly("free", &Linkage::free)
      .def(
          "update_frames", [](Linkage& l) { l.problem().rebase(); },
          py::call_guard<py::gil_scoped_release>())
      .def_property_readonly("vertices", &Linkage::vertices)
      .def_property_readonly("opening_angles", &Linkage::opening_angles)
      .def_property_readonly("state", &Linkage::state)
      .def_property_readonly("length_scale", [](Linkage& l) { return l.problem().length_scale(); })
      .def_property_readonly("force_scale", [](Linkage& l) { return l.problem().force_scale(); });
}

}  // namespace xshell::python
