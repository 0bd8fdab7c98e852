#include "common/config/case_config.hpp"

#include "common/io/exact_number.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

namespace tankfsi {

namespace fs = std::filesystem;

namespace {

// ---- small helpers on YAML trees ------------------------------------------------------

void set_path(YAML::Node node, const std::string& name, const YAML::Node& value) {
  const auto dot = name.find('.');
  if (dot == std::string::npos) {
    node[name] = value;
    return;
  }
  set_path(node[name.substr(0, dot)], name.substr(dot + 1), value);
}

YAML::Node get_path(const YAML::Node& node, const std::string& name) {
  // A missing key yields an invalid node, on which IsMap() would throw.
  if (!node.IsDefined() || !node.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
  const auto dot = name.find('.');
  const YAML::Node& const_node = node;
  if (dot == std::string::npos) return const_node[name];
  return get_path(const_node[name.substr(0, dot)], name.substr(dot + 1));
}

std::string scalar_text(const YAML::Node& node) { return node.IsScalar() ? node.Scalar() : ""; }

std::string describe_node(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "nothing";
  if (node.IsScalar()) return "'" + node.Scalar() + "'";
  if (node.IsSequence()) return "a list";
  return "a map";
}

std::optional<long long> parse_integer(std::string text) {
  if (!text.empty() && text.front() == '+') text.erase(0, 1);
  long long value = 0;
  const auto* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end) return std::nullopt;
  return value;
}

bool within_bounds(const KeySpec& spec, double v) {
  if (spec.lower && (spec.lower->inclusive ? v < spec.lower->value : v <= spec.lower->value)) return false;
  if (spec.upper && (spec.upper->inclusive ? v > spec.upper->value : v >= spec.upper->value)) return false;
  return true;
}

std::string section_of(const std::string& name) {
  const auto dot = name.find('.');
  return dot == std::string::npos ? "" : name.substr(0, dot);
}

std::string join(const std::vector<std::string>& words, const std::string& separator) {
  std::string out;
  for (const auto& w : words) out += (out.empty() ? "" : separator) + w;
  return out;
}

// Sections that describe a model part: absent means "no such part", so their
// keys are neither required nor defaulted. Other sections always get defaults.
const std::set<std::string> model_sections = {"fluid", "structure", "coupling"};

// Short name for default folders: the file's stem, or its folder's name for case.yaml.
std::string case_name_of(const fs::path& file) {
  if (file.stem() == "case") {
    const auto folder = fs::absolute(file).parent_path().filename();
    if (!folder.empty()) return folder.string();
  }
  return file.stem().string();
}

// ---- validation of one scope --------------------------------------------------------------

struct Context {
  fs::path case_folder;
  std::string case_name;
  std::string file_label;
  std::map<std::string, Origin> override_origins;  // full key -> "--set ..." origin
  std::map<std::string, Origin> origins;           // output: full key -> origin
};

class ScopeValidator {
 public:
  ScopeValidator(Context& context, const Schema& schema, std::string prefix, Origin scope_origin,
                 bool top_level)
      : ctx_(context), schema_(schema), prefix_(std::move(prefix)),
        scope_origin_(std::move(scope_origin)), top_level_(top_level) {}

  YAML::Node run(const YAML::Node& node) {
    if (node.IsDefined() && !node.IsNull() && !node.IsMap()) {
      throw ConfigError(scope_origin_, top_level_ ? "" : prefix_,
                        top_level_ ? "the case file must be a map of sections (fluid, structure, "
                                     "coupling, excitation, output), got " + describe_node(node)
                                   : "expected a map of keys, got " + describe_node(node));
    }
    collect(node, "");
    validate_given();
    complete_missing();
    // Emit in declaration order, so that a resolved case reads like the schema.
    YAML::Node out(YAML::NodeType::Map);
    for (const auto& spec : schema_.keys)
      if (auto it = values_.find(spec.name); it != values_.end()) set_path(out, spec.name, it->second);
    return out;
  }

 private:
  struct Given {
    const KeySpec* spec;
    YAML::Node value;
    Origin origin;
  };

