#pragma once
/// \file config.hpp
/// Typed, validated configuration: a schema of dotted keys (`rimless.K`), values from a
/// YAML file and from `--set key=value` overrides, resolved into a Config.
///
/// Rules (docs/guide/commands.md): an unknown key, a wrong type, a value out of range, NaN or infinity,
/// or a missing/unreadable file is a ConfigError whose message names the origin (file and
/// line, or `--set`), the key, the offending value and what is allowed.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace flexgait {

/// Bad usage: the user asked for something that cannot be done as asked (a bad option value, a
/// directory that holds no sweep to resume, ...). The one error command-line programs map to
/// exit code 2 (and the Python module to ValueError); every other exception is a runtime failure
/// (exit 1), and std::logic_error / std::invalid_argument mean a bug in flexgait.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Bad configuration: a key, a value or a file. A UsageError that names the key.
class ConfigError : public UsageError {
 public:
  ConfigError(std::string key, const std::string& message) : UsageError(message), key_(std::move(key)) {}
  /// The offending dotted key ("" when the error concerns a whole file).
  const std::string& key() const noexcept { return key_; }

 private:
  std::string key_;
};

/// List: a list of structured items (e.g. disturbance.pushes), each a mapping of the fields
/// `ParamSpec::item_fields`, every field given; written as YAML (a block list in a file, flow
/// YAML such as `[{time: 1, force: [0, 9, 0]}]` after --set). Reals: a list of one or more real
/// numbers, each in [min, max] (`[0.105, 0.6]` in a file and after --set).
enum class ParamType { Real, Integer, Boolean, Choice, Text, List, Reals };

/// One documented configuration parameter.
struct ParamSpec {
  std::string key;  ///< dotted key, e.g. "rimless.K"
  ParamType type = ParamType::Real;
  std::string fallback;                                   ///< default value, as written in YAML
  std::string unit;                                       ///< SI unit, "" for dimensionless
  std::string doc;                                        ///< one line: what it is
  double min = -std::numeric_limits<double>::infinity();  ///< lower bound (Real, Integer, each of Reals)
  double max = std::numeric_limits<double>::infinity();   ///< upper bound (Real, Integer, each of Reals)
  bool min_inclusive = true;
  bool max_inclusive = true;
  std::vector<std::string> choices;    ///< allowed values (Choice)
  std::vector<ParamSpec> item_fields;  ///< List: the fields of one item (key: the field's name)
  int length = 0;  ///< a field of a List item: 0 one value, n > 0 a list of exactly n values of `type`
  /// A field of a List item that may be left out: it then takes `fallback`, and a configuration
  /// leaves it out while it holds that value (one value only: length 0).
  bool optional = false;
  /// Non-empty: the key's value is derived from other inputs unless set (e.g. walk.pelvis_height
  /// from the robot); says how. Such a key also takes the value `auto` (derive it), and a
  /// configuration writes it as `auto` while it is derived. `fallback` is then only a placeholder.
  std::string derived;

  /// Human-readable domain, e.g. "a real number > 0" or "one of flexible, rigid".
  std::string allowed() const;
};

/// Builders of documented parameters (bounds inclusive unless said otherwise).
ParamSpec real_param(std::string key, std::string fallback, std::string unit, std::string doc, double min, double max,
                     bool min_inclusive = true, bool max_inclusive = true);
ParamSpec integer_param(std::string key, std::string fallback, std::string doc, double min, double max);
ParamSpec choice_param(std::string key, std::string fallback, std::string doc, std::vector<std::string> choices);
ParamSpec boolean_param(std::string key, std::string fallback, std::string doc);
/// Free text (a name or a path): any one-line value that is not empty.
ParamSpec text_param(std::string key, std::string fallback, std::string doc);

/// A key that stands for several keys of one quantity, each set to the alias's value (rimless.mu:
/// rimless.mu_s = rimless.mu_k). It holds no value of its own: a configuration writes its parts.
struct ParamAlias {
  std::string key;
  std::vector<std::string> parts;
  std::string doc;
};

