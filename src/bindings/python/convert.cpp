#include "convert.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <charconv>
#include <limits>
#include <vector>

#include "flexgait/core/text.hpp"

namespace flexgait::python {

using namespace pybind11::literals;

namespace {

/// The dict's entries as configuration entries; a nested dict {a: {b: v}} gives the key a.b (as YAML nests).
void add_entries(const py::dict& dict, const std::string& prefix, std::vector<ConfigEntry>& entries) {
  const py::module_ numbers = py::module_::import("numbers");
  for (const auto& [k, v] : dict) {
    if (!py::isinstance<py::str>(k)) throw py::type_error("config keys must be str, e.g. 'rimless.mu_s'");
    const std::string key = prefix + k.cast<std::string>();
    if (py::isinstance<py::dict>(v)) {
      add_entries(v.cast<py::dict>(), key + ".", entries);
      continue;
    }
    std::string text;
    // numbers.Integral / Real: Python's and numpy's (numpy.int64, numpy.float32, ...) alike.
    if (py::isinstance<py::bool_>(v))
      text = v.cast<bool>() ? "true" : "false";
    else if (py::isinstance(v, numbers.attr("Integral")))
      text = py::str(py::int_(py::reinterpret_borrow<py::object>(v)));
    else if (py::isinstance(v, numbers.attr("Real")))
      text = py::repr(py::float_(py::reinterpret_borrow<py::object>(v)));
    else if (py::isinstance<py::str>(v))
      text = v.cast<std::string>();
    else
      throw py::value_error("config key '" + one_line(key) +
                            "': value must be a float, int, bool, str or a dict of them, not " +
                            std::string(py::str(v.get_type().attr("__name__"))));
    entries.push_back({key, text, "config"});
  }
}

}  // namespace

Config make_config(const Schema& schema, const py::object& overrides, const std::optional<std::string>& config_file) {
  std::vector<ConfigEntry> entries;  // each under its own key: a key holding '=' is a key, not a split point
  if (!overrides.is_none()) {
    if (!py::isinstance<py::dict>(overrides)) throw py::type_error("config must be a dict of key: value, or None");
    add_entries(overrides.cast<py::dict>(), "", entries);
  }
  std::optional<std::filesystem::path> file;
  if (config_file) file = *config_file;
  return resolve_config(schema, file, {}, entries);
}

py::dict config_with(const py::object& config, const py::dict& extra) {
  py::dict out;
  if (!config.is_none()) {
    if (!py::isinstance<py::dict>(config)) throw py::type_error("config must be a dict of key: value, or None");
    for (const auto& [k, v] : config.cast<py::dict>()) out[k] = v;
  }
  for (const auto& [k, v] : extra) out[k] = v;
  return out;
}

py::dict csv_columns(const std::string& csv, const std::vector<std::string>& vectors,
                     const std::vector<std::string>& complex_vectors) {
  const std::vector<CsvRecord> records = parse_csv(csv);  // RFC 4180, the writer's own reader
  std::vector<std::string> names;
  std::vector<std::vector<std::string>> cells;
  if (!records.empty()) names = records.front().fields;
  cells.resize(names.size());
  for (std::size_t r = 1; r < records.size(); ++r) {
    const auto& row = records[r].fields;
    for (std::size_t i = 0; i < names.size(); ++i) cells[i].push_back(i < row.size() ? row[i] : "");
  }
  py::dict out;
  const auto among = [](const std::vector<std::string>& list, const std::string& name) {
    return std::find(list.begin(), list.end(), name) != list.end();
  };
  for (std::size_t i = 0; i < names.size(); ++i)
    out[py::str(names[i])] = among(vectors, names[i])           ? vector_rows(cells[i])
                             : among(complex_vectors, names[i]) ? complex_rows(cells[i])
                                                                : typed_column(cells[i]);
  return out;
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double number_or_nan(std::string_view text) {
  double v = kNaN;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  return ec == std::errc() && end == text.data() + text.size() ? v : kNaN;
}

}  // namespace

py::array_t<double> padded_matrix(const std::vector<std::vector<double>>& rows) {
  std::size_t width = 0;
  for (const auto& r : rows) width = std::max(width, r.size());
  py::array_t<double> a({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(width)});
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < width; ++j)
      a.mutable_at(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(j)) = j < rows[i].size() ? rows[i][j] : kNaN;
  return a;
}

py::array_t<double> vector_rows(const std::vector<std::string>& cells) {
  std::vector<std::vector<double>> rows;
  for (const std::string& cell : cells) {
    rows.emplace_back();
    if (!cell.empty())
      for (const std::string& item : split_text(cell, ';')) rows.back().push_back(number_or_nan(item));
  }
  return padded_matrix(rows);
}

