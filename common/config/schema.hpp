#pragma once
// Schema: the declared keys of a case file.
//
// Every key has a kind, an SI unit, a default (or is required), an allowed range
// or set of choices, and a description. The validator, the resolved case file and
// `--help` all read this one table, so documentation cannot drift from behaviour.
#include <optional>
#include <string>
#include <vector>

namespace tankfsi {

enum class ValueKind {
  real,         ///< finite floating-point number
  integer,      ///< whole number
  boolean,      ///< true or false
  text,         ///< free text
  choice,       ///< one of a fixed set of words
  input_path,   ///< existing readable file, relative to the case file's folder
  output_path,  ///< folder to create, relative to the working directory
  real_vector,  ///< list of finite numbers (fixed length when length > 0)
  record_list,  ///< list of maps, each validated against `fields`
};

struct Bound {
  double value = 0.0;
  bool inclusive = true;
};

struct KeySpec {
  std::string name;  ///< dotted path within its scope ("spacing", "time_step.mode")
  ValueKind kind = ValueKind::real;
  std::string unit;  ///< SI unit, empty for dimensionless and non-numeric keys
  std::string description;
  std::string default_yaml;  ///< YAML text of the default; empty when none
  bool required = false;     ///< required when its section is present and it applies
  std::optional<Bound> lower;
  std::optional<Bound> upper;
  std::vector<std::string> choices;
  int length = 0;  ///< real_vector: exact length, or 0 for any non-empty length
  /// The key applies only when sibling key `when_key` has one of `when_values`.
  std::string when_key;
  std::vector<std::string> when_values;
  std::vector<KeySpec> fields;  ///< record_list: keys of one record

  // Fluent declaration helpers, so that a schema reads as a table.
  KeySpec& unit_is(std::string u) { unit = std::move(u); return *this; }
  KeySpec& default_is(std::string yaml) { default_yaml = std::move(yaml); return *this; }
  KeySpec& is_required() { required = true; return *this; }
  KeySpec& above(double v) { lower = Bound{v, false}; return *this; }
  KeySpec& at_least(double v) { lower = Bound{v, true}; return *this; }
  KeySpec& below(double v) { upper = Bound{v, false}; return *this; }
  KeySpec& at_most(double v) { upper = Bound{v, true}; return *this; }
  KeySpec& with_length(int n) { length = n; return *this; }
  KeySpec& only_when(std::string key, std::vector<std::string> values) {
    when_key = std::move(key);
    when_values = std::move(values);
    return *this;
  }
  KeySpec& with_fields(std::vector<KeySpec> f) { fields = std::move(f); return *this; }
};

/// Declaration shorthands: key(kind, name, description).
KeySpec real_key(std::string name, std::string description);
KeySpec integer_key(std::string name, std::string description);
KeySpec boolean_key(std::string name, std::string description);
KeySpec text_key(std::string name, std::string description);
KeySpec choice_key(std::string name, std::vector<std::string> choices, std::string description);
KeySpec input_path_key(std::string name, std::string description);
KeySpec output_path_key(std::string name, std::string description);
KeySpec real_vector_key(std::string name, std::string description);
KeySpec record_list_key(std::string name, std::string description);

/// A set of keys forming one scope (the whole case file, or one record).
struct Schema {
  std::vector<KeySpec> keys;

  [[nodiscard]] const KeySpec* find(const std::string& name) const;
  /// True when `name` is a map holding declared keys ("fluid", "fluid.time_step").
  [[nodiscard]] bool is_map_prefix(const std::string& name) const;
  /// The declared name closest to `name` (for "did you mean"), or empty.
  [[nodiscard]] std::string closest(const std::string& name) const;
};

/// Human-readable rules of one key: kind, unit, default, range, choices.
std::string describe_kind(const KeySpec& spec);
std::string describe_range(const KeySpec& spec);  ///< "> 0", "in (0, 1]", or empty

/// The `--help` listing of every key of `schema`, grouped by section.
std::string schema_help_text(const Schema& schema);

}  // namespace tankfsi