  [[nodiscard]] std::string full(const std::string& name) const {
    return prefix_.empty() ? name : prefix_ + "." + name;
  }

  [[nodiscard]] Origin origin_of(const std::string& name, const YAML::Node& key_node) const {
    if (auto it = ctx_.override_origins.find(full(name)); it != ctx_.override_origins.end())
      return it->second;
    if (key_node.Mark().line >= 0) return Origin{ctx_.file_label, key_node.Mark().line + 1};
    return scope_origin_;
  }

  // Walks the user's map, sorting its entries into declared keys and groups.
  void collect(const YAML::Node& node, const std::string& relative) {
    if (!node.IsDefined() || node.IsNull()) return;
    std::set<std::string> seen;
    for (auto it = node.begin(); it != node.end(); ++it) {
      const std::string key = scalar_text(it->first);
      const std::string name = relative.empty() ? key : relative + "." + key;
      const Origin origin = origin_of(name, it->first);
      if (key.empty()) throw ConfigError(origin, full(relative), "keys must be plain words");
      if (!seen.insert(key).second) throw ConfigError(origin, full(name), "duplicate key");
      if (const KeySpec* spec = schema_.find(name)) {
        given_.push_back(Given{spec, it->second, origin});
        continue;
      }
      if (schema_.is_map_prefix(name)) {
        map_origins_[name] = origin;
        if (!it->second.IsNull() && !it->second.IsMap())
          throw ConfigError(origin, full(name), "expected a map of keys, got " + describe_node(it->second));
        if (top_level_ && relative.empty()) present_sections_.insert(name);
        collect(it->second, name);
        continue;
      }
      std::string message = "unknown key";
      if (const auto suggestion = schema_.closest(name); !suggestion.empty())
        message += " (did you mean " + full(suggestion) + "?)";
      throw ConfigError(origin, full(name), message);
    }
  }

  [[nodiscard]] const Given* given(const std::string& name) const {
    for (const auto& g : given_)
      if (g.spec->name == name) return &g;
    return nullptr;
  }

  // The value that decides whether a conditional key applies (given or default).
  [[nodiscard]] std::string condition_value(const std::string& when_key) const {
    if (const Given* g = given(when_key)) return scalar_text(g->value);
    const KeySpec* spec = schema_.find(when_key);
    return spec ? spec->default_yaml : "";
  }

  [[nodiscard]] bool applies(const KeySpec& spec) const {
    if (spec.when_key.empty()) return true;
    const auto value = condition_value(spec.when_key);
    return std::find(spec.when_values.begin(), spec.when_values.end(), value) != spec.when_values.end();
  }

  [[nodiscard]] bool section_present(const KeySpec& spec) const {
    if (!top_level_) return true;
    const auto section = section_of(spec.name);
    return section.empty() || !model_sections.contains(section) || present_sections_.contains(section);
  }

  void validate_given() {
    // Keys that decide conditions first, so that a misspelt choice is reported as
    // such. Ordered by index: YAML::Node assignment writes into the tree instead
    // of rebinding, so the Given entries themselves must never be moved.
    auto decides = [&](const Given& g) {
      return std::any_of(schema_.keys.begin(), schema_.keys.end(),
                         [&](const KeySpec& k) { return k.when_key == g.spec->name; });
    };
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < given_.size(); ++i)
      if (decides(given_[i])) order.push_back(i);
    for (std::size_t i = 0; i < given_.size(); ++i)
      if (!decides(given_[i])) order.push_back(i);
    for (const std::size_t i : order) {
      const Given& g = given_[i];
      const KeySpec& spec = *g.spec;
      if (!applies(spec)) {
        // A required deciding key that is missing is the error, not this key.
        if (const KeySpec* decider = schema_.find(spec.when_key);
            decider && decider->required && !given(spec.when_key) && section_present(*decider))
          throw ConfigError(enclosing_origin(decider->name), full(decider->name), "required key is missing");
        throw ConfigError(g.origin, full(spec.name),
                          "only used when " + full(spec.when_key) + " is " + join(spec.when_values, " or ") +
                              " (here it is " + condition_value(spec.when_key) + ")");
      }
      values_.emplace(spec.name, normalise(spec, g.value, g.origin));
      ctx_.origins[full(spec.name)] = g.origin;
    }
  }

