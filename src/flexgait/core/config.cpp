#include "flexgait/core/config.hpp"

#include <yaml-cpp/yaml.h>

#include <fmt/format.h>
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>
#include <string_view>

#include "flexgait/core/config_file.hpp"
#include "flexgait/core/text.hpp"

namespace flexgait {
namespace {

std::string bound_text(double v) {
  return fmt::format("{}", v);
}

// "time, body, force, duration": the fields of a List's items.
std::string field_names(const ParamSpec& list) {
  std::string s;
  for (std::size_t i = 0; i < list.item_fields.size(); ++i) s += (i ? ", " : "") + list.item_fields[i].key;
  return s;
}

std::string error_text(const std::string& origin, const std::string& key, const std::string& value,
                       const std::string& problem, const ParamSpec* spec) {
  std::string msg = fmt::format("{}: key '{}' = '{}': {}", origin, one_line(key), one_line(value), problem);
  if (spec != nullptr) {
    msg += fmt::format("; allowed: {}", spec->allowed());
    if (!spec->unit.empty()) msg += fmt::format(" ({})", spec->unit);
  }
  return msg;
}

bool parse_double(const std::string& text, double& out) {
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (first != last && *first == '+') ++first;
  auto [ptr, ec] = std::from_chars(first, last, out);
  return ec == std::errc() && ptr == last;
}

bool parse_int(const std::string& text, std::int64_t& out) {
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (first != last && *first == '+') ++first;
  auto [ptr, ec] = std::from_chars(first, last, out);
  return ec == std::errc() && ptr == last;
}

void check_range(const ParamSpec& spec, double v, const std::string& text, const std::string& origin) {
  const bool low_ok = spec.min_inclusive ? v >= spec.min : v > spec.min;
  const bool high_ok = spec.max_inclusive ? v <= spec.max : v < spec.max;
  if (!low_ok || !high_ok) throw ConfigError(spec.key, error_text(origin, spec.key, text, "out of range", &spec));
}

// Levenshtein distance, letters compared without case (a name typed as rimless.k is rimless.K).
std::size_t edit_distance(std::string_view a, std::string_view b) {
  const auto same = [](char x, char y) {
    return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
  };
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (same(a[i - 1], b[j - 1]) ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string_view leaf(std::string_view key) {
  const std::size_t dot = key.rfind('.');
  return dot == std::string_view::npos ? key : key.substr(dot + 1);
}

// How far `candidate` is from the mistyped `key`, or nothing if it is no plausible meaning of it.
// The whole names may differ in up to 3 edits, and the last components (the quantity's own name)
// in at most half the shorter one's letters: a one-letter name is offered only for a case
// difference, so rimless.mu never suggests rimless.m, the mass. A last component that begins
// with the typed one and an underscore (mu -> mu_s) is offered too.
std::optional<std::size_t> nearness(const std::string& key, const std::string& candidate) {
  const std::size_t whole = edit_distance(key, candidate);
  if (whole > 3) return std::nullopt;
  const std::string_view typed = leaf(key), named = leaf(candidate);
  const std::size_t last = edit_distance(typed, named);
  if (2 * last <= std::min(typed.size(), named.size())) return whole;
  if (named.size() > typed.size() + 1 && named[typed.size()] == '_' &&
      edit_distance(named.substr(0, typed.size()), typed) == 0)
    return whole;
  return std::nullopt;
}

// " (did you mean 'rimless.K'?)" for a near miss (the nearest names, aliases included), else
// a pointer to the list of keys.
std::string suggestion(const Schema& schema, const std::string& key) {
  const std::string fallback = "; `flexgait schema` lists every key";
  if (key.size() > 100) return fallback;  // no key is that long; spare the quadratic distance
  std::vector<std::string> names;
  for (const auto& p : schema.params()) names.push_back(p.key);
  for (const auto& a : schema.aliases()) names.push_back(a.key);
  std::vector<std::string> best;
  std::size_t best_d = std::numeric_limits<std::size_t>::max();
  for (const auto& name : names) {
    const auto d = nearness(key, name);
    if (!d || *d > best_d) continue;
    if (*d < best_d) best.clear();
    best_d = *d;
    best.push_back(name);
  }
  if (best.empty()) return fallback;
  std::string s;
  for (std::size_t i = 0; i < best.size() && i < 3; ++i)
    s += fmt::format("{}'{}'", i == 0 ? "" : (i + 1 == std::min<std::size_t>(best.size(), 3) ? " or " : ", "), best[i]);
  return fmt::format(" (did you mean {}?)", s);
}

}  // namespace

std::string ParamSpec::allowed() const {
  if (!derived.empty()) {
    ParamSpec one = *this;
    one.derived.clear();
    return one.allowed() + ", or auto (" + derived + ")";
  }
  if (length > 0) {
    ParamSpec one = *this;
    one.length = 0;
    return fmt::format("a list of {} values, each {}", length, one.allowed());
  }
  switch (type) {
    case ParamType::List:
      return "a list of mappings, each with the fields " + field_names(*this);
    case ParamType::Reals: {
      ParamSpec one = *this;
      one.type = ParamType::Real;
      return "a list [a, b, ...] of one or more values, each " + one.allowed();
    }
    case ParamType::Boolean:
      return "true or false";
    case ParamType::Text:
      return "a non-empty text without control characters";
    case ParamType::Choice: {
      std::string s = "one of ";
      for (std::size_t i = 0; i < choices.size(); ++i) s += (i ? ", " : "") + choices[i];
      return s;
    }
    case ParamType::Real:
    case ParamType::Integer: {
      const std::string what = type == ParamType::Real ? "a finite real number" : "an integer";
      const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
      if (has_min && has_max)
        return fmt::format("{} in {}{}, {}{}", what, min_inclusive ? "[" : "(", bound_text(min), bound_text(max),
                           max_inclusive ? "]" : ")");
      if (has_min) return fmt::format("{} {} {}", what, min_inclusive ? ">=" : ">", bound_text(min));
      if (has_max) return fmt::format("{} {} {}", what, max_inclusive ? "<=" : "<", bound_text(max));
      return what;
    }
  }
  return {};
}

ParamSpec real_param(std::string key, std::string fallback, std::string unit, std::string doc, double min, double max,
                     bool min_inclusive, bool max_inclusive) {
  ParamSpec p;
  p.key = std::move(key);
  p.type = ParamType::Real;
  p.fallback = std::move(fallback);
  p.unit = std::move(unit);
  p.doc = std::move(doc);
  p.min = min;
  p.max = max;
  p.min_inclusive = min_inclusive;
  p.max_inclusive = max_inclusive;
  return p;
}

ParamSpec integer_param(std::string key, std::string fallback, std::string doc, double min, double max) {
  ParamSpec p = real_param(std::move(key), std::move(fallback), "", std::move(doc), min, max);
  p.type = ParamType::Integer;
  return p;
}

ParamSpec text_param(std::string key, std::string fallback, std::string doc) {
  ParamSpec p;
  p.key = std::move(key);
  p.type = ParamType::Text;
  p.fallback = std::move(fallback);
  p.doc = std::move(doc);
  return p;
}

ParamSpec choice_param(std::string key, std::string fallback, std::string doc, std::vector<std::string> choices) {
  ParamSpec p = text_param(std::move(key), std::move(fallback), std::move(doc));
  p.type = ParamType::Choice;
  p.choices = std::move(choices);
  return p;
}

ParamSpec boolean_param(std::string key, std::string fallback, std::string doc) {
  ParamSpec p = text_param(std::move(key), std::move(fallback), std::move(doc));
  p.type = ParamType::Boolean;
  return p;
}

Schema& Schema::add(ParamSpec spec) {
  if (find(spec.key) != nullptr || find_alias(spec.key) != nullptr)
    throw std::logic_error("duplicate configuration key " + spec.key);
  parse_value(spec, spec.fallback, "default");  // a default outside its own domain is a bug
  params_.push_back(std::move(spec));
  return *this;
}

Schema& Schema::alias(std::string key, std::vector<std::string> parts, std::string doc) {
  if (find(key) != nullptr || find_alias(key) != nullptr) throw std::logic_error("duplicate configuration key " + key);
  if (parts.empty()) throw std::logic_error("an alias of no key: " + key);
  for (const auto& part : parts) {
    const ParamSpec* p = find(part);
    if (p == nullptr || p->type != find(parts.front())->type)
      throw std::logic_error("alias " + key + " of an unknown key or of keys of different types: " + part);
  }
  aliases_.push_back({std::move(key), std::move(parts), std::move(doc)});
  return *this;
}

Schema& Schema::merge(const Schema& other) {
  for (const auto& p : other.params()) add(p);
  for (const auto& a : other.aliases()) alias(a.key, a.parts, a.doc);
  return *this;
}

const ParamAlias* Schema::find_alias(const std::string& key) const {
  for (const auto& a : aliases_)
    if (a.key == key) return &a;
  return nullptr;
}

const ParamSpec* Schema::find(const std::string& key) const {
  for (const auto& p : params_)
    if (p.key == key) return &p;
  return nullptr;
}

namespace {

// True if `key` occurs in `text` as a whole dotted name (not inside a longer one).
bool mentions(const std::string& text, const std::string& key) {
  auto part_of_name = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '.'; };
  for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + 1)) {
    const bool starts = at == 0 || !part_of_name(text[at - 1]);
    const std::size_t end = at + key.size();
    const bool ends = end == text.size() || !part_of_name(text[end]) || (text[end] == '.' && end + 1 == text.size());
    if (starts && ends) return true;
  }
  return false;
}

}  // namespace