py::array complex_rows(const std::vector<std::string>& cells) {
  std::vector<std::vector<std::complex<double>>> rows;
  std::size_t width = 0;
  for (const std::string& cell : cells) {
    rows.emplace_back();
    if (!cell.empty())
      for (const std::string& item : split_text(cell, ';')) {
        const auto colon = item.find(':');
        const std::string_view text(item);
        rows.back().emplace_back(number_or_nan(text.substr(0, colon)),
                                 colon == std::string::npos ? kNaN : number_or_nan(text.substr(colon + 1)));
      }
    width = std::max(width, rows.back().size());
  }
  py::array_t<std::complex<double>> a({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(width)});
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < width; ++j)
      a.mutable_at(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(j)) =
          j < rows[i].size() ? rows[i][j] : std::complex<double>(kNaN, kNaN);
  return a;
}

py::object typed_column(const std::vector<std::string>& cells) {
  std::vector<double> values(cells.size(), std::numeric_limits<double>::quiet_NaN());
  bool numeric = true, boolean = true, any = false, missing = false;
  for (std::size_t r = 0; r < cells.size(); ++r) {
    const std::string& s = cells[r];
    if (s.empty()) {
      missing = true;
      continue;
    }
    any = true;
    boolean = boolean && (s == "true" || s == "false");
    if (numeric) {
      const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), values[r]);
      numeric = ec == std::errc() && end == s.data() + s.size();
    }
  }
  if (any && numeric) {
    py::array_t<double> a(static_cast<py::ssize_t>(values.size()));
    std::copy(values.begin(), values.end(), a.mutable_data());
    return a;
  }
  if (any && boolean) {
    const py::module_ np = py::module_::import("numpy");
    py::list list;
    for (const std::string& s : cells) list.append(s.empty() ? py::object(py::none()) : py::bool_(s == "true"));
    return np.attr("array")(list, "dtype"_a = missing ? np.attr("object_") : np.attr("bool_"));
  }
  return py::cast(cells);
}

py::array complex_array(const std::vector<std::complex<double>>& values) {
  py::array_t<std::complex<double>> a(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), a.mutable_data());
  return a;
}

py::dict table_columns(Table table) {
  py::dict out;
  for (Table::Column& c : table.release()) {
    if (c.kind == Table::Kind::Text) {
      out[py::str(c.name)] = py::cast(c.text);
      continue;
    }
    // The array views the vector, which the capsule owns and frees with the array.
    auto* owned = new std::vector<double>(std::move(c.numbers));
    const py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<double>*>(p); });
    out[py::str(c.name)] = py::array_t<double>(static_cast<py::ssize_t>(owned->size()), owned->data(), free_when_done);
  }
  return out;
}

py::object json_value(const nlohmann::ordered_json& j) {
  switch (j.type()) {
    case nlohmann::ordered_json::value_t::null:
      return py::none();
    case nlohmann::ordered_json::value_t::boolean:
      return py::bool_(j.get<bool>());
    case nlohmann::ordered_json::value_t::number_integer:
      return py::int_(j.get<std::int64_t>());
    case nlohmann::ordered_json::value_t::number_unsigned:
      return py::int_(j.get<std::uint64_t>());
    case nlohmann::ordered_json::value_t::number_float:
      return py::float_(j.get<double>());
    case nlohmann::ordered_json::value_t::string:
      return py::str(j.get_ref<const std::string&>());
    case nlohmann::ordered_json::value_t::array: {
      py::list out;
      for (const auto& item : j) out.append(json_value(item));
      return out;
    }
    case nlohmann::ordered_json::value_t::object: {
      py::dict out;
      for (const auto& [key, value] : j.items()) out[py::str(key)] = json_value(value);
      return out;
    }
    default:
      throw std::logic_error("json_value: a binary or discarded JSON value");
  }
}

py::dict config_dict(const Config& config) {
  py::dict out;
  for (const auto& p : config.schema().params()) {
    switch (p.type) {
      case ParamType::Real:
        out[py::str(p.key)] = config.real(p.key);
        break;
      case ParamType::Integer:
        out[py::str(p.key)] = config.integer(p.key);
        break;
      case ParamType::Boolean:
        out[py::str(p.key)] = config.boolean(p.key);
        break;
      case ParamType::Choice:
        out[py::str(p.key)] = config.choice(p.key);
        break;
      case ParamType::Text:
        out[py::str(p.key)] = config.text(p.key);
        break;
      case ParamType::List:
        out[py::str(p.key)] = format_value(config.list(p.key), p.item_fields);
        break;  // flow YAML
      case ParamType::Reals:
        out[py::str(p.key)] = py::cast(config.reals(p.key));
        break;
    }
  }
  return out;
}

void InterruptCheck::operator()() {
  const auto now = std::chrono::steady_clock::now();
  if (now < next_) return;
  next_ = now + std::chrono::milliseconds(50);
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // made with the GIL held
}

}  // namespace flexgait::python
