#pragma once
/// \file convert.hpp
/// The bindings' conversions: a Python dict of overrides → a validated Config (the command line's
/// rules and errors), a table → a dict of numpy arrays, a JSON text → Python objects. One source
/// for each table: the arrays a Python user gets hold the numbers of the same rows the command
/// line writes as CSV — from a Table (core/table.hpp) built by the writer's own row code, or from
/// the CSV text parsed back exactly (shortest round-trip formatting) — so both agree to the last
/// digit.
#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <chrono>
#include <complex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "flexgait/core/config.hpp"
#include "flexgait/core/table.hpp"

namespace flexgait::python {

namespace py = pybind11;

/// Defaults, then the YAML file `config_file` (if given), then `overrides` (a dict key → value,
/// or None). Raises ValueError naming the key for an unknown key or a bad value.
Config make_config(const Schema& schema, const py::object& overrides, const std::optional<std::string>& config_file);

/// A new dict: the entries of `config` (None or a dict, which is left unchanged) and over them
/// `extra`'s (keys a function's own arguments set). TypeError naming `config` if it is not a dict.
py::dict config_with(const py::object& config, const py::dict& extra);

/// {column name: typed_column(its cells)} of a CSV text with a header; the columns named in
/// `vectors` (each cell numbers joined by ';', e.g. a section state) as vector_rows, those in
/// `complex_vectors` (each cell re:im pairs joined by ';', e.g. Floquet multipliers) as complex_rows.
py::dict csv_columns(const std::string& csv, const std::vector<std::string>& vectors = {},
                     const std::vector<std::string>& complex_vectors = {});

/// Cells of numbers joined by ';' as a 2-D float64 array, one row per cell, NaN-padded to the
/// longest (a state's dimension depends on its mode; an empty cell, a point without one, is all NaN).
py::array_t<double> vector_rows(const std::vector<std::string>& cells);

/// Cells of "re:im" pairs joined by ';' as a 2-D complex128 array, one row per cell, NaN-padded.
py::array complex_rows(const std::vector<std::string>& cells);

/// Rows of different lengths as a 2-D float64 array, NaN-padded to the longest.
py::array_t<double> padded_matrix(const std::vector<std::vector<double>>& rows);

/// One column's cells, typed: numbers (an empty cell: a point that failed or has no value) as a
/// float64 array with NaN there; true/false as a numpy bool array (an object array with None at
/// the empty cells); anything else (and a column of empty cells only) as a list of str.
py::object typed_column(const std::vector<std::string>& cells);

/// The values as a numpy complex128 array (Floquet multipliers).
py::array complex_array(const std::vector<std::complex<double>>& values);

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

/// A record (nlohmann JSON) as Python values, as json.loads reads its text: None, bool, int,
/// float, str, list, dict (keys in the record's order).
py::object json_value(const nlohmann::ordered_json& record);

/// The resolved configuration as a dict key → value (float, int, bool or str).
py::dict config_dict(const Config& config);

}  // namespace flexgait::python
