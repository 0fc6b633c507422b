#pragma once
/// \file record.hpp
/// One declaration per record (docs/guide/library.md): a parameter or result struct lists its fields once —
/// key, member, unit, domain, one line of documentation — in the manner of Drake's
/// `Serialize(Archive*)`, and small generic visitors derive the rest: the configuration schema
/// (`schema_of`), the reading of a resolved configuration (`record_from_config`), JSON
/// (record_json.hpp) and the field list of `schema.json`.
///
/// A record R declares
///
///     template <class Self, class Visitor>
///     static void visit_fields(Self& self, Visitor& visit) {
///       visit("rimless.m", self.m, {.unit = "kg", .doc = "total mass", .bounds = positive()});
///       ...
///     }
///
/// Self is R or const R, so the one list serves readers and writers. The order of the calls is
/// the order of the keys in every derived form. The default of a parameter is the struct's own
/// default member initialiser: there is no second copy to drift.
///
/// Field types: double, int, std::int64_t, bool, an enum with a name table (enum_names.hpp),
/// std::string (a parameter of type text: a name or a path) and, for results only, std::optional<std::string> (null
/// when empty) and std::vector<std::string>; std::vector<double> (a parameter of type reals: one or more numbers, each
/// within the bounds); and a list of structured items, std::vector<Item> (a parameter of type list), where Item
/// declares its fields with short names in
///
///     template <class Self, class Visitor>
///     static void visit_item_fields(Self& self, Visitor& visit) {
///       visit("time", self.time, {.unit = "s", .doc = "start", .bounds = non_negative()});
///       visit("force", self.force, {.unit = "N", .doc = "world frame"});  // std::array<double, 3>
///     }
///
/// of the scalar types above or std::array<double, N>. Every field of an item must be given.
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "flexgait/core/config.hpp"
#include "flexgait/core/enum_names.hpp"

