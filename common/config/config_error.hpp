#pragma once
// ConfigError: a user-input error that names where it comes from,
// formatted "file:line: key.path: message" (or "origin: key.path: message"
// for command-line overrides). Programs report it and exit with status 2.
#include <stdexcept>
#include <string>

namespace tankfsi {

/// Where a value came from: a line of a file, or a command-line override.
struct Origin {
  std::string source;  ///< file path as the user gave it, or "--set key=value"
  int line = 0;        ///< 1-based; 0 when the source has no lines

  [[nodiscard]] std::string str() const {
    return line > 0 ? source + ":" + std::to_string(line) : source;
  }
};

class ConfigError : public std::runtime_error {
 public:
  ConfigError(const Origin& origin, const std::string& key_path, const std::string& message)
      : std::runtime_error(origin.str() + ": " + (key_path.empty() ? "" : key_path + ": ") +
                           message) {}
};

/// Exit status of a program stopped by bad input (case file, options, meshes).
inline constexpr int exit_status_bad_input = 2;

}  // namespace tankfsi
