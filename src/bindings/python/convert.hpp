#pragma once
/// \file convert.hpp
/// The bindings' conversions: a Python dict of overrides → a validated Config (the command line's
/// rules and errors), a table → a dict of numpy arrays, a JSON text → Python objects. One source
/// for each table: the arrays a Python user gets hold the numbers of the same rows the command
/// line writes as CSV — from a Table (core/table.hpp) built by the writer's own row code, or from
/// the CSV text parsed back exactly (shortest round-trip formatting) — so both agree to the last
/// digit.
#include <pybind11/pybind11.h>

#include <chrono>
#include <optional>
#include <string>

#include "flexgait/core/config.hpp"
#include "flexgait/core/table.hpp"

namespace flexgait::python {

namespace py = pybind11;

/// Defaults, then the YAML file `config_file` (if given), then `overrides` (a dict key → value,
/// or None). Raises ValueError naming the key for an unknown key or a bad value.
Config make_config(const Schema& schema, const py::object& overrides, const std::optional<std::string>& config_file);

/// {column name: numpy float64 array} for numeric columns, {name: list of str} for the others.
py::dict csv_columns(const std::string& csv);

/// The same dict from a Table, without text: each numeric column becomes a numpy float64 array
/// that owns the table's own vector (no copy), each text column a list of str.
py::dict table_columns(Table table);

/// Ctrl-C in a long call. Called often from C++ that runs with the GIL released (a progress hook,
/// a sweep's loop), it takes the GIL for PyErr_CheckSignals at most every 50 ms of wall time (a
/// clock read otherwise); if a signal handler raised (KeyboardInterrupt), it throws
/// py::error_already_set, which unwinds the C++ call back to Python with that exception. One
/// object per call, used by its thread only.
class InterruptCheck {
 public:
  void operator()();

 private:
  std::chrono::steady_clock::time_point next_ = std::chrono::steady_clock::now();
};

/// json.loads(text).
py::object json_value(const std::string& text);

/// The resolved configuration as a dict key → value (float, int, bool or str).
py::dict config_dict(const Config& config);

}  // namespace flexgait::python