  [[nodiscard]] Origin enclosing_origin(const std::string& name) const {
    for (auto dot = name.rfind('.'); dot != std::string::npos; dot = name.rfind('.', dot - 1)) {
      if (auto it = map_origins_.find(name.substr(0, dot)); it != map_origins_.end()) return it->second;
      if (dot == 0) break;
    }
    return scope_origin_;
  }

  void complete_missing() {
    for (const auto& spec : schema_.keys) {
      if (given(spec.name) || !section_present(spec) || !applies(spec)) continue;
      const Origin origin = enclosing_origin(spec.name);
      if (spec.required) {
        std::string message = "required key is missing";
        if (!spec.when_key.empty())
          message += " (needed when " + full(spec.when_key) + " is " + condition_value(spec.when_key) + ")";
        throw ConfigError(origin, full(spec.name), message);
      }
      if (spec.default_yaml.empty()) continue;
      values_.emplace(spec.name, normalise(spec, YAML::Load(spec.default_yaml), origin));
      ctx_.origins[full(spec.name)] = origin;
    }
  }

  [[nodiscard]] YAML::Node normalise(const KeySpec& spec, const YAML::Node& value, const Origin& origin) const {
    const std::string key = full(spec.name);
    auto fail = [&](const std::string& message) { return ConfigError(origin, key, message); };
    auto unit_note = [&] { return spec.unit.empty() ? std::string() : " (" + spec.unit + ")"; };
    auto number = [&](const YAML::Node& element, const std::string& element_key) {
      const auto parsed = element.IsScalar() ? parse_number(element.Scalar()) : std::nullopt;
      if (!element.IsScalar() || !parsed)
        throw ConfigError(origin, element_key, "expected a number" + unit_note() + ", got " + describe_node(element));
      if (!std::isfinite(*parsed))
        throw ConfigError(origin, element_key, "must be a finite number, got " + scalar_text(element));
      if (!within_bounds(spec, *parsed))
        throw ConfigError(origin, element_key, "must be " + describe_range(spec) + ", got " + scalar_text(element));
      return *parsed;
    };

    switch (spec.kind) {
      case ValueKind::real:
        return YAML::Node(exact_text(number(value, key)));
      case ValueKind::integer: {
        const auto parsed = value.IsScalar() ? parse_integer(value.Scalar()) : std::nullopt;
        if (!parsed) throw fail("expected an integer, got " + describe_node(value));
        if (!within_bounds(spec, static_cast<double>(*parsed)))
          throw fail("must be " + describe_range(spec) + ", got " + value.Scalar());
        return YAML::Node(std::to_string(*parsed));
      }
      case ValueKind::boolean: {
        const auto text = scalar_text(value);
        if (!value.IsScalar() || (text != "true" && text != "false"))
          throw fail("expected true or false, got " + describe_node(value));
        return YAML::Node(text);
      }
      case ValueKind::text:
        if (!value.IsScalar()) throw fail("expected text, got " + describe_node(value));
        return YAML::Node(value.Scalar());
      case ValueKind::choice: {
        const auto text = scalar_text(value);
        if (!value.IsScalar() || std::find(spec.choices.begin(), spec.choices.end(), text) == spec.choices.end())
          throw fail("must be one of " + join(spec.choices, ", ") + ", got " + describe_node(value));
        return YAML::Node(text);
      }
      case ValueKind::input_path: {
        const auto text = scalar_text(value);
        if (!value.IsScalar() || text.empty()) throw fail("expected a file path, got " + describe_node(value));
        fs::path p(text);
        if (p.is_relative()) p = ctx_.case_folder / p;
        p = p.lexically_normal();
        std::error_code ec;
        if (!fs::is_regular_file(p, ec)) throw fail("no such file: " + p.string());
        if (!std::ifstream(p)) throw fail("cannot read file: " + p.string() + ": " + std::strerror(errno));
        return YAML::Node(p.string());
      }
      case ValueKind::output_path: {
        auto text = scalar_text(value);
        if (!value.IsScalar() || text.empty()) throw fail("expected a folder path, got " + describe_node(value));
        for (auto at = text.find("{case}"); at != std::string::npos; at = text.find("{case}"))
          text.replace(at, 6, ctx_.case_name);
        return YAML::Node(fs::absolute(fs::path(text)).lexically_normal().string());
      }
      case ValueKind::real_vector: {
        if (!value.IsSequence() || value.size() == 0)
          throw fail("expected a list of numbers" + unit_note() + ", got " + describe_node(value));
        if (spec.length > 0 && value.size() != static_cast<std::size_t>(spec.length))
          throw fail("expected a list of " + std::to_string(spec.length) + " numbers, got " +
                     std::to_string(value.size()));
        YAML::Node out(YAML::NodeType::Sequence);
        out.SetStyle(YAML::EmitterStyle::Flow);
        for (std::size_t i = 0; i < value.size(); ++i)
          out.push_back(exact_text(number(value[i], key + "[" + std::to_string(i) + "]")));
        return out;
      }
      case ValueKind::record_list: {
        YAML::Node out(YAML::NodeType::Sequence);
        if (value.IsNull() || value.size() == 0) {
          out.SetStyle(YAML::EmitterStyle::Flow);
          return out;
        }
        if (!value.IsSequence()) throw fail("expected a list of records, got " + describe_node(value));
        const Schema record_schema{spec.fields};
        for (std::size_t i = 0; i < value.size(); ++i) {
          const std::string record_key = key + "[" + std::to_string(i) + "]";
          const auto mark = value[i].Mark();
          const Origin record_origin = mark.line >= 0 ? Origin{ctx_.file_label, mark.line + 1} : origin;
          ScopeValidator record(ctx_, record_schema, record_key, record_origin, false);
          out.push_back(record.run(value[i]));
        }
        return out;
      }
    }
    throw fail("unhandled kind");
  }