void check_with_origin(const Config& config, const std::function<void()>& check) {
  try {
    check();
  } catch (const ConfigError& e) {
    if (e.key().empty() || config.schema().find(e.key()) == nullptr) throw;
    // The blamed key's origin in front; every other key the message names, with its own origin
    // where that differs (a file's value checked against a --set one: both places are named). A
    // default is blamed on the value given against it: --set rimless.mu_s=0.1 against the default
    // rimless.mu_k leads with "--set:" and says that rimless.mu_k is a default.
    std::string blamed = config.origin(e.key());
    std::string others;
    const std::string what = e.what();
    std::vector<const ParamSpec*> named;
    for (const ParamSpec& p : config.schema().params())
      if (p.key == e.key() || mentions(what, p.key)) named.push_back(&p);
    if (blamed == "default")
      for (const ParamSpec* p : named)
        if (config.origin(p->key) != "default") {
          blamed = config.origin(p->key);
          break;
        }
    for (const ParamSpec* p : named) {
      if (config.origin(p->key) == blamed) continue;
      others += fmt::format("{}{} from {}", others.empty() ? "" : "; ", p->key, config.origin(p->key));
    }
    if (blamed == "default") blamed = "the defaults";
    throw ConfigError(e.key(), blamed + ": " + what + (others.empty() ? "" : " (" + others + ")"));
  }
}

