// xshell._core: the compiled part of the Python module xshell. The Python
// package (python/xshell/__init__.py) gives it its documented interface
// (README, "Python").
#include <pybind11/pybind11.h>

#include "bindings.hpp"

PYBIND11_MODULE(_core, m) {
  m.doc() = "xshell's engine: relax and design runs and the linkage model (see the package xshell)";
  m.attr("version") = XSHELL_VERSION;
  xshell::python::bind_relax(m);
  xshell::python::bind_linkage(m);
  xshell::python::bind_design(m);
}
