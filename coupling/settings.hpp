#pragma once
// CouplingSettings: what both partners must agree on before the first window
// (METHOD.md §4). Read from the case file's coupling section; compared key by
// key at the handshake, so a mismatch names the key and both values.
#include <map>
#include <string>

namespace tankfsi {
class CaseConfig;
}

namespace tankfsi::coupling {

/// The two sides of the interface. The structure side owns the interface mesh
/// and writes displacements; the fluid side writes forces.
enum class Side { fluid, structure };
enum class Scheme { parallel_staggered, sequential_staggered, implicit };
enum class ImplicitMode { serial, parallel };
enum class AccelerationType { constant, aitken, iqn_ils };

[[nodiscard]] const char* side_name(Side side);
[[nodiscard]] inline Side other(Side side) { return side == Side::fluid ? Side::structure : Side::fluid; }

struct CouplingSettings {
  Scheme scheme = Scheme::parallel_staggered;
  double time_window = 0.01;  ///< dt_c (s)
  double end_time = 1.0;      ///< simulated time of the run (s)
  double ramp_chi = 1.0;      ///< chi of eq 17, in [1, 2]
  /// True: the structure holds the fluid's window average F̄ over the window
  /// instead of the ramp of eq 17 (coupling.structure_load: window_average).
  bool hold_window_average = false;
  /// True: added-mass partitioning (coupling.added_mass: computed;
  /// coupling/added_mass/added_mass.hpp, PROTOCOL.md "Added mass").
  bool added_mass_operator = false;
  Side first = Side::fluid;   ///< sequential staggered and serial implicit
  ImplicitMode implicit_mode = ImplicitMode::serial;
  int max_iterations = 30;
  double relative_tolerance = 1e-4;
  double absolute_tolerance = 0.0;
  bool stop_on_nonconvergence = true;
  AccelerationType acceleration = AccelerationType::aitken;
  double initial_relaxation = 0.5;
  int reused_windows = 8;
  double filter_tolerance = 0.01;
  double timeout = 600.0;  ///< longest wait for the partner (s)

  [[nodiscard]] bool is_implicit() const { return scheme == Scheme::implicit; }
  /// Every setting as "key: value" with the case file's key names; the
  /// handshake compares these maps.
  [[nodiscard]] std::map<std::string, std::string> as_map() const;
  /// Throws std::invalid_argument naming the key if a value is out of range.
  void check() const;
};

/// The settings of a case (coupling section and end_time). The case must have
/// a coupling section (ConfigError naming the file otherwise).
CouplingSettings read_coupling_settings(const CaseConfig& config);

/// A program's own time step (case key `step_key`) must fit in the window:
/// throws ConfigError naming the key's line otherwise.
void require_step_within_window(const CaseConfig& config, const std::string& step_key, const CouplingSettings& settings);

/// Fingerprint of each section of a case that both partners read (all but
/// output and title): "section" -> 64-bit FNV-1a of its resolved YAML, as hex.
/// Partners that read different cases differ in at least one entry.
std::map<std::string, std::string> case_fingerprints(const CaseConfig& config);

/// 64-bit FNV-1a of a byte string, as 16 hex digits.
std::string fnv1a_hex(const std::string& bytes);

}  // namespace tankfsi::coupling
