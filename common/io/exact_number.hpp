#pragma once
// Numbers as text that read back to the same double: every file tankfsi
// writes (resolved case, probe CSV, ground motions) uses this one formatter.
#include <charconv>
#include <optional>
#include <string>

namespace tankfsi {

/// Shortest text that parses back to exactly `value` (std::to_chars round trip).
inline std::string exact_text(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

/// Parses the whole of `text` as a number (an optional leading '+' allowed).
inline std::optional<double> parse_number(std::string_view text) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end) return std::nullopt;
  return value;
}

}  // namespace tankfsi