namespace {

ConfigScalar scalar_of(const ConfigValue& value) {
  return std::visit(
      [](const auto& v) -> ConfigScalar {
        using V = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<V, ConfigList> || std::is_same_v<V, std::vector<double>>)
          throw std::logic_error("a list item's field holds a list value");
        else
          return v;
      },
      value);
}

// One item of a List (ParamType::List): every field of spec.item_fields, each checked against its
// own spec under the key `key[i].field`.
std::vector<std::vector<ConfigScalar>> parse_item(const ParamSpec& spec, std::size_t i,
                                                  const std::vector<ItemFieldText>& item, const std::string& origin) {
  const std::string item_key = fmt::format("{}[{}]", spec.key, i);
  for (const ItemFieldText& f : item) {
    const bool known = std::any_of(spec.item_fields.begin(), spec.item_fields.end(),
                                   [&](const ParamSpec& p) { return p.key == f.name; });
    if (!known) {
      const std::string key = item_key + "." + f.name;
      throw ConfigError(key, fmt::format("{}: unknown key '{}'; an item of {} has the fields {}", origin, one_line(key),
                                         spec.key, field_names(spec)));
    }
  }
  std::vector<std::vector<ConfigScalar>> fields;
  for (const ParamSpec& field : spec.item_fields) {
    ParamSpec named = field;
    named.key = item_key + "." + field.key;
    const auto given =
        std::find_if(item.begin(), item.end(), [&](const ItemFieldText& f) { return f.name == field.key; });
    if (given == item.end() && field.optional) {
      if (field.length != 0) throw std::logic_error("an optional list item field holds one value");
      named.length = 0;
      fields.push_back({scalar_of(parse_value(named, field.fallback, origin))});
      continue;
    }
    if (given == item.end())
      throw ConfigError(named.key, fmt::format("{}: key '{}' missing; allowed: {}{}", origin, named.key,
                                               named.allowed(), named.unit.empty() ? "" : " (" + named.unit + ")"));
    std::string shown = given->values.empty() ? "" : given->values[0];
    if (given->list) {
      shown = "[";
      for (std::size_t j = 0; j < given->values.size(); ++j) shown += (j ? ", " : "") + given->values[j];
      shown += "]";
    }
    const bool shape_ok = field.length == 0
                              ? !given->list
                              : given->list && given->values.size() == static_cast<std::size_t>(field.length);
    if (!shape_ok)
      throw ConfigError(named.key, error_text(origin, named.key, shown,
                                              field.length == 0 ? "a list where one value belongs"
                                                                : fmt::format("not a list of {} values", field.length),
                                              &named));
    named.length = 0;
    std::vector<ConfigScalar> values;
    for (const std::string& v : given->values) values.push_back(scalar_of(parse_value(named, v, origin)));
    fields.push_back(std::move(values));
  }
  return fields;
}

