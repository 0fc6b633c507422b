#pragma once
/// \file bindings.hpp  The parts of the `flexgait` Python module, each registered by one function.
#include <pybind11/pybind11.h>

namespace flexgait::python {
void bind_rimless(pybind11::module_& m);
void bind_humanoid(pybind11::module_& m);
void bind_loop(pybind11::module_& m);
}  // namespace flexgait::python
