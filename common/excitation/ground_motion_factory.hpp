#pragma once
// The ground motion a case file asks for (section excitation; keys declared in
// common/config/case_schema_excitation.cpp).
#include <memory>

#include "common/config/case_config.hpp"
#include "common/excitation/ground_motion.hpp"

namespace tankfsi {

/// excitation.type none: zero everywhere; knet, csv, synthetic: a sampled record,
/// windowed and scaled so that a record sample at record time t_r appears at
/// simulation time (t_r - window_start) * time_scale + start_time; harmonic and
/// sweep: tapered sines starting at start_time.
/// Throws ConfigError for unreadable or malformed records (naming their file and
/// line) and for inconsistent settings (naming the case key).
[[nodiscard]] std::unique_ptr<GroundMotion> make_ground_motion(const CaseConfig& config);

}  // namespace tankfsi
