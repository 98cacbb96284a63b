// xshell._core.relax: one run of `xshell relax` (app/relax_run.hpp) for the
// Python module. The GIL is released while the run goes; it is taken again
// after every iteration, briefly, to pass the new history records to the
// progress callable and to let Python handle its signals
// (PyErr_CheckSignals): Ctrl-C raises the run's stop flag, the run stops at
// its next iteration and ends as an interrupted run does (its outputs
// written), and KeyboardInterrupt is raised once it has. An exception of the
// progress callable stops the run the same way and is raised after it.
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <exception>
#include <iostream>
#include <optional>
#include <string>

#include "app/exit_status.hpp"
#include "app/relax_run.hpp"
#include "bindings.hpp"

namespace py = pybind11;

namespace xshell::python {

namespace {

py::dict record_dict(const IterationRecord& r) {
  py::dict d;
  d["iteration"] = r.iteration;
  d["time"] = r.time;
  d["energy"] = r.energy;
  d["gradient_norm"] = r.gradient_norm;
  d["step"] = r.step;
  d["kinetic_energy"] = r.kinetic_energy;
  d["seconds"] = r.seconds;
  return d;
}

Toggle parse_progress(const std::string& lines) {
  if (lines == "on") return Toggle::On;
  if (lines == "auto") return Toggle::Auto;
  return Toggle::Off;
}

// Runs `request` without the GIL; see the file's comment. Returns
// (exit status, error message, summary.json's text or None, state text).
py::tuple run(const RelaxRequest& request, const std::optional<py::function>& progress,
              const std::string& lines, bool log) {
  // Python handles signals in its main thread only: elsewhere, the GIL is
  // taken only for a progress callable.
  const py::module_ threading = py::module_::import("threading");
  const bool main_thread = threading.attr("current_thread")().is(threading.attr("main_thread")());
  std::atomic<bool> stop{false};
  std::optional<py::error_already_set> pending;  // raised after the run (held with the GIL)
  std::exception_ptr failure;                    // the same, of another kind
  RelaxHooks hooks;
  hooks.stop = &stop;
  hooks.progress = parse_progress(lines);
  hooks.log = log ? &std::cerr : nullptr;
  hooks.on_iteration = [&](const std::vector<IterationRecord>& records) {
    if (stop.load() || (!progress && !main_thread)) return;
    const py::gil_scoped_acquire gil;
    try {
      if (progress)
        for (const IterationRecord& r : records) (*progress)(record_dict(r));
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    } catch (py::error_already_set& e) {
      pending.emplace(std::move(e));
      stop = true;
    } catch (...) {  // nothing may cross the solvers' C callbacks
      failure = std::current_exception();
      stop = true;
    }
  };
  RelaxOutcome outcome;
  {
    const py::gil_scoped_release no_gil;
    outcome = relax(request, hooks);
  }
  if (pending) {
    pending->restore();
    pending.reset();
    throw py::error_already_set();
  }
  if (failure) std::rethrow_exception(failure);
  py::object summary = py::none();
  if (outcome.summary) summary = py::str(to_json(*outcome.summary).dump());
  return py::make_tuple(outcome.exit_status, outcome.error, summary, outcome.state);
}

}  // namespace

void bind_relax(py::module_& m) {
  m.def(
      "relax",
      [](const std::string& config, const std::optional<std::string>& config_text,
         const std::string& base_dir, const std::optional<std::string>& solver, bool write_files,
         const std::optional<std::string>& out, const std::optional<std::string>& init,
         const std::optional<std::string>& init_text, const std::optional<py::function>& progress,
         const std::string& lines, bool log) {
        RelaxRequest request;
        request.config = config;
        request.config_text = config_text;
        request.base_dir = base_dir;
        request.solver = solver;
        request.write_files = write_files;
        request.out = out;
        request.init = init;
        request.init_text = init_text;
        request.keep_state = true;
        return run(request, progress, lines, log);
      },
      py::arg("config"), py::arg("config_text"), py::arg("base_dir"), py::arg("solver"),
      py::arg("write_files"), py::arg("out"), py::arg("init"), py::arg("init_text"),
      py::arg("progress"), py::arg("lines") = "off", py::arg("log") = false,
      "One run of `xshell relax` (see xshell.relax): returns (exit status, error message, "
      "summary.json's text or None, the final state's text).");
  m.attr("EXIT_INVALID_INPUT") = static_cast<int>(kExitInvalidInput);
  m.attr("EXIT_OUTPUT_FAILED") = static_cast<int>(kExitOutputFailed);
  m.attr("EXIT_INTERRUPTED") = static_cast<int>(kExitInterrupted);
  m.attr("EXIT_NOT_CONVERGED") = static_cast<int>(kExitNotConverged);
}

}  // namespace xshell::python
