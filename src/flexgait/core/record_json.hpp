#pragma once
/// \file record_json.hpp
/// JSON of a record (record.hpp): its fields in declaration order under their keys; enums by
/// name; fields whose FieldInfo says `present = false` are left out.
#include <nlohmann/json.hpp>

#include "flexgait/core/record.hpp"

namespace flexgait {

namespace detail {

struct JsonWriter {
  nlohmann::ordered_json& json;
  template <class T>
  void operator()(std::string_view key, const T& value, const FieldInfo& info) const {
    if (!info.present) return;
    if constexpr (NamedEnum<T>)
      json[std::string(key)] = std::string(name_of(value));
    else if constexpr (std::is_same_v<T, std::optional<std::string>>)
      json[std::string(key)] = value ? nlohmann::ordered_json(*value) : nlohmann::ordered_json(nullptr);
    else
      json[std::string(key)] = value;
  }
};

}  // namespace detail

/// Adds a record's fields to `json` (an object).
template <class R>
void add_record_json(nlohmann::ordered_json& json, const R& record) {
  detail::JsonWriter writer{json};
  R::visit_fields(record, writer);
}

template <class R>
nlohmann::ordered_json record_json(const R& record) {
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
  add_record_json(json, record);
  return json;
}

/// A JSON file's text: two-space indents, keys in the object's order, a final newline (numbers
/// round-trip exactly). Every summary.json of the project is written so.
inline std::string json_file_text(const nlohmann::ordered_json& json) {
  return json.dump(2) + "\n";
}

/// `schema.json`'s entry of a record: {"fields": [{"key", "type", "unit", "doc"[, "choices"]}, ...]}.
template <class R>
nlohmann::ordered_json record_schema_json() {
  nlohmann::ordered_json fields = nlohmann::ordered_json::array();
  for (const auto& f : describe_record<R>()) {
    nlohmann::ordered_json d;
    d["key"] = f.key;
    d["type"] = f.type;
    d["unit"] = f.unit;
    d["doc"] = f.doc;
    if (!f.choices.empty()) d["choices"] = f.choices;
    fields.push_back(std::move(d));
  }
  nlohmann::ordered_json out;
  out["fields"] = std::move(fields);
  return out;
}

}  // namespace flexgait