namespace flexgait {

/// The domain of a numeric field: from min to max, each end closed or open.
struct Bounds {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_inclusive = true;
  bool max_inclusive = true;
};
/// [a, b]
constexpr Bounds closed(double a, double b) {
  return {a, b, true, true};
}
/// (a, b]
constexpr Bounds left_open(double a, double b) {
  return {a, b, false, true};
}
/// [a, b)
constexpr Bounds right_open(double a, double b) {
  return {a, b, true, false};
}
/// (a, b)
constexpr Bounds open(double a, double b) {
  return {a, b, false, false};
}
/// [a, ∞)
constexpr Bounds at_least(double a) {
  return {a, std::numeric_limits<double>::infinity(), true, true};
}
/// (a, ∞)
constexpr Bounds above(double a) {
  return {a, std::numeric_limits<double>::infinity(), false, true};
}
/// (0, ∞)
constexpr Bounds positive() {
  return above(0.0);
}
/// [0, ∞)
constexpr Bounds non_negative() {
  return at_least(0.0);
}

/// What a record says about one of its fields.
struct FieldInfo {
  std::string_view unit{};     ///< SI unit; "" when dimensionless
  std::string_view doc{};      ///< one line: what it is
  Bounds bounds{};             ///< allowed values of a parameter
  bool present = true;         ///< results: false when the field does not apply to this value (left out of JSON)
  std::string_view derived{};  ///< a parameter derived unless set (ParamSpec::derived): how
  bool optional = false;       ///< a field of a List item that may be left out (ParamSpec::optional)
};

namespace detail {

template <class T>
inline constexpr bool kAlwaysFalse = false;

template <class T>
struct IsDoubleArray : std::false_type {};
template <std::size_t N>
struct IsDoubleArray<std::array<double, N>> : std::true_type {};

template <class T>
ParamSpec param_spec(std::string_view key, const T& value, const FieldInfo& info);

/// The field specs of a list's item (keys: the field names; std::array<double, N>: length N).
struct ItemSpecBuilder {
  std::vector<ParamSpec>& fields;
  template <class T>
  void operator()(std::string_view name, const T& value, const FieldInfo& info) {
    if constexpr (IsDoubleArray<T>::value) {
      fields.push_back(param_spec(name, value[0], info));
      fields.back().length = static_cast<int>(value.size());
    } else {
      fields.push_back(param_spec(name, value, info));
    }
  }
};

/// An item's fields as configuration values, in declaration order.
struct ItemWriter {
  std::vector<std::vector<ConfigScalar>>& fields;
  template <class T>
  void operator()(std::string_view, const T& value, const FieldInfo&) {
    std::vector<ConfigScalar> values;
    if constexpr (IsDoubleArray<T>::value) {
      for (const double v : value) values.emplace_back(v);
    } else if constexpr (std::is_same_v<T, bool>) {
      values.emplace_back(value);
    } else if constexpr (NamedEnum<T>) {
      values.emplace_back(std::string(name_of(value)));
    } else if constexpr (std::is_integral_v<T>) {
      values.emplace_back(static_cast<std::int64_t>(value));
    } else if constexpr (std::is_floating_point_v<T>) {
      values.emplace_back(static_cast<double>(value));
    } else {
      values.emplace_back(std::string(value));
    }
    fields.push_back(std::move(values));
  }
};

/// An item's fields from configuration values (checked against ItemSpecBuilder's specs).
struct ItemReader {
  const std::vector<std::vector<ConfigScalar>>& fields;
  std::size_t next = 0;
  template <class T>
  void operator()(std::string_view name, T& member, const FieldInfo&) {
    const std::vector<ConfigScalar>& values = fields.at(next++);
    if constexpr (IsDoubleArray<T>::value) {
      for (std::size_t i = 0; i < member.size(); ++i) member[i] = std::get<double>(values.at(i));
    } else if constexpr (std::is_same_v<T, bool>) {
      member = std::get<bool>(values.at(0));
    } else if constexpr (NamedEnum<T>) {
      const auto value = enum_from_name<T>(std::get<std::string>(values.at(0)));
      if (!value) throw std::logic_error("list item field " + std::string(name) + " holds a name outside its enum");
      member = *value;
    } else if constexpr (std::is_integral_v<T>) {
      member = static_cast<T>(std::get<std::int64_t>(values.at(0)));
    } else if constexpr (std::is_floating_point_v<T>) {
      member = std::get<double>(values.at(0));
    } else {
      member = std::get<std::string>(values.at(0));
    }
  }
};

/// A list of structured items: std::vector<Item> whose Item declares visit_item_fields.
template <class T>
struct IsItemList : std::false_type {};
template <class Item>
requires requires(const Item& item, ItemSpecBuilder& b) {
  Item::visit_item_fields(item, b);
}
struct IsItemList<std::vector<Item>> : std::true_type {};

template <class Item>
std::vector<ParamSpec> item_fields_of() {
  std::vector<ParamSpec> fields;
  ItemSpecBuilder builder{fields};
  const Item item{};
  Item::visit_item_fields(item, builder);
  return fields;
}

template <class Item>
ConfigList config_list_of(const std::vector<Item>& items) {
  ConfigList list;
  for (const Item& item : items) {
    ItemWriter writer{list.items.emplace_back()};
    Item::visit_item_fields(item, writer);
  }
  return list;
}

/// The configuration parameter of one field.
template <class T>
ParamSpec param_spec(std::string_view key, const T& value, const FieldInfo& info) {
  ParamSpec p;
  p.key = std::string(key);
  p.unit = std::string(info.unit);
  p.doc = std::string(info.doc);
  p.derived = std::string(info.derived);
  p.optional = info.optional;
  p.min = info.bounds.min;
  p.max = info.bounds.max;
  p.min_inclusive = info.bounds.min_inclusive;
  p.max_inclusive = info.bounds.max_inclusive;
  if constexpr (std::is_same_v<T, bool>) {
    p.type = ParamType::Boolean;
    p.fallback = value ? "true" : "false";
  } else if constexpr (NamedEnum<T>) {
    p.type = ParamType::Choice;
    p.fallback = std::string(name_of(value));
    p.choices = enum_name_list<T>();
  } else if constexpr (std::is_integral_v<T>) {
    p.type = ParamType::Integer;
    p.fallback = format_value(static_cast<std::int64_t>(value));
  } else if constexpr (std::is_floating_point_v<T>) {
    p.type = ParamType::Real;
    p.fallback = format_value(static_cast<double>(value));
  } else if constexpr (std::is_same_v<T, std::string>) {
    p.type = ParamType::Text;
    p.fallback = value;
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    p.type = ParamType::Reals;
    p.fallback = format_value(value);
  } else if constexpr (IsItemList<T>::value) {
    p.type = ParamType::List;
    p.item_fields = item_fields_of<typename T::value_type>();
    p.fallback = format_value(config_list_of(value), p.item_fields);
  } else {
    static_assert(kAlwaysFalse<T>, "a configuration field must be a number, a bool or a named enum");
  }
  return p;
}

struct SchemaBuilder {
  Schema& schema;
  template <class T>
  void operator()(std::string_view key, const T& value, const FieldInfo& info) {
    schema.add(param_spec(key, value, info));
  }
};

struct ConfigReader {
  const Config& config;
  template <class T>
  void operator()(std::string_view key, T& member, const FieldInfo&) const {
    const std::string k(key);
    if constexpr (std::is_same_v<T, bool>) {
      member = config.boolean(k);
    } else if constexpr (NamedEnum<T>) {
      const auto value = enum_from_name<T>(config.choice(k));
      if (!value) throw std::logic_error("configuration key " + k + " holds a name outside its enum");
      member = *value;
    } else if constexpr (std::is_integral_v<T>) {
      member = static_cast<T>(config.integer(k));
    } else if constexpr (std::is_floating_point_v<T>) {
      member = config.real(k);
    } else if constexpr (std::is_same_v<T, std::string>) {
      member = config.text(k);
    } else if constexpr (std::is_same_v<T, std::vector<double>>) {
      member = config.reals(k);
    } else if constexpr (IsItemList<T>::value) {
      member.clear();
      for (const auto& fields : config.list(k).items) {
        ItemReader reader{fields};
        T::value_type::visit_item_fields(member.emplace_back(), reader);
      }
    } else {
      static_assert(kAlwaysFalse<T>, "a configuration field must be a number, a bool or a named enum");
    }
  }
};

}  // namespace detail

/// The configuration keys of a parameter record, with the defaults of `defaults`.
template <class R>
Schema schema_of(const R& defaults = R{}) {
  Schema s;
  detail::SchemaBuilder builder{s};
  R::visit_fields(defaults, builder);
  return s;
}

/// Reads a record's fields from a resolved configuration whose schema includes schema_of<R>();
/// fields the record does not list keep the values of `base`.
template <class R>
R record_from_config(const Config& config, R base = R{}) {
  detail::ConfigReader reader{config};
  R::visit_fields(base, reader);
  return base;
}

/// One field of a record as `schema.json` describes it.
struct FieldDescription {
  std::string key;
  std::string type;  ///< real, integer, boolean, choice, text, list, list of real
  std::string unit;
  std::string doc;
  std::vector<std::string> choices;  ///< for choice
};

namespace detail {

struct Describer {
  std::vector<FieldDescription>& out;
  template <class T>
  void operator()(std::string_view key, const T&, const FieldInfo& info) {
    FieldDescription d{std::string(key), "", std::string(info.unit), std::string(info.doc), {}};
    if constexpr (std::is_same_v<T, bool>) {
      d.type = "boolean";
    } else if constexpr (NamedEnum<T>) {
      d.type = "choice";
      d.choices = enum_name_list<T>();
    } else if constexpr (std::is_integral_v<T>) {
      d.type = "integer";
    } else if constexpr (std::is_floating_point_v<T>) {
      d.type = "real";
    } else if constexpr (std::is_same_v<T, std::string>) {
      d.type = "text";
    } else if constexpr (std::is_same_v<T, std::optional<std::string>>) {
      d.type = "text or null";
    } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
      d.type = "list of text";
    } else if constexpr (std::is_same_v<T, std::vector<double>>) {
      d.type = "list of real";
    } else if constexpr (IsItemList<T>::value) {
      d.type = "list";
    } else {
      static_assert(kAlwaysFalse<T>, "unsupported record field type");
    }
    out.push_back(std::move(d));
  }
};

}  // namespace detail

namespace detail {

struct KeyFinder {
  const void* target;
  std::string key;
  template <class T>
  void operator()(std::string_view k, const T& field, const FieldInfo&) {
    if (static_cast<const void*>(&field) == target) key = k;
  }
};

}  // namespace detail

/// The key record R declares for its data member `member` (R::visit_fields): code that names a
/// field through its member, e.g. field_key(&WalkMetrics::fell) == "fell", cannot misspell it.
/// Throws std::logic_error when the member is not a declared field (a programming error).
template <class R, class T>
std::string field_key(T R::*member) {
  const R r{};
  detail::KeyFinder find{&(r.*member), {}};
  R::visit_fields(r, find);
  if (find.key.empty()) throw std::logic_error("field_key: the member is not a declared field of its record");
  return find.key;
}

/// Every field a record can hold (whether or not a given value holds it), in declaration order.
template <class R>
std::vector<FieldDescription> describe_record() {
  std::vector<FieldDescription> out;
  detail::Describer d{out};
  const R r{};
  R::visit_fields(r, d);
  return out;
}

}  // namespace flexgait