  Context& ctx_;
  const Schema& schema_;
  std::string prefix_;
  Origin scope_origin_;
  bool top_level_;
  std::vector<Given> given_;
  std::map<std::string, YAML::Node> values_;  // normalised, by key name
  std::map<std::string, Origin> map_origins_;
  std::set<std::string> present_sections_;
};

void apply_override(YAML::Node& tree, const Override& o, const Schema& schema, Context& ctx) {
  const Origin origin{o.source.empty() ? "--set " + o.key + "=" + o.value : o.source, 0};
  const KeySpec* spec = schema.find(o.key);
  if (!spec) {
    if (schema.is_map_prefix(o.key))
      throw ConfigError(origin, o.key, "is a group of keys; set its keys one by one");
    std::string message = "unknown key";
    if (const auto suggestion = schema.closest(o.key); !suggestion.empty())
      message += " (did you mean " + suggestion + "?)";
    throw ConfigError(origin, o.key, message);
  }
  if (spec->kind == ValueKind::record_list)
    throw ConfigError(origin, o.key, "lists of records cannot be set from the command line; edit the case file");
  YAML::Node value;
  try {
    value = YAML::Load(o.value);
  } catch (const YAML::Exception& e) {
    throw ConfigError(origin, o.key, "cannot parse value '" + o.value + "': " + e.msg);
  }
  // A --set replaces the key; a section given as a bare value cannot take keys.
  const auto section = section_of(o.key);
  if (!section.empty() && tree[section].IsDefined() && !tree[section].IsNull() && !tree[section].IsMap())
    throw ConfigError(origin, o.key, "section " + section + " in the case file is not a map");
  set_path(tree, o.key, value);
  ctx.override_origins[o.key] = origin;
}

}  // namespace

// ---- ConfigView -------------------------------------------------------------------------

std::string ConfigView::full_key(const std::string& key) const {
  return prefix_.empty() ? key : prefix_ + "." + key;
}

YAML::Node ConfigView::value(const std::string& key) const {
  YAML::Node node = get_path(resolved_, key);
  if (!node.IsDefined() || node.IsNull())
    throw std::logic_error("case key " + full_key(key) + " read but not set (missing default or condition)");
  return node;
}

