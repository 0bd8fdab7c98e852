#pragma once
// CaseConfig: a case file read, overridden from the command line, validated
// against the schema and completed with defaults.
//
// Every read of a value goes through a typed getter; every later semantic check
// (a fill level above the roof, a time step longer than the window) raises its
// error through error_at(), so it too names file, line and key.
#include <Eigen/Core>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/config/config_error.hpp"
#include "common/config/schema.hpp"

namespace tankfsi {

/// One `--set key=value` from the command line.
struct Override {
  std::string key;
  std::string value;   ///< YAML text: 0.02, true, [0, 0, 1]
  std::string source;  ///< how errors name it; empty means "--set key=value"
};

/// Read access to one validated scope: the whole case, or one record of a list.
class ConfigView {
 public:
  [[nodiscard]] bool has(const std::string& key) const;  ///< given or defaulted
  [[nodiscard]] double real(const std::string& key) const;
  [[nodiscard]] long long integer(const std::string& key) const;
  [[nodiscard]] bool boolean(const std::string& key) const;
  [[nodiscard]] std::string text(const std::string& key) const;  ///< text and choice keys
  [[nodiscard]] std::filesystem::path path(const std::string& key) const;
  [[nodiscard]] std::vector<double> real_vector(const std::string& key) const;
  [[nodiscard]] Eigen::Vector3d vector3(const std::string& key) const;
  [[nodiscard]] std::vector<ConfigView> records(const std::string& key) const;

  /// An error about `key` of this scope, located at the line the key came from.
  [[nodiscard]] ConfigError error_at(const std::string& key, const std::string& message) const;
  /// The full key path of `key` ("fluid.probes[2].position").
  [[nodiscard]] std::string full_key(const std::string& key) const;

 protected:
  struct Shared {
    std::map<std::string, Origin> origins;  ///< full key path -> where it was set
    Origin file_origin;                     ///< the case file itself (line 0)
  };
  ConfigView(YAML::Node resolved, std::string prefix, std::shared_ptr<const Shared> shared)
      : resolved_(std::move(resolved)), prefix_(std::move(prefix)), shared_(std::move(shared)) {}
  [[nodiscard]] YAML::Node value(const std::string& key) const;

  YAML::Node resolved_;
  std::string prefix_;
  std::shared_ptr<const Shared> shared_;
};

class CaseConfig : public ConfigView {
 public:
  /// Reads, overrides and validates; throws ConfigError on the first problem.
  static CaseConfig load(const std::filesystem::path& file, const std::vector<Override>& overrides,
                         const Schema& schema);

  [[nodiscard]] bool has_section(const std::string& section) const;
  /// Throws unless the case has `section` (a program's own section is required).
  void require_section(const std::string& section, const std::string& program) const;

  [[nodiscard]] const std::filesystem::path& file() const { return file_; }
  /// Short name for default folders: the case file's stem, or its folder's name
  /// when the file is called case.yaml.
  [[nodiscard]] std::string case_name() const;
  /// The complete case after defaults and overrides, as YAML text.
  [[nodiscard]] std::string resolved_yaml() const;

 private:
  CaseConfig(YAML::Node resolved, std::shared_ptr<const Shared> shared, std::filesystem::path file)
      : ConfigView(std::move(resolved), "", std::move(shared)), file_(std::move(file)) {}
  std::filesystem::path file_;
};

}  // namespace tankfsi
