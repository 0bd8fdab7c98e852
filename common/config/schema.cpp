#include "common/config/schema.hpp"

#include <algorithm>
#include <sstream>

namespace tankfsi {

namespace {

KeySpec make_key(ValueKind kind, std::string name, std::string description) {
  KeySpec spec;
  spec.kind = kind;
  spec.name = std::move(name);
  spec.description = std::move(description);
  return spec;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string format_number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

}  // namespace

KeySpec real_key(std::string n, std::string d) { return make_key(ValueKind::real, std::move(n), std::move(d)); }
KeySpec integer_key(std::string n, std::string d) { return make_key(ValueKind::integer, std::move(n), std::move(d)); }
KeySpec boolean_key(std::string n, std::string d) { return make_key(ValueKind::boolean, std::move(n), std::move(d)); }
KeySpec text_key(std::string n, std::string d) { return make_key(ValueKind::text, std::move(n), std::move(d)); }
KeySpec input_path_key(std::string n, std::string d) { return make_key(ValueKind::input_path, std::move(n), std::move(d)); }
KeySpec output_path_key(std::string n, std::string d) { return make_key(ValueKind::output_path, std::move(n), std::move(d)); }
KeySpec real_vector_key(std::string n, std::string d) { return make_key(ValueKind::real_vector, std::move(n), std::move(d)); }
KeySpec record_list_key(std::string n, std::string d) { return make_key(ValueKind::record_list, std::move(n), std::move(d)); }
KeySpec choice_key(std::string n, std::vector<std::string> choices, std::string d) {
  KeySpec spec = make_key(ValueKind::choice, std::move(n), std::move(d));
  spec.choices = std::move(choices);
  return spec;
}

const KeySpec* Schema::find(const std::string& name) const {
  for (const auto& k : keys)
    if (k.name == name) return &k;
  return nullptr;
}

bool Schema::is_map_prefix(const std::string& name) const {
  const std::string prefix = name + ".";
  return std::any_of(keys.begin(), keys.end(),
                     [&](const KeySpec& k) { return k.name.starts_with(prefix); });
}

std::string Schema::closest(const std::string& name) const {
  // Candidates are every declared key and every map prefix of one.
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(3, name.size() / 4) + 1;
  auto consider = [&](const std::string& candidate) {
    const std::size_t d = edit_distance(name, candidate);
    if (d < best_distance) {
      best_distance = d;
      best = candidate;
    }
  };
  for (const auto& k : keys) {
    consider(k.name);
    for (std::size_t dot = k.name.find('.'); dot != std::string::npos; dot = k.name.find('.', dot + 1))
      consider(k.name.substr(0, dot));
  }
  return best;
}

std::string describe_kind(const KeySpec& spec) {
  switch (spec.kind) {
    case ValueKind::real: return "number";
    case ValueKind::integer: return "integer";
    case ValueKind::boolean: return "true|false";
    case ValueKind::text: return "text";
    case ValueKind::choice: {
      std::string s;
      for (const auto& c : spec.choices) s += (s.empty() ? "" : "|") + c;
      return s;
    }
    case ValueKind::input_path: return "file path (relative to the case file)";
    case ValueKind::output_path: return "folder path (relative to the working directory)";
    case ValueKind::real_vector:
      return spec.length > 0 ? "list of " + std::to_string(spec.length) + " numbers" : "list of numbers";
    case ValueKind::record_list: return "list of records";
  }
  return "";
}

std::string describe_range(const KeySpec& spec) {
  if (spec.lower && spec.upper)
    return "in " + std::string(spec.lower->inclusive ? "[" : "(") + format_number(spec.lower->value) +
           ", " + format_number(spec.upper->value) + (spec.upper->inclusive ? "]" : ")");
  if (spec.lower) return (spec.lower->inclusive ? ">= " : "> ") + format_number(spec.lower->value);
  if (spec.upper) return (spec.upper->inclusive ? "<= " : "< ") + format_number(spec.upper->value);
  return "";
}

namespace {

void append_key_help(std::ostringstream& out, const KeySpec& k, const std::string& full_name,
                     const std::string& indent) {
  out << indent << full_name << "  (" << describe_kind(k);
  if (!k.unit.empty()) out << ", " << k.unit;
  if (const auto range = describe_range(k); !range.empty()) out << ", " << range;
  if (k.required)
    out << ", required";
  else if (!k.default_yaml.empty())
    out << ", default " << k.default_yaml;
  out << ")\n" << indent << "    " << k.description;
  if (!k.when_key.empty()) {
    out << " [only when " << k.when_key << " is ";
    for (std::size_t i = 0; i < k.when_values.size(); ++i) out << (i ? "|" : "") << k.when_values[i];
    out << "]";
  }
  out << "\n";
  for (const auto& field : k.fields) append_key_help(out, field, full_name + "[]." + field.name, indent + "  ");
}

}  // namespace

std::string schema_help_text(const Schema& schema) {
  std::ostringstream out;
  std::string section;
  for (const auto& k : schema.keys) {
    const auto dot = k.name.find('.');
    const std::string this_section = dot == std::string::npos ? "" : k.name.substr(0, dot);
    if (this_section != section || (&k == &schema.keys.front())) {
      section = this_section;
      out << "\n" << (section.empty() ? "top level" : section + ":") << "\n";
    }
    append_key_help(out, k, k.name, "  ");
  }
  return out.str();
}

}  // namespace tankfsi