bool ConfigView::has(const std::string& key) const {
  const YAML::Node node = get_path(resolved_, key);
  return node.IsDefined() && !node.IsNull();
}

double ConfigView::real(const std::string& key) const { return value(key).as<double>(); }
long long ConfigView::integer(const std::string& key) const { return value(key).as<long long>(); }
bool ConfigView::boolean(const std::string& key) const { return value(key).Scalar() == "true"; }
std::string ConfigView::text(const std::string& key) const { return value(key).Scalar(); }
fs::path ConfigView::path(const std::string& key) const { return fs::path(value(key).Scalar()); }

std::vector<double> ConfigView::real_vector(const std::string& key) const {
  return value(key).as<std::vector<double>>();
}

Eigen::Vector3d ConfigView::vector3(const std::string& key) const {
  const auto v = real_vector(key);
  if (v.size() != 3) throw error_at(key, "expected a list of 3 numbers, got " + std::to_string(v.size()));
  return {v[0], v[1], v[2]};
}

std::vector<ConfigView> ConfigView::records(const std::string& key) const {
  std::vector<ConfigView> out;
  const YAML::Node list = get_path(resolved_, key);
  if (!list.IsSequence()) return out;
  for (std::size_t i = 0; i < list.size(); ++i)
    out.push_back(ConfigView(list[i], full_key(key) + "[" + std::to_string(i) + "]", shared_));
  return out;
}

ConfigError ConfigView::error_at(const std::string& key, const std::string& message) const {
  const std::string name = full_key(key);
  auto it = shared_->origins.find(name);
  return ConfigError(it != shared_->origins.end() ? it->second : shared_->file_origin, name, message);
}

// ---- CaseConfig -------------------------------------------------------------------------

CaseConfig CaseConfig::load(const fs::path& file, const std::vector<Override>& overrides, const Schema& schema) {
  Context ctx;
  ctx.file_label = file.string();
  ctx.case_folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  ctx.case_name = case_name_of(file);
  const Origin file_origin{ctx.file_label, 0};

  std::ifstream in(file);
  std::error_code ec;
  if (fs::is_directory(file, ec)) throw ConfigError(file_origin, "", "cannot read case file: is a folder");
  if (!in) throw ConfigError(file_origin, "", std::string("cannot read case file: ") + std::strerror(errno));
  std::stringstream text;
  text << in.rdbuf();

  YAML::Node tree;
  try {
    tree = YAML::Load(text.str());
  } catch (const YAML::ParserException& e) {
    throw ConfigError(Origin{ctx.file_label, e.mark.line + 1}, "", "YAML syntax error: " + e.msg);
  }
  if (!tree.IsDefined() || tree.IsNull()) tree = YAML::Node(YAML::NodeType::Map);
  if (!tree.IsMap())
    throw ConfigError(Origin{ctx.file_label, std::max(1, tree.Mark().line + 1)}, "",
                      "the case file must be a map of sections (fluid, structure, coupling, excitation, "
                      "output), got " + describe_node(tree));
  for (const auto& o : overrides) apply_override(tree, o, schema, ctx);

  ScopeValidator validator(ctx, schema, "", Origin{ctx.file_label, 1}, true);
  YAML::Node resolved = validator.run(tree);

  auto shared = std::make_shared<Shared>();
  shared->origins = std::move(ctx.origins);
  shared->file_origin = file_origin;
  return CaseConfig(resolved, shared, file);
}

bool CaseConfig::has_section(const std::string& section) const {
  const YAML::Node node = get_path(resolved_, section);
  return node.IsDefined() && node.IsMap();
}

void CaseConfig::require_section(const std::string& section, const std::string& program) const {
  if (!has_section(section))
    throw ConfigError(Origin{file_.string(), 0}, section, "section is missing; " + program + " needs it");
}

std::string CaseConfig::case_name() const { return case_name_of(file_); }

std::string CaseConfig::resolved_yaml() const {
  YAML::Emitter out;
  out << resolved_;
  return "# Case " + file_.string() + " after defaults and command-line overrides.\n" +
         std::string(out.c_str()) + "\n";
}

}  // namespace tankfsi
