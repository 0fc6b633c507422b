#pragma once
/// \file convert.hpp
/// The bindings' conversions: a Python dict of overrides → a validated Config (the command line's
/// rules and errors), a table → a dict of numpy arrays, a JSON text → Python objects. One source
/// for each table: the arrays a Python user gets hold the numbers of the same rows the command
/// line writes as CSV — from a Table (core/table.hpp) built by the writer's own row code, or from
/// the CSV text parsed back exactly (shortest round-trip formatting) — so both agree to the last
/// digit.
#include <pybind11/pybind11.h>

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

/// json.loads(text).
py::object json_value(const std::string& text);

/// The resolved configuration as a dict key → value (float, int, bool or str).
py::dict config_dict(const Config& config);

}  // namespace flexgait::python
