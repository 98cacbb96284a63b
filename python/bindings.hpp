// The parts of the Python module xshell._core (module.cpp).
#pragma once

#include <pybind11/pybind11.h>

namespace xshell::python {

// _core.relax (relax_binding.cpp).
void bind_relax(pybind11::module_& m);

// _core.design (design_binding.cpp).
void bind_design(pybind11::module_& m);

// _core.Linkage (linkage_binding.cpp).
void bind_linkage(pybind11::module_& m);

}  // namespace xshell::python
