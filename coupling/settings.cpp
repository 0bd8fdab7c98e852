#include "coupling/settings.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "common/config/case_config.hpp"
#include "common/io/exact_number.hpp"

namespace tankfsi::coupling {

const char* side_name(Side side) { return side == Side::fluid ? "fluid" : "structure"; }

namespace {

const char* scheme_name(Scheme s) {
  switch (s) {
    case Scheme::parallel_staggered: return "parallel_staggered";
    case Scheme::sequential_staggered: return "sequential_staggered";
    case Scheme::implicit: return "implicit";
  }
  return "?";
}

const char* acceleration_name(AccelerationType a) {
  switch (a) {
    case AccelerationType::constant: return "constant";
    case AccelerationType::aitken: return "aitken";
    case AccelerationType::iqn_ils: return "iqn_ils";
  }
  return "?";
}

}  // namespace

std::map<std::string, std::string> CouplingSettings::as_map() const {
  std::map<std::string, std::string> m{
      {"coupling.scheme", scheme_name(scheme)},
      {"coupling.time_window", exact_text(time_window)},
      {"end_time", exact_text(end_time)},
      {"coupling.structure_load", hold_window_average ? "window_average" : "ramp"},
  };
  // Only when used: a 2.0 partner, which knows no added mass, still couples without it.
  if (added_mass_operator) m["coupling.added_mass"] = "computed";
  if (!hold_window_average) m["coupling.ramp_chi"] = exact_text(ramp_chi);
  if (scheme != Scheme::parallel_staggered) m["coupling.first"] = side_name(first);
  if (is_implicit()) {
    m["coupling.implicit.mode"] = implicit_mode == ImplicitMode::serial ? "serial" : "parallel";
    m["coupling.implicit.max_iterations"] = std::to_string(max_iterations);
    m["coupling.implicit.relative_tolerance"] = exact_text(relative_tolerance);
    m["coupling.implicit.absolute_tolerance"] = exact_text(absolute_tolerance);
    m["coupling.implicit.on_nonconvergence"] = stop_on_nonconvergence ? "stop" : "accept";
    m["coupling.acceleration.type"] = acceleration_name(acceleration);
    m["coupling.acceleration.initial_relaxation"] = exact_text(initial_relaxation);
    m["coupling.acceleration.reused_windows"] = std::to_string(reused_windows);
    m["coupling.acceleration.filter_tolerance"] = exact_text(filter_tolerance);
  }
  return m;
}

void CouplingSettings::check() const {
  const auto fail = [](const std::string& key, const std::string& rule) {
    throw std::invalid_argument(key + ": " + rule);
  };
  if (!(time_window > 0)) fail("coupling.time_window", "must be > 0");
  if (!(end_time > 0)) fail("end_time", "must be > 0");
  if (!(ramp_chi >= 1 && ramp_chi <= 2)) fail("coupling.ramp_chi", "must be in [1, 2]");
  if (max_iterations < 1) fail("coupling.implicit.max_iterations", "must be >= 1");
  if (!(relative_tolerance > 0 && relative_tolerance < 1)) fail("coupling.implicit.relative_tolerance", "must be in (0, 1)");
  if (!(absolute_tolerance >= 0)) fail("coupling.implicit.absolute_tolerance", "must be >= 0");
  if (!(initial_relaxation > 0 && initial_relaxation <= 1))
    fail("coupling.acceleration.initial_relaxation", "must be in (0, 1]");
  if (reused_windows < 0) fail("coupling.acceleration.reused_windows", "must be >= 0");
  if (!(filter_tolerance > 0 && filter_tolerance < 1)) fail("coupling.acceleration.filter_tolerance", "must be in (0, 1)");
  if (!(timeout > 0)) fail("coupling.timeout", "must be > 0");
}

CouplingSettings read_coupling_settings(const CaseConfig& config) {
  config.require_section("coupling", "a coupled run");
  CouplingSettings s;
  const std::string scheme = config.text("coupling.scheme");
  s.scheme = scheme == "implicit"               ? Scheme::implicit
             : scheme == "sequential_staggered" ? Scheme::sequential_staggered
                                                : Scheme::parallel_staggered;
  s.time_window = config.real("coupling.time_window");
  s.end_time = config.real("end_time");
  s.hold_window_average = config.text("coupling.structure_load") == "window_average";
  s.added_mass_operator = config.text("coupling.added_mass") == "computed";
  if (!s.hold_window_average) s.ramp_chi = config.real("coupling.ramp_chi");
  s.timeout = config.real("coupling.timeout");
  if (config.has("coupling.first")) s.first = config.text("coupling.first") == "structure" ? Side::structure : Side::fluid;
  if (s.is_implicit()) {
    s.implicit_mode = config.text("coupling.implicit.mode") == "parallel" ? ImplicitMode::parallel : ImplicitMode::serial;
    s.max_iterations = static_cast<int>(config.integer("coupling.implicit.max_iterations"));
    s.relative_tolerance = config.real("coupling.implicit.relative_tolerance");
    s.absolute_tolerance = config.real("coupling.implicit.absolute_tolerance");
    s.stop_on_nonconvergence = config.text("coupling.implicit.on_nonconvergence") == "stop";
    const std::string a = config.text("coupling.acceleration.type");
    s.acceleration = a == "constant" ? AccelerationType::constant
                     : a == "iqn_ils" ? AccelerationType::iqn_ils
                                      : AccelerationType::aitken;
    s.initial_relaxation = config.real("coupling.acceleration.initial_relaxation");
    s.reused_windows = static_cast<int>(config.integer("coupling.acceleration.reused_windows"));
    s.filter_tolerance = config.real("coupling.acceleration.filter_tolerance");
  }
  return s;
}

void require_step_within_window(const CaseConfig& config, const std::string& step_key, const CouplingSettings& settings) {
  const double step = config.real(step_key);
  if (step > settings.time_window)
    throw config.error_at(step_key, "the time step " + exact_text(step) + " s is longer than coupling.time_window " +
                                        exact_text(settings.time_window) + " s");
}

std::string fnv1a_hex(const std::string& bytes) {
  std::uint64_t hash = 14695981039346656037ull;
  for (unsigned char c : bytes) {
    hash ^= c;
    hash *= 1099511628211ull;
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

std::map<std::string, std::string> case_fingerprints(const CaseConfig& config) {
  const YAML::Node resolved = YAML::Load(config.resolved_yaml());
  std::map<std::string, std::string> prints;
  for (const auto& entry : resolved) {
    const std::string section = entry.first.as<std::string>();
    if (section == "output" || section == "title") continue;
    YAML::Emitter out;
    out << entry.second;
    prints[section] = fnv1a_hex(out.c_str());
  }
  return prints;
}

}  // namespace tankfsi::coupling
