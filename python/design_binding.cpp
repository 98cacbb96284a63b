// xshell._core.design: one run of `xshell design` (app/design_run.hpp) for
// the Python module. As relax_binding.cpp: the GIL is released while the
// design runs and taken again after every design iteration, to pass the
// iteration's record to the progress callable and to let Python handle its
// signals; Ctrl-C or an exception of the callable stops the optimization at
// its next iteration (the best design so far is reported and, with an
// output folder, written), then is raised.
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <exception>
#include <iostream>
#include <optional>
#include <string>

#include "app/design_run.hpp"
#include "bindings.hpp"

namespace py = pybind11;

namespace xshell::python {

namespace {

// (exit status, error message, design.json's text or None, deployed state
// text, flat state text).
py::tuple run(const DesignRequest& request, const std::optional<py::function>& progress, bool log) {
  const py::module_ threading = py::module_::import("threading");
  const bool main_thread = threading.attr("current_thread")().is(threading.attr("main_thread")());
  std::atomic<bool> stop{false};
  std::optional<py::error_already_set> pending;
  std::exception_ptr failure;
  DesignHooks hooks;
  hooks.stop = &stop;
  hooks.log = log ? &std::cerr : nullptr;
  hooks.on_iteration = [&](const DesignIteration&, const nlohmann::json& record) {
    if (stop.load() || (!progress && !main_thread)) return;
    const py::gil_scoped_acquire gil;
    try {
      if (progress) (*progress)(py::module_::import("json").attr("loads")(record.dump()));
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    } catch (py::error_already_set& e) {
      pending.emplace(std::move(e));
      stop = true;
    } catch (...) {  // nothing may cross IPOPT's callbacks
      failure = std::current_exception();
      stop = true;
    }
  };
  DesignOutcome outcome;
  {
    const py::gil_scoped_release no_gil;
    outcome = run_design(request, hooks);
  }
  if (pending) {
    pending->restore();
    pending.reset();
    throw py::error_already_set();
  }
  if (failure) std::rethrow_exception(failure);
  py::object report = py::none();
  if (outcome.report) report = py::str(outcome.report->dump());
  return py::make_tuple(outcome.exit_status, outcome.error, report, outcome.deployed_state,
                        outcome.flat_state);
}

}  // namespace

void bind_design(py::module_& m) {
  m.def(
      "design",
      [](const std::string& config, const std::optional<std::string>& config_text,
         const std::string& base_dir, bool write_files, const std::optional<std::string>& out,
         const std::optional<std::string>& init, const std::optional<std::string>& init_text,
         const std::optional<py::function>& progress, bool log) {
        DesignRequest request;
        request.config = config;
        request.config_text = config_text;
        request.base_dir = base_dir;
        request.write_files = write_files;
        request.out = out;
        request.init = init;
        request.init_text = init_text;
        return run(request, progress, log);
      },
      py::arg("config"), py::arg("config_text"), py::arg("base_dir"), py::arg("write_files"),
      py::arg("out"), py::arg("init"), py::arg("init_text"), py::arg("progress"),
      py::arg("log") = false,
      "One run of `xshell design` (see xshell.design): returns (exit status, error message, "
      "design.json's text or None, the deployed state's text, the flat state's text).");
}

}  // namespace xshell::python
