#include "common/excitation/csv_motion.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/config/config_error.hpp"
#include "common/io/number_text.hpp"
#include "common/io/text_fields.hpp"

namespace tankfsi {

namespace {

constexpr std::array<const char*, 4> columns{"time_s", "ax", "ay", "az"};
constexpr const char* header_text = "time_s,ax,ay,az";

std::vector<std::string_view> fields_of(std::string_view line) {
  std::vector<std::string_view> fields;
  for (std::size_t start = 0;;) {
    const auto comma = line.find(',', start);
    fields.push_back(trimmed(line.substr(start, comma == std::string_view::npos ? comma : comma - start)));
    if (comma == std::string_view::npos) return fields;
    start = comma + 1;
  }
}

std::optional<double> finite_number(std::string_view text) {
  if (text.starts_with('+')) text.remove_prefix(1);
  double value = 0.0;
  const auto* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

void append_number(std::string& out, double value) {
  char buffer[32];
  const auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, ptr);
}

}  // namespace

SampledGroundMotion read_motion_csv(const std::filesystem::path& file) {
  auto fail = [&](int line, const std::string& message) {
    return ConfigError(Origin{file.string(), line}, "", message);
  };
  std::ifstream in(file);
  if (!in) throw fail(0, std::string("cannot read ground-motion CSV: ") + std::strerror(errno));

  std::string text;
  if (!std::getline(in, text) || trimmed(text) != header_text)
    throw fail(1, "expected the header " + std::string(header_text) + ", got '" + std::string(trimmed(text)) + "'");

  std::vector<double> times;
  std::vector<Eigen::Vector3d> accelerations;
  for (int line = 2; std::getline(in, text); ++line) {
    if (trimmed(text).empty()) continue;
    const auto fields = fields_of(text);
    if (fields.size() != columns.size())
      throw fail(line, "expected 4 columns (" + std::string(header_text) + "), got " +
                           std::to_string(fields.size()));
    std::array<double, 4> values{};
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const auto value = finite_number(fields[c]);
      if (!value)
        throw fail(line, std::string("column ") + columns[c] + ": '" + std::string(fields[c]) +
                             "' is not a finite number");
      values[c] = *value;
    }
    if (!times.empty() && values[0] <= times.back())
      throw fail(line, "time " + std::string(fields[0]) + " s is not after the previous sample's time");
    // Records are sampled uniformly (the response spectra of the outputs assume
    // it); a longer interval is a gap, a shorter one a wrong time. 0.1 % allows
    // for times written with few digits.
    if (times.size() >= 2) {
      const double first = times[1] - times[0];
      const double interval = values[0] - times.back();
      if (std::abs(interval - first) > 1e-3 * first)
        throw fail(line, "irregular sampling: " + number_text(interval) + " s since the previous sample, " +
                             number_text(first) + " s between the first two (a gap or a wrong time): a "
                             "ground-motion record must be sampled uniformly");
    }
    times.push_back(values[0]);
    accelerations.emplace_back(values[1], values[2], values[3]);
  }
  if (times.empty()) throw fail(1, "no samples after the header");
  return SampledGroundMotion(std::move(times), std::move(accelerations));
}

void write_motion_csv(const std::filesystem::path& file, const SampledGroundMotion& motion) {
  std::string text = std::string(header_text) + "\n";
  const auto& times = motion.times();
  const auto& accelerations = motion.accelerations();
  for (std::size_t i = 0; i < times.size(); ++i) {
    append_number(text, times[i]);
    for (int c = 0; c < 3; ++c) {
      text += ',';
      append_number(text, accelerations[i][c]);
    }
    text += '\n';
  }
  std::ofstream out(file, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw std::runtime_error("cannot write ground-motion CSV " + file.string());
}

}  // namespace tankfsi