// The text without the blanks at either end.
std::string_view trimmed(std::string_view text) {
  const auto blank = [](char c) { return c == ' ' || c == '\t'; };
  while (!text.empty() && blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && blank(text.back())) text.remove_suffix(1);
  return text;
}

// A Reals value: flow YAML `[a, b, ...]` of plain numbers, one or more, each checked as a Real
// under the key `key[i]`.
std::vector<double> parse_reals(const ParamSpec& spec, const std::string& text, const std::string& origin) {
  const std::string_view all = trimmed(text);
  if (all.size() < 2 || all.front() != '[' || all.back() != ']')
    throw ConfigError(spec.key, error_text(origin, spec.key, text, "not a list in brackets", &spec));
  const std::string_view inner = trimmed(all.substr(1, all.size() - 2));
  if (inner.empty()) throw ConfigError(spec.key, error_text(origin, spec.key, text, "an empty list", &spec));
  ParamSpec item = spec;
  item.type = ParamType::Real;
  std::vector<double> values;
  for (const std::string& field : split_text(inner, ',')) {
    item.key = fmt::format("{}[{}]", spec.key, values.size());
    values.push_back(std::get<double>(parse_value(item, std::string(trimmed(field)), origin)));
  }
  return values;
}

}  // namespace

ConfigValue parse_value(const ParamSpec& spec, const std::string& text, const std::string& origin) {
  switch (spec.type) {
    case ParamType::Reals:
      return parse_reals(spec, text, origin);
    case ParamType::List: {
      std::vector<std::vector<ItemFieldText>> items;
      try {
        items = parse_list_text(text);
      } catch (const ConfigError& e) {
        throw ConfigError(spec.key, error_text(origin, spec.key, text, e.what(), &spec));
      }
      ConfigList list;
      for (std::size_t i = 0; i < items.size(); ++i) list.items.push_back(parse_item(spec, i, items[i], origin));
      return list;
    }
    case ParamType::Real: {
      double v = 0;
      if (!parse_double(text, v))
        throw ConfigError(spec.key, error_text(origin, spec.key, text, "not a number", &spec));
      if (!std::isfinite(v)) throw ConfigError(spec.key, error_text(origin, spec.key, text, "not finite", &spec));
      check_range(spec, v, text, origin);
      return v;
    }
    case ParamType::Integer: {
      std::int64_t v = 0;
      if (!parse_int(text, v)) throw ConfigError(spec.key, error_text(origin, spec.key, text, "not an integer", &spec));
      check_range(spec, static_cast<double>(v), text, origin);
      return v;
    }
    case ParamType::Boolean:
      if (text == "true") return true;
      if (text == "false") return false;
      throw ConfigError(spec.key, error_text(origin, spec.key, text, "not a boolean", &spec));
    case ParamType::Choice:
      for (const auto& c : spec.choices)
        if (c == text) return text;
      throw ConfigError(spec.key, error_text(origin, spec.key, text, "not an allowed value", &spec));
    case ParamType::Text:
      if (text.empty() || std::any_of(text.begin(), text.end(),
                                      [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
        throw ConfigError(spec.key,
                          error_text(origin, spec.key, text, "not a one-line text without control characters", &spec));
      return text;
  }
  throw std::logic_error("unhandled parameter type");
}

namespace {

ConfigValue value_of(const ConfigScalar& scalar) {
  return std::visit([](const auto& v) -> ConfigValue { return v; }, scalar);
}

// A List value as YAML: flow items (`{time: 4.1, force: [0.0, 120.0, 0.0]}`) in a flow or block list.
void emit_list(YAML::Emitter& out, const ConfigList& list, const std::vector<ParamSpec>& item_fields) {
  out << YAML::BeginSeq;
  for (const auto& item : list.items) {
    if (item.size() != item_fields.size()) throw std::logic_error("a list item does not match its fields");
    out << YAML::Flow << YAML::BeginMap;
    for (std::size_t f = 0; f < item.size(); ++f) {
      if (item_fields[f].optional && format_value(value_of(item[f].at(0))) == item_fields[f].fallback) continue;
      out << YAML::Key << item_fields[f].key << YAML::Value;
      if (item_fields[f].length == 0) {
        out << format_value(value_of(item[f].at(0)));
      } else {
        out << YAML::Flow << YAML::BeginSeq;
        for (const ConfigScalar& v : item[f]) out << format_value(value_of(v));
        out << YAML::EndSeq;
      }
    }
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

}  // namespace

std::string format_value(const ConfigValue& value, const std::vector<ParamSpec>& item_fields) {
  if (const auto* list = std::get_if<ConfigList>(&value)) {
    YAML::Emitter out;
    out << YAML::Flow;
    emit_list(out, *list, item_fields);
    return out.c_str();
  }
  struct Visitor {
    std::string operator()(double v) const {
      std::string s = fmt::format("{}", v);  // shortest text that round-trips
      if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
      return s;
    }
    std::string operator()(std::int64_t v) const { return fmt::format("{}", v); }
    std::string operator()(bool v) const { return v ? "true" : "false"; }
    std::string operator()(const std::string& v) const { return v; }
    std::string operator()(const ConfigList&) const { return {}; }  // (above)
    std::string operator()(const std::vector<double>& v) const {
      std::string s = "[";
      for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + (*this)(v[i]);
      return s + "]";
    }
  };
  return std::visit(Visitor{}, value);
}

const ConfigValue& Config::value(const std::string& key, ParamType expected) const {
  const ParamSpec* spec = schema_.find(key);
  if (spec == nullptr) throw std::logic_error("no configuration key " + key);
  if (spec->type != expected) throw std::logic_error("configuration key " + key + " read with the wrong type");
  return values_.at(key);
}

double Config::real(const std::string& key) const {
  return std::get<double>(value(key, ParamType::Real));
}
std::int64_t Config::integer(const std::string& key) const {
  return std::get<std::int64_t>(value(key, ParamType::Integer));
}
bool Config::boolean(const std::string& key) const {
  return std::get<bool>(value(key, ParamType::Boolean));
}
const std::string& Config::choice(const std::string& key) const {
  return std::get<std::string>(value(key, ParamType::Choice));
}
const std::string& Config::text(const std::string& key) const {
  return std::get<std::string>(value(key, ParamType::Text));
}
const ConfigList& Config::list(const std::string& key) const {
  return std::get<ConfigList>(value(key, ParamType::List));
}
const std::vector<double>& Config::reals(const std::string& key) const {
  return std::get<std::vector<double>>(value(key, ParamType::Reals));
}
const std::string& Config::origin(const std::string& key) const {
  return origins_.at(key);
}

void Config::set(const std::string& key, const std::string& text, const std::string& origin, bool list) {
  if (const ParamAlias* alias = schema_.find_alias(key)) {
    ParamSpec named = *schema_.find(alias->parts.front());  // a bad value is named under the alias
    named.key = alias->key;
    parse_value(named, text, origin);
    for (const std::string& part : alias->parts) set(part, text, origin, list);
    return;
  }
  const ParamSpec* spec = schema_.find(key);
  if (spec == nullptr)
    throw ConfigError(key, fmt::format("{}: unknown key '{}' (value '{}'){}", origin, one_line(key), one_line(text),
                                       suggestion(schema_, key)));
  if (list && spec->type != ParamType::List && spec->type != ParamType::Reals)
    throw ConfigError(key, fmt::format("{}: key '{}' must be a single value, not a list", origin, one_line(key)));
  const bool derive = !spec->derived.empty() && text == "auto";
  values_[key] = parse_value(*spec, derive ? spec->fallback : text, origin);
  origins_[key] = origin;
  if (derive)
    derived_.insert(key);
  else
    derived_.erase(key);
}

std::string Config::to_yaml() const {
  YAML::Emitter out;
  // Build nested maps in schema order: a key's prefix groups are opened once, in order.
  std::vector<std::string> open;  // currently open path components
  out << YAML::BeginMap;
  for (const auto& spec : schema_.params()) {
    std::vector<std::string> parts;
    std::stringstream ss(spec.key);
    for (std::string part; std::getline(ss, part, '.');) parts.push_back(part);
    std::size_t common = 0;
    while (common < open.size() && common + 1 < parts.size() && open[common] == parts[common]) ++common;
    for (std::size_t i = open.size(); i > common; --i) out << YAML::EndMap;
    open.resize(common);
    for (std::size_t i = common; i + 1 < parts.size(); ++i) {
      out << YAML::Key << parts[i] << YAML::Value << YAML::BeginMap;
      open.push_back(parts[i]);
    }
    out << YAML::Key << parts.back() << YAML::Value;
    if (spec.type == ParamType::List) {
      emit_list(out, std::get<ConfigList>(values_.at(spec.key)), spec.item_fields);
    } else if (spec.type == ParamType::Reals) {
      out << YAML::Flow << YAML::BeginSeq;
      for (const double v : std::get<std::vector<double>>(values_.at(spec.key))) out << format_value(v);
      out << YAML::EndSeq;
    } else if (derived(spec.key)) {
      out << "auto";
    } else {
      out << format_value(values_.at(spec.key));
    }
    std::string comment = derived(spec.key) ? spec.doc + "; auto: " + spec.derived : spec.doc;
    if (!derived(spec.key) && !spec.derived.empty() && origin(spec.key) == kDerivedOrigin)
      comment += "; derived: " + spec.derived;
    if (!spec.unit.empty()) comment += " [" + spec.unit + "]";
    if (!comment.empty()) out << YAML::Comment(comment);
  }
  for (std::size_t i = 0; i < open.size(); ++i) out << YAML::EndMap;
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

Config resolve_config(const Schema& schema, const std::optional<std::filesystem::path>& file,
                      const std::vector<std::string>& overrides, const std::vector<ConfigEntry>& options) {
  Config cfg;
  cfg.schema_ = schema;
  for (const auto& spec : schema.params()) {
    cfg.values_[spec.key] = parse_value(spec, spec.fallback, "default");
    cfg.origins_[spec.key] = "default";
    if (!spec.derived.empty()) cfg.derived_.insert(spec.key);
  }
  if (file) {
    for (const ConfigEntry& e : read_config_file(*file)) cfg.set(e.key, e.text, e.origin, e.list);
  }
  for (const ConfigEntry& e : options) cfg.set(e.key, e.text, e.origin);
  for (const auto& item : overrides) {
    const std::optional<KeyValue> kv = split_key_value(item);
    if (!kv || kv->key.empty())
      throw ConfigError("", fmt::format("--set: '{}' is not of the form key=value", one_line(item)));
    cfg.set(kv->key, kv->value, "--set");
  }
  return cfg;
}

}  // namespace flexgait
