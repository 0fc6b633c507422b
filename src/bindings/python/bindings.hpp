#pragma once
/// \file bindings.hpp  The parts of the `flexgait` Python module, each registered by one function.
#include <pybind11/pybind11.h>

#include <string>

#include "flexgait/rimless/poincare.hpp"

namespace flexgait::python {
void bind_rimless(pybind11::module_& m);
/// The Poincaré section named `name` ("touchdown" or "upright"); ValueError naming `section` otherwise.
rimless::Section section_of(const std::string& name);
/// continuation, basin, orbit_diagram, gait_vs_friction, stagnation into flexgait.rimless.
void bind_rimless_maps(pybind11::module_& r);
void bind_humanoid(pybind11::module_& m);
void bind_loop(pybind11::module_& m);
void bind_campaign(pybind11::module_& m);
}  // namespace flexgait::python