/// The set of keys a command accepts, in declaration order.
class Schema {
 public:
  /// Adds a parameter; throws std::logic_error on a duplicate key or a default outside the domain.
  Schema& add(ParamSpec spec);
  /// Adds an alias of keys already in the schema, all of one type; throws std::logic_error otherwise.
  Schema& alias(std::string key, std::vector<std::string> parts, std::string doc);
  /// Adds every parameter and alias of another schema.
  Schema& merge(const Schema& other);
  const ParamSpec* find(const std::string& key) const;
  const ParamAlias* find_alias(const std::string& key) const;
  const std::vector<ParamSpec>& params() const { return params_; }
  const std::vector<ParamAlias>& aliases() const { return aliases_; }

 private:
  std::vector<ParamSpec> params_;
  std::vector<ParamAlias> aliases_;
};

using ConfigScalar = std::variant<double, std::int64_t, bool, std::string>;
/// A List value: items × fields (in ParamSpec::item_fields order) × values (1, or the field's length).
struct ConfigList {
  std::vector<std::vector<std::vector<ConfigScalar>>> items;
  bool operator==(const ConfigList&) const = default;
};
using ConfigValue = std::variant<double, std::int64_t, bool, std::string, ConfigList, std::vector<double>>;

/// One value with its dotted key, its text and where it comes from ("FILE:LINE", "--steps").
struct ConfigEntry {
  std::string key;
  std::string text;
  std::string origin;
  bool list = false;  ///< the text is a YAML list read from a file (a key that takes one value refuses it)
};

/// A resolved configuration: every key of its schema has a validated value.
class Config {
 public:
  double real(const std::string& key) const;
  std::int64_t integer(const std::string& key) const;
  bool boolean(const std::string& key) const;
  const std::string& choice(const std::string& key) const;
  const std::string& text(const std::string& key) const;
  const ConfigList& list(const std::string& key) const;
  const std::vector<double>& reals(const std::string& key) const;
  /// Where the value came from: "default", "--set", or "FILE:LINE".
  const std::string& origin(const std::string& key) const;
  /// The key (ParamSpec::derived non-empty) is to be derived: left unset or set to `auto`.
  bool derived(const std::string& key) const { return derived_.count(key) > 0; }
  /// Replaces a value after validation against the schema (used by sweeps); an alias sets each of
  /// its parts. `list`: the text is a YAML list from a file (refused by a key that takes one value: not List or Reals).
  void set(const std::string& key, const std::string& text, const std::string& origin = "--set", bool list = false);
  /// The resolved configuration as nested YAML, keys in schema order; round-trips through load.
  std::string to_yaml() const;
  const Schema& schema() const { return schema_; }

 private:
  friend Config resolve_config(const Schema&, const std::optional<std::filesystem::path>&,
                               const std::vector<std::string>&, const std::vector<ConfigEntry>&);
  const ConfigValue& value(const std::string& key, ParamType expected) const;
  Schema schema_;
  std::map<std::string, ConfigValue> values_;
  std::map<std::string, std::string> origins_;
  std::set<std::string> derived_;  ///< keys left to their derivation (ParamSpec::derived)
};

/// Runs a cross-field check of `config`: a ConfigError it throws naming a key of `config` is
/// rethrown with that key's origin in front ("--set: ", "FILE:LINE: ", "default: ").
void check_with_origin(const Config& config, const std::function<void()>& check);

/// Parses `text` as the value of `spec`; throws ConfigError naming origin, key and domain.
ConfigValue parse_value(const ParamSpec& spec, const std::string& text, const std::string& origin);

/// Formats a value as YAML text that parses back to the identical value (a list: flow YAML, whose
/// items need their spec to be named: `item_fields`).
std::string format_value(const ConfigValue& value, const std::vector<ParamSpec>& item_fields = {});

/// The origin of a value derived from other inputs and written in (Config::set): to_yaml marks it
/// in the key's comment ("derived: RULE"), and a file read back holds it as set.
inline constexpr const char* kDerivedOrigin = "derived";

/// Resolves defaults, then the YAML file (if any), then `options` (values of command-line options
/// such as --steps, each under its own origin), then `key=value` overrides (--set) in order.
Config resolve_config(const Schema& schema, const std::optional<std::filesystem::path>& file,
                      const std::vector<std::string>& overrides, const std::vector<ConfigEntry>& options = {});

}  // namespace flexgait
